/* Unicycle flat map and exact held-command motion; see internal/unicycle.h. */
#include "internal/unicycle.h"

/* 2 pi = HI + LO with HI = 6.28125 (8 significant bits: n * HI is exact for |n| < 2^16). */
#define UNICYCLE_TWO_PI_HI TVO_R(6.28125)
#define UNICYCLE_TWO_PI_LO TVO_R(0.0019353071795864769253)

tvo_real_t tvo_wrap_angle(tvo_real_t angle_rad)
{
    if (!isfinite(angle_rad)) {
        return angle_rad;
    }
    if (unicycle_angle_in_range(angle_rad)) {
        return angle_rad; /* the common case: headings move by at most omega_max h per step */
    }
    /* Subtract the nearest multiple of 2 pi in constant time, 2 pi split in two parts (Cody-Waite)
     * so that n * 2pi_hi is exact and the reduction keeps the angle's own precision. */
    const tvo_real_t turns = TVO_FLOOR(angle_rad * TVO_INV_TWO_PI + TVO_R(0.5));
    tvo_real_t wrapped = (angle_rad - turns * UNICYCLE_TWO_PI_HI) - turns * UNICYCLE_TWO_PI_LO;
    if (wrapped <= -TVO_PI) {
        wrapped += TVO_R(2.0) * TVO_PI; /* rounding at the boundary: keep (-pi, pi] */
    }
    return wrapped;
}

void tvo_unicycle_flat_map(tvo_real_t heading_rad, tvo_real_t speed_mps, const tvo_real_t output_accel_mps2[2],
                           tvo_real_t min_speed_mps, tvo_real_t *accel_mps2, tvo_real_t *turn_rate_radps,
                           uint8_t *low_speed)
{
    tvo_real_t cs[2];
    tvo_sincos(heading_rad, &cs[1], &cs[0]);
    *low_speed = 0u;
    tvo_unicycle_flat_map_cs(cs, speed_mps, output_accel_mps2, min_speed_mps, accel_mps2, turn_rate_radps, low_speed);
}

void tvo_unicycle_predict(const tvo_pose_t *start, tvo_real_t speed_mps, tvo_real_t turn_rate_radps, tvo_real_t dt_s,
                          tvo_pose_t *out)
{
    tvo_real_t heading_cs[2];
    tvo_unicycle_predict_cs(start, speed_mps, turn_rate_radps, dt_s, out, heading_cs);
}
