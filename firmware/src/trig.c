/* Sine and cosine together; see tvo/trig.h. */
#include "internal/trig_kernel.h"
#include "internal/wide_mul.h"

#include <string.h>

#if !TVO_USE_DOUBLE
/* 2/pi = sum_i b_i 2^-i: its bits b_1 .. b_256, b_1 the top bit of the first word. */
static const uint32_t two_over_pi_bits[8] = {0xA2F9836Eu, 0x4E441529u, 0xFC2757D1u, 0xF534DDC0u,
                                             0xDB629599u, 0x3C439041u, 0xFE5163ABu, 0xDEBBC561u};
/* pi/2 in Q62, rounded. */
#define TRIG_PIO2_Q62 UINT64_C(0x6487ED5110B4611A)

/* Bits b_first .. b_first+31 of 2/pi (first >= 1, first + 31 <= 256). */
static uint32_t two_over_pi_word(unsigned first)
{
    const unsigned index = (first - 1u) / 32u;
    const unsigned offset = (first - 1u) % 32u;
    if (offset == 0u) {
        return two_over_pi_bits[index];
    }
    return (two_over_pi_bits[index] << offset) | (two_over_pi_bits[index + 1u] >> (32u - offset));
}

/*
 * sin and cos of a finite |angle| >= TVO_SINCOS_FAST_LIMIT_RAD by exact reduction (Payne-Hanek):
 * angle 2/pi modulo 4 in integer arithmetic, from the 96 bits of 2/pi that matter at the angle's
 * exponent. No libm: its reduction of a huge argument takes over 400 bytes of stack on Cortex-M.
 * Kept out of line, so the common path's frame does not carry its registers.
 */
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void sincos_huge(float angle_rad, float *sin_out, float *cos_out)
{
    uint32_t bits;
    memcpy(&bits, &angle_rad, sizeof(bits));
    const uint64_t mantissa = (bits & 0x7FFFFFu) | 0x800000u;
    const int exponent = (int)((bits >> 23) & 0xFFu) - 150; /* |angle| = mantissa 2^exponent */
    /* The bits b_i with exponent - i >= 2 add whole multiples of 4 quarter turns: skipped. */
    const unsigned first = exponent >= 2 ? (unsigned)(exponent - 1) : 1u;
    const unsigned fraction_bits = (unsigned)((int)first + 95 - exponent); /* 94 .. 106 */
    /* mantissa times the 96 bits b_first .. b_first+95: a 120-bit product, high:low. */
    const uint64_t part_low = mantissa * two_over_pi_word(first + 64u);
    const uint64_t part_mid = mantissa * two_over_pi_word(first + 32u) + (part_low >> 32);
    const uint64_t high = mantissa * two_over_pi_word(first) + (part_mid >> 32);
    const uint64_t low = (part_mid << 32) | (part_low & 0xFFFFFFFFu);
    /* Quarter turns: two bits above the binary point; the 64 bits below it, the fraction. */
    const unsigned shift = fraction_bits - 64u; /* 30 .. 42 */
    const uint64_t fraction = (low >> shift) | (high << (64u - shift));
    /* To the nearest quarter: a fraction of 1/2 or more counts as the next quarter less the rest. */
    const uint32_t up = (uint32_t)(fraction >> 63);
    const uint32_t quarter = (uint32_t)(high >> shift) + up;
    const uint64_t rest_magnitude = up ? (~fraction + 1u) : fraction; /* |rest| 2^64, at most 2^63 */
    /* angle mod pi/2 = rest pi/2: (|rest| 2^64)(pi/2 2^62) 2^-126, its high 64 bits scaled by 2^-62. */
    float reduced = (float)wide_mul_high_u64(rest_magnitude, TRIG_PIO2_Q62) * 0x1p-62f;
    if (up) {
        reduced = -reduced;
    }
    float s;
    float c;
    sincos_kernel(reduced, &s, &c);
    by_quadrant(quarter, s, c, sin_out, cos_out);
    if (angle_rad < 0.0f) {
        *sin_out = -*sin_out; /* sin is odd, cos even */
    }
}
#endif

void tvo_sincos(tvo_real_t angle_rad, tvo_real_t *sin_out, tvo_real_t *cos_out)
{
#if TVO_USE_DOUBLE
    *sin_out = sin(angle_rad);
    *cos_out = cos(angle_rad);
#else
    if (!(TVO_FABS(angle_rad) <= TVO_SINCOS_FAST_LIMIT_RAD)) {
        if (!isfinite(angle_rad)) {
            *sin_out = angle_rad - angle_rad; /* NaN for NaN and for the infinities, as libm */
            *cos_out = *sin_out;
            return;
        }
        sincos_huge(angle_rad, sin_out, cos_out);
        return;
    }
    sincos_fast_range(angle_rad, sin_out, cos_out);
#endif
}

void tvo_sincos_turns(uint64_t turns_q64, tvo_real_t extra_rad, tvo_real_t *sin_out, tvo_real_t *cos_out)
{
    if (!(TVO_FABS(extra_rad) <= TVO_SINCOS_FAST_LIMIT_RAD)) {
        /* Out of contract (and NaN): no huge-angle reduction on the targets' path, whose stack it would deepen. */
        *sin_out = (tvo_real_t)NAN;
        *cos_out = *sin_out;
        return;
    }
#if TVO_USE_DOUBLE
    /* Signed turns in [-1/2, 1/2): the angle stays small, and double keeps 53 of the 64 bits. */
    const double angle = (double)(int64_t)turns_q64 * (6.283185307179586476925 / 18446744073709551616.0) + extra_rad;
    *sin_out = sin(angle);
    *cos_out = cos(angle);
#else
    sincos_turns_body(turns_q64, extra_rad, sin_out, cos_out);
#endif
}
