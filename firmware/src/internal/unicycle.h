/*
 * Internal: unicycle's functions (the types are in tvo/unicycle.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_UNICYCLE_H
#define TVO_INTERNAL_UNICYCLE_H

#include "tvo/unicycle.h"
#include "internal/assert.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * Flat map: accel_mps2 = y''.e_theta, turn_rate_radps = (e_theta x y'')/v_reg. min_speed_mps > 0.
 * *low_speed is set to 1 when |speed| < min_speed_mps (the regularisation was active), else 0.
 */
tvo_status_t tvo_unicycle_flat_map(tvo_real_t heading_rad, tvo_real_t speed_mps,
                                   const tvo_real_t output_accel_mps2[2], tvo_real_t min_speed_mps,
                                   tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps, uint8_t *low_speed);

/** The flat map with the heading given as (cos, sin): the step's way, with no trigonometry. */
tvo_status_t tvo_unicycle_flat_map_cs(const tvo_real_t heading_cs[2], tvo_real_t speed_mps,
                                      const tvo_real_t output_accel_mps2[2], tvo_real_t min_speed_mps,
                                      tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps, uint8_t *low_speed);

/**
 * Exact pose after dt_s under a held (speed, turn rate): a circular arc, or a straight line when
 * the turn is negligible (series form avoids 0/0). dt_s >= 0. out may alias start.
 */
tvo_status_t tvo_unicycle_predict(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps,
                                  tvo_real_t dt_s, tvo_pose_t *out);

/** tvo_unicycle_predict, and heading_cs = (cos, sin) of the new heading from the same sines. */
tvo_status_t tvo_unicycle_predict_cs(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps,
                                     tvo_real_t dt_s, tvo_pose_t *out, tvo_real_t heading_cs[2]);

/** Wraps an angle to (-pi, pi]. */
tvo_real_t tvo_wrap_angle(tvo_real_t angle_rad);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_UNICYCLE_H */
