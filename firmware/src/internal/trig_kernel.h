/*
 * Internal: the float32 sine and cosine kernels, inline, so that a caller's shape copy (src/shape.h)
 * carries them in its own body (no call, the pair never through memory); tvo_sincos and
 * tvo_sincos_turns (trig.c) are these behind their argument checks.
 */
#ifndef TVO_TRIG_KERNEL_H
#define TVO_TRIG_KERNEL_H

#include "shape.h"
#include "internal/trig.h"

#define TRIG_PI_OVER_TWO TVO_R(1.57079632679489661923)
/* pi/2 = P1 + P2 + P3, P1 and P2 with few enough bits that q * P1, q * P2 are exact for q < 2^13. */
#define TRIG_PIO2_1 TVO_R(1.5703125)
#define TRIG_PIO2_2 TVO_R(4.837512969970703125e-4)
#define TRIG_PIO2_3 TVO_R(7.54978995489188216e-8)

#if !TVO_USE_DOUBLE
/* The largest float the reduction below maps to quarter 0 (pi/4 itself rounds to quarter 1 there):
 * below it the reduction is the identity, so skipping it changes no result. */
#define TRIG_NO_REDUCTION_LIMIT 0x1.921fb2p-1f

/* sin and cos on [-pi/4, pi/4]: the minimax polynomials of Cephes' sinf/cosf. */
static inline void sincos_kernel(float x, float *s, float *c)
{
    const float z = x * x;
    *s = x + x * z * (-1.6666654611e-1f + z * (8.3321608736e-3f + z * -1.9515295891e-4f));
    *c = 1.0f - 0.5f * z + z * z * (4.166664568298827e-2f + z * (-1.388731625493765e-3f + z * 2.443315711809948e-5f));
}

/* Rotates (sin, cos) of the reduced angle by quadrant q (q pi/2 added). */
static inline void by_quadrant(uint32_t q, float s, float c, float *sin_out, float *cos_out)
{
    switch (q & 3u) {
    case 0u:
        *sin_out = s;
        *cos_out = c;
        break;
    case 1u:
        *sin_out = c;
        *cos_out = -s;
        break;
    case 2u:
        *sin_out = -s;
        *cos_out = -c;
        break;
    default:
        *sin_out = -c;
        *cos_out = s;
        break;
    }
}

/* sin and cos of |angle| <= TVO_SINCOS_FAST_LIMIT_RAD (Cody-Waite to the nearest quarter turn);
 * in both callers' bodies when the build compiles for speed. */
TVO_SHAPE_BODY void sincos_fast_range(float angle_rad, float *sin_out, float *cos_out)
{
    if (TVO_FABS(angle_rad) <= TRIG_NO_REDUCTION_LIMIT) {
        sincos_kernel(angle_rad, sin_out, cos_out); /* small angles (a turn over one period): no reduction */
        return;
    }
    /* Nearest quarter turn by conversion to integer (one instruction; floorf is a library call). */
    const float scaled = angle_rad * TVO_TWO_OVER_PI;
    const int32_t quarter = (int32_t)(scaled + (scaled >= 0.0f ? 0.5f : -0.5f));
    const float q = (float)quarter;
    const float x = ((angle_rad - q * TRIG_PIO2_1) - q * TRIG_PIO2_2) - q * TRIG_PIO2_3;
    float s;
    float c;
    sincos_kernel(x, &s, &c);
    by_quadrant((uint32_t)quarter, s, c, sin_out, cos_out);
}

/* tvo_sincos_turns for |extra_rad| <= TVO_SINCOS_FAST_LIMIT_RAD (its caller checked). */
TVO_SHAPE_BODY void sincos_turns_body(uint64_t turns_q64, float extra_rad, float *sin_out, float *cos_out)
{
    /* The nearest quarter turn from the top bits, exactly; the rest is a small signed angle. */
    const uint32_t turns_q32 = (uint32_t)(turns_q64 >> 32);
    const uint32_t centred = turns_q32 + 0x20000000u;
    const uint32_t q = centred >> 30;
    const int32_t rest_q32 = (int32_t)(turns_q32 - (q << 30));
    const float rest = (float)rest_q32 * (TRIG_PI_OVER_TWO / 1073741824.0f) + extra_rad;
    float s;
    float c;
    if (TVO_FABS(rest) > 0.7853982f) {
        /* The extra angle left the octant: reduce it too (|rest| <= the limit + pi/4 keeps q < 2^13). */
        sincos_fast_range(rest, &s, &c);
    } else {
        sincos_kernel(rest, &s, &c);
    }
    by_quadrant(q, s, c, sin_out, cos_out);
}
#endif /* !TVO_USE_DOUBLE */

#endif /* TVO_TRIG_KERNEL_H */
