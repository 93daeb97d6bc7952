/*
 * Internal: unicycle's functions (the types are in tvo/unicycle.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_UNICYCLE_H
#define TVO_INTERNAL_UNICYCLE_H

#include "tvo/unicycle.h"
#include "internal/assert.h"
#include "internal/trig.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Wraps an angle to (-pi, pi] (non-finite angles are returned as they are). */
tvo_real_t tvo_wrap_angle(tvo_real_t angle_rad);

/* Whether an angle is in tvo_wrap_angle's range (-pi, pi] already (false for NaN and infinities). */
static inline int unicycle_angle_in_range(tvo_real_t angle_rad)
{
    return angle_rad <= TVO_PI && angle_rad > -TVO_PI;
}

/* tvo_wrap_angle for an angle that is usually in range already (a heading moved by one period). */
static inline tvo_real_t unicycle_wrap_angle_near(tvo_real_t angle_rad)
{
    return unicycle_angle_in_range(angle_rad) ? angle_rad : tvo_wrap_angle(angle_rad);
}

/**
 * The flat map (paper, "Unicycle"): y'' -> (v', omega) at the heading's (cos, sin) heading_cs and
 * speed v: v' = e_theta . y'', omega = (e_theta x y'') / v, |v| floored at min_speed_mps > 0 (keeping
 * v's sign, zero counts as positive) for the division; *low_speed is set to 1 (only ever set) when
 * the floor acts.
 */
static inline void tvo_unicycle_flat_map_cs(const tvo_real_t heading_cs[2], tvo_real_t speed_mps,
                                            const tvo_real_t output_accel_mps2[2], tvo_real_t min_speed_mps,
                                            tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps, uint8_t *low_speed)
{
    TVO_ASSERT(min_speed_mps > TVO_R(0.0));
    const tvo_real_t c = heading_cs[0];
    const tvo_real_t s = heading_cs[1];
    /* Along-track part drives the speed state; cross-track part, divided by v, turns. */
    const tvo_real_t along = output_accel_mps2[0] * c + output_accel_mps2[1] * s;
    const tvo_real_t across = c * output_accel_mps2[1] - s * output_accel_mps2[0];
    tvo_real_t v = speed_mps;
    if (TVO_FABS(v) < min_speed_mps) {
        v = (v < TVO_R(0.0)) ? -min_speed_mps : min_speed_mps;
        *low_speed = 1;
    }
    *accel_mps2 = along;
    *turn_rate_radps = across / v;
}

/**
 * The pose after dt_s >= 0 of constant (v, omega) (exact arc; straight line for omega = 0); out may
 * alias start. heading_cs receives the new heading's (cos, sin).
 */
static inline void tvo_unicycle_predict_cs(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps,
                                           tvo_real_t dt_s, tvo_pose_t *out, tvo_real_t heading_cs[2])
{
    TVO_ASSERT(!(dt_s < TVO_R(0.0)));
    const tvo_real_t th = start->heading_rad;
    const tvo_real_t dth = turn_rate_radps * dt_s;
    /* Two (sin, cos) pairs serve the arc and the new heading: th, and half the turn
     * (sin dth = 2 sh ch, 1 - cos dth = 2 sh^2: no cancellation for small turns in float32). */
    tvo_real_t s;
    tvo_real_t c;
    tvo_real_t sh;
    tvo_real_t ch;
    tvo_sincos(th, &s, &c);
    tvo_sincos(TVO_R(0.5) * dth, &sh, &ch);
    const tvo_real_t sin_turn = TVO_R(2.0) * sh * ch;
    const tvo_real_t one_minus_cos_turn = TVO_R(2.0) * sh * sh;
    /* Displacement = v dt [sinc(dth), (1 - cos dth)/dth] rotated by th; both factors by their
     * series when dth is small, where the closed forms would cancel catastrophically. */
    tvo_real_t sinc;
    tvo_real_t cosc;
    if (TVO_FABS(dth) < TVO_R(1e-3)) {
        const tvo_real_t d2 = dth * dth;
        sinc = TVO_R(1.0) - d2 / TVO_R(6.0);
        cosc = dth * (TVO_R(0.5) - d2 / TVO_R(24.0));
    } else {
        sinc = sin_turn / dth;
        cosc = one_minus_cos_turn / dth;
    }
    const tvo_real_t dist = speed_mps * dt_s;
    const tvo_real_t fwd = dist * sinc;
    const tvo_real_t left = dist * cosc;
    out->position_m[0] = start->position_m[0] + c * fwd - s * left;
    out->position_m[1] = start->position_m[1] + s * fwd + c * left;
    out->heading_rad = unicycle_wrap_angle_near(th + dth);
    /* The new heading's cosine and sine by the angle-sum formulas (no further trigonometry). */
    heading_cs[0] = c - (c * one_minus_cos_turn + s * sin_turn);
    heading_cs[1] = s + (c * sin_turn - s * one_minus_cos_turn);
}

/** tvo_unicycle_flat_map_cs at a heading given as an angle. */
void tvo_unicycle_flat_map(tvo_real_t heading_rad, tvo_real_t speed_mps, const tvo_real_t output_accel_mps2[2],
                           tvo_real_t min_speed_mps, tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps,
                           uint8_t *low_speed);

/** tvo_unicycle_predict_cs without the new heading's (cos, sin) (a plant model's step). */
void tvo_unicycle_predict(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps, tvo_real_t dt_s,
                          tvo_pose_t *out);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_UNICYCLE_H */
