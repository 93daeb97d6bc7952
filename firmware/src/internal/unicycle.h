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

/** Wraps an angle to (-pi, pi] (non-finite angles are returned as they are). A function of its argument
 *  alone: a caller that drops the result drops the call. */
#if defined(__GNUC__)
__attribute__((const))
#endif
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

/* The turn below which the arc's factors come from their series: up to the d^4 terms they are exact to
 * the scalar's precision (the next, d^6 / 5040, below half an ulp) for |d| <= 1/8 in float32, 1/256 in
 * double. A period's turn at the default limits (2 pi rad/s over 15 ms) is 0.09 rad. */
#if TVO_USE_DOUBLE
#define UNICYCLE_SERIES_TURN_RAD 0.00390625
#else
#define UNICYCLE_SERIES_TURN_RAD 0.125f
#endif

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
    tvo_real_t s;
    tvo_real_t c;
    tvo_sincos(th, &s, &c);
    /* Displacement = v dt [sinc(dth), (1 - cos dth)/dth] rotated by th, and the turn's sin dth and
     * 1 - cos dth for the new heading. */
    tvo_real_t sinc;
    tvo_real_t cosc;
    tvo_real_t sin_turn;
    tvo_real_t one_minus_cos_turn;
    if (TVO_FABS(dth) <= UNICYCLE_SERIES_TURN_RAD) {
        /* A turn over a period or two: both factors by their series, exact to this precision there (the
         * next terms are below half an ulp), with no trigonometry, no division and no cancellation. */
        const tvo_real_t d2 = dth * dth;
        sinc = TVO_R(1.0) - d2 * (TVO_R(0.16666666666666667) - d2 * TVO_R(0.0083333333333333333));
        cosc = dth * (TVO_R(0.5) - d2 * (TVO_R(0.041666666666666667) - d2 * TVO_R(0.0013888888888888889)));
        sin_turn = dth * sinc;
        one_minus_cos_turn = dth * cosc;
    } else {
        /* (sin, cos) of half the turn: sin dth = 2 sh ch, 1 - cos dth = 2 sh^2 (no cancellation). */
        tvo_real_t sh;
        tvo_real_t ch;
        tvo_sincos(TVO_R(0.5) * dth, &sh, &ch);
        sin_turn = TVO_R(2.0) * sh * ch;
        one_minus_cos_turn = TVO_R(2.0) * sh * sh;
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
