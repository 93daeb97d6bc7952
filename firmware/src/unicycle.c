/* Unicycle flat map and exact held-command motion; see tvo/unicycle.h. */
#include "tvo/unicycle.h"

#include "tvo/trig.h"

#define UNICYCLE_PI TVO_R(3.14159265358979323846)
#define UNICYCLE_INV_TWO_PI TVO_R(0.15915494309189533577)
/* 2 pi = HI + LO with HI = 6.28125 (8 significant bits: n * HI is exact for |n| < 2^16). */
#define UNICYCLE_TWO_PI_HI TVO_R(6.28125)
#define UNICYCLE_TWO_PI_LO TVO_R(0.0019353071795864769253)

#define TVO_PI TVO_R(3.14159265358979323846)

tvo_real_t tvo_wrap_angle(tvo_real_t angle_rad)
{
    if (!isfinite(angle_rad)) {
        return angle_rad;
    }
    /* In range: unchanged (the common case: headings move by at most omega_max h per step). */
    if (angle_rad <= UNICYCLE_PI && angle_rad > -UNICYCLE_PI) {
        return angle_rad;
    }
    /* Subtract the nearest multiple of 2 pi in constant time, 2 pi split in two parts (Cody-Waite)
     * so that n * 2pi_hi is exact and the reduction keeps the angle's own precision. */
    const tvo_real_t turns = TVO_FLOOR(angle_rad * UNICYCLE_INV_TWO_PI + TVO_R(0.5));
    tvo_real_t wrapped = (angle_rad - turns * UNICYCLE_TWO_PI_HI) - turns * UNICYCLE_TWO_PI_LO;
    if (wrapped <= -UNICYCLE_PI) {
        wrapped += TVO_R(2.0) * UNICYCLE_PI; /* rounding at the boundary: keep (-pi, pi] */
    }
    return wrapped;
}

tvo_status_t tvo_unicycle_flat_map_cs(const tvo_real_t heading_cs[2], tvo_real_t speed_mps,
                                      const tvo_real_t output_accel_mps2[2], tvo_real_t min_speed_mps,
                                      tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps, uint8_t *low_speed)
{
    if (heading_cs == NULL || output_accel_mps2 == NULL || accel_mps2 == NULL || turn_rate_radps == NULL ||
        low_speed == NULL) {
        return TVO_ERR_NULL;
    }
    *accel_mps2 = TVO_R(0.0);
    *turn_rate_radps = TVO_R(0.0);
    *low_speed = 0;
    if (!isfinite(heading_cs[0]) || !isfinite(heading_cs[1]) || !isfinite(speed_mps) ||
        !isfinite(output_accel_mps2[0]) || !isfinite(output_accel_mps2[1]) || !isfinite(min_speed_mps)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (!(min_speed_mps > TVO_R(0.0))) {
        return TVO_ERR_PARAM;
    }
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
    return TVO_OK;
}

tvo_status_t tvo_unicycle_flat_map(tvo_real_t heading_rad, tvo_real_t speed_mps,
                                   const tvo_real_t output_accel_mps2[2], tvo_real_t min_speed_mps,
                                   tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps, uint8_t *low_speed)
{
    tvo_real_t cs[2];
    tvo_sincos(heading_rad, &cs[1], &cs[0]);
    return tvo_unicycle_flat_map_cs(cs, speed_mps, output_accel_mps2, min_speed_mps, accel_mps2, turn_rate_radps,
                                    low_speed);
}

tvo_status_t tvo_unicycle_predict_cs(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps,
                                     tvo_real_t dt_s, tvo_pose_t *out, tvo_real_t heading_cs[2])
{
    if (start == NULL || out == NULL || heading_cs == NULL) {
        return TVO_ERR_NULL;
    }
    if (!isfinite(start->position_m[0]) || !isfinite(start->position_m[1]) || !isfinite(start->heading_rad) ||
        !isfinite(speed_mps) || !isfinite(turn_rate_radps) || !isfinite(dt_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (dt_s < TVO_R(0.0)) {
        return TVO_ERR_PARAM;
    }
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
    out->heading_rad = tvo_wrap_angle(th + dth);
    /* The new heading's cosine and sine by the angle-sum formulas (no further trigonometry). */
    heading_cs[0] = c - (c * one_minus_cos_turn + s * sin_turn);
    heading_cs[1] = s + (c * sin_turn - s * one_minus_cos_turn);
    return TVO_OK;
}

tvo_status_t tvo_unicycle_predict(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps,
                                  tvo_real_t dt_s, tvo_pose_t *out)
{
    tvo_real_t heading_cs[2];
    return tvo_unicycle_predict_cs(start, speed_mps, turn_rate_radps, dt_s, out, heading_cs);
}
