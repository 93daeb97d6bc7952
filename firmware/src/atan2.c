/* atan2 in float32 from IEEE float operations alone; see internal/trig.h. In a file of its own, so a
 * firmware without it (no position-only velocity) links none of its constants. */
#include "internal/trig.h"
#include "internal/real_bits.h"

#include <math.h>
#include <string.h>

/* q pi/4 = hi + lo, q = 0 .. 4, the sum to about 2^-48. */
static const float quarter_pi_hi[5] = {0.0f, 0x1.921fb6p-1f, 0x1.921fb6p+0f, 0x1.2d97c8p+1f, 0x1.921fb6p+1f};
static const float quarter_pi_lo[5] = {0.0f, -0x1.777a5cp-26f, -0x1.777a5cp-25f, -0x1.99bc5cp-28f, -0x1.777a5cp-24f};
#define ATAN_TAN_PI_8 0x1.a8279ap-2f

/* atan(small / large) = q pi/4 + x + *x_p for 0 <= small <= large, large > 0 finite: q = 1 and
 * x = (small - large)/(small + large) above tan(pi/8) (one rounding less than forming the quotient
 * first), else q = 0 and x the quotient; atan(x) = x + x z P(z), z = x^2, P a least-squares fit
 * (relative error 7e-10 on |x| <= tan(pi/8)), x z P(z) in *x_p. */
static float atan_ratio(float small, float large, uint32_t *q, float *x_p)
{
    float x = small / large;
    *q = 0u;
    if (x > ATAN_TAN_PI_8) {
        const float scale = (large < 0x1p125f) ? 1.0f : 0.25f; /* the sum stays finite; exact either way */
        x = (small * scale - large * scale) / (small * scale + large * scale);
        *q = 1u;
    }
    const float z = x * x;
    *x_p = x * (z * (-0x1.555548p-2f + z * (0x1.99916ep-3f + z * (-0x1.23b2aep-3f + z * (0x1.b1cc4ep-4f + z * -0x1.f15c7ap-5f)))));
    return x;
}

float tvo_atan2f(float y, float x)
{
    const uint32_t y_bits = float_bits(y);
    const uint32_t x_bits = float_bits(x);
    const uint32_t y_magnitude = y_bits & 0x7FFFFFFFu;
    const uint32_t x_magnitude = x_bits & 0x7FFFFFFFu;
    if (y_magnitude > 0x7F800000u || x_magnitude > 0x7F800000u) {
        /* NaN in, that NaN out, quieted (by its bits: the same NaN on every target) */
        const uint32_t nan_bits = (y_magnitude > 0x7F800000u ? y_bits : x_bits) | 0x00400000u;
        float nan_out;
        memcpy(&nan_out, &nan_bits, sizeof(nan_out));
        return nan_out;
    }
    const int x_negative = (x_bits >> 31) != 0u; /* -0 counts: atan2(+-0, -0) = +-pi */
    /* |angle| = q pi/4 + a + a_small, |a| <= tan(pi/8) */
    uint32_t q;
    float a = 0.0f;
    float a_small = 0.0f;
    if (y_magnitude == 0x7F800000u && x_magnitude == 0x7F800000u) {
        q = x_negative ? 3u : 1u;
    } else if (y_magnitude == 0u || x_magnitude == 0x7F800000u) {
        q = x_negative ? 4u : 0u; /* y on the axis, or x infinitely far */
    } else if (x_magnitude == 0u || y_magnitude == 0x7F800000u) {
        q = 2u;
    } else {
        const float ay = fabsf(y);
        const float ax = fabsf(x);
        if (ay <= ax) {
            a = atan_ratio(ay, ax, &q, &a_small);
        } else {
            a = -atan_ratio(ax, ay, &q, &a_small); /* pi/2 - atan(|x/y|) */
            a_small = -a_small;
            q = 2u - q;
        }
        if (x_negative) {
            a = -a; /* pi - the angle */
            a_small = -a_small;
            q = 4u - q;
        }
    }
    /* q pi/4 + a with its rounding error kept (|q pi/4| >= |a| unless q = 0, where the sum is a). */
    const float sum = quarter_pi_hi[q] + a;
    const float sum_error = a - (sum - quarter_pi_hi[q]);
    const float angle = sum + ((quarter_pi_lo[q] + a_small) + sum_error);
    return (y_bits >> 31) != 0u ? -angle : angle;
}
