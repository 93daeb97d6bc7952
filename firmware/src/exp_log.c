/* The core's own float32 exp and log, correctly rounded; see internal/exp_log.h. */
#include "internal/exp_log.h"

#include <string.h>

#include "internal/wide_mul.h"
#include "internal/real_bits.h"

/* A floating-point unit takes exp's float path first; a soft-float target (Cortex-M0+, RV32IMAC)
 * runs the integer path alone, which costs it fewer library calls. Both round correctly: the same bits. */
#if defined(__SOFTFP__) || (defined(__riscv) && !defined(__riscv_flen))
#define EXP_FLOAT_PATH 0
#else
#define EXP_FLOAT_PATH 1
#endif

#define FLOAT_SIGN 0x80000000u
#define FLOAT_INFINITY 0x7F800000u
#define FLOAT_QUIET 0x00400000u

/*
 * value 2^(exponent - 62) rounded to the nearest float, ties to even (w > 0; w the value in Q62 of
 * its binade, 2^62 <= w < 2^64): the one rounding of the integer paths, subnormals and overflow included.
 */
static float round_q62(uint64_t w, int32_t exponent)
{
    int32_t biased = exponent + 127;
    unsigned shift = 39u; /* w's top 24 bits are the significand */
    if ((w >> 63) != 0u) {
        ++biased;
        ++shift;
    }
    if (biased >= 255) {
        return float_from_bits(FLOAT_INFINITY);
    }
    if (biased <= 0) {
        const unsigned extra = (unsigned)(1 - biased); /* a subnormal keeps fewer bits */
        if (shift + extra > 64u) {
            return 0.0f; /* below half the smallest subnormal */
        }
        shift += extra;
        biased = 0;
        if (shift == 64u) {
            /* the value is w 2^-213: half the smallest subnormal is 2^63 */
            return w > (UINT64_C(1) << 63) ? float_from_bits(1u) : 0.0f;
        }
    }
    const uint64_t significand = w >> shift;
    const uint64_t rest = w & ((UINT64_C(1) << shift) - 1u);
    const uint64_t half = UINT64_C(1) << (shift - 1u);
    /* A normal significand's leading bit carries into the exponent; a carry out of it rounds up a binade. */
    uint32_t bits = (biased > 0 ? (uint32_t)(biased - 1) << 23 : 0u) + (uint32_t)significand;
    if (rest > half || (rest == half && (significand & 1u) != 0u)) {
        ++bits;
    }
    return float_from_bits(bits);
}

/* ---- exp -----------------------------------------------------------------------------------------
 * exp(x) = 2^m 2^(j/32) exp(r), k = 32 m + j = x 32/ln2 rounded, r = x - k ln2/32. */

/* 2^(j/32) = head + tail + residual 2^-62: the head its first 12 bits (whose products with 12-bit
 * numbers are exact in float), the tail the rest rounded to float, the residual what Q62 keeps beyond. */
typedef struct {
    float head;
    float tail;
} exp2_entry_t;
static const exp2_entry_t exp2_table[32] = {
    {0x1p+0f, 0.0f}, {0x1.058p+0f, 0x1.b0d316p-12f}, {0x1.0b4p+0f, 0x1.586cfap-12f},
    {0x1.112p+0f, 0x1.01d012p-12f}, {0x1.172p+0f, 0x1.7078fap-13f}, {0x1.1d4p+0f, 0x1.0e62d2p-13f},
    {0x1.238p+0f, 0x1.e9b9d6p-14f}, {0x1.29ep+0f, 0x1.3bea4p-13f}, {0x1.306p+0f, 0x1.fc1464p-13f},
    {0x1.37p+0f, 0x1.a7373ap-12f}, {0x1.3dep+0f, 0x1.4c9824p-13f}, {0x1.44ep+0f, 0x1.0c0c32p-17f},
    {0x1.4bep+0f, 0x1.dad536p-12f}, {0x1.534p+0f, 0x1.5ab4eap-15f}, {0x1.5aap+0f, 0x1.07dd48p-12f},
    {0x1.624p+0f, 0x1.fac0eap-14f}, {0x1.6ap+0f, 0x1.3cccfep-13f}, {0x1.71ep+0f, 0x1.75e8ecp-12f},
    {0x1.7ap+0f, 0x1.1473ecp-12f}, {0x1.824p+0f, 0x1.89994cp-12f}, {0x1.8acp+0f, 0x1.ca8456p-13f},
    {0x1.936p+0f, 0x1.37b0cep-12f}, {0x1.9c4p+0f, 0x1.230548p-13f}, {0x1.a54p+0f, 0x1.03b23ep-12f},
    {0x1.ae8p+0f, 0x1.3f32b6p-13f}, {0x1.b7ep+0f, 0x1.76f2fcp-12f}, {0x1.c18p+0f, 0x1.9bdd86p-12f},
    {0x1.cb6p+0f, 0x1.20dcfp-12f}, {0x1.d58p+0f, 0x1.8dcfbap-16f}, {0x1.dfcp+0f, 0x1.2e66f8p-13f},
    {0x1.ea4p+0f, 0x1.5f454ap-13f}, {0x1.f5p+0f, 0x1.d96dbap-14f}};
static const int32_t exp2_residual_q62[32] = {
    0, -32124692, -31179382, 23937684, 21359475, -18437664, -7806565, -8682319,
    -19114824, 44509852, 13666519, -1788916, 11050101, 4065148, 22062435, -11136312,
    15675970, 25022325, -66708641, 54020651, -24941201, -15232047, -4046734, 9794093,
    -11618950, -42394709, -45453175, -29252524, 1186967, -26379546, -29137386, -15400547};

/* |x| below 2^-26 (these bits): exp(x) rounds to 1. At and beyond 104: to 0 or overflow. */
#define EXP_TINY_BITS 0x32800000u
#define EXP_HUGE_BITS 0x42D00000u

/* 2^(j/32) in Q62 from its three parts. */
static uint64_t exp2_q62(uint32_t j)
{
    const uint32_t head = float_bits(exp2_table[j].head);
    const uint32_t tail = float_bits(exp2_table[j].tail);
    uint64_t t = (uint64_t)((head & 0x7FFFFFu) | 0x800000u) << 39; /* the head lies in [1, 2) */
    if (tail != 0u) {
        t += (uint64_t)((tail & 0x7FFFFFu) | 0x800000u) << ((tail >> 23) - 88u); /* tail 2^62, exact */
    }
    return t + (uint64_t)(int64_t)exp2_residual_q62[j];
}

/* ln2 2^94 rounded: its top bits and the next 32 (k ln2/32 in Q67 to a unit of its last place). */
#define EXP_LN2_Q94_HIGH UINT64_C(0x2C5C85FDF473DE6A)
#define EXP_LN2_Q94_LOW UINT64_C(0xF278ECE6)
/* ln2/32 in Q67, rounded: the width of r's interval. */
#define EXP_LN2_OVER_32_Q67 UINT64_C(0x2C5C85FDF473DE6B)
#define EXP_32_OVER_LN2 0x1.715476p+5f

/* 1/n! in Q64, n = 2 .. 4, and in Q38, n = 5 .. 8: exp(r) - 1 - r to 2^-64 on [0, ln2/32) (the
 * terms from r^5 on, below 2^-34, need only 32-bit products). */
static const uint64_t exp_taylor_q64[3] = {UINT64_C(0x8000000000000000), UINT64_C(0x2AAAAAAAAAAAAAAB),
                                           UINT64_C(0x0AAAAAAAAAAAAAAB)};
static const uint32_t exp_taylor_q38[4] = {0x88888889u, 0x16C16C17u, 0x03403403u, 0x00680680u};

/* k ln2/32 in Q67, modulo 2^64 (|k| < 2^13). */
static uint64_t exp_k_ln2_over_32_q67(int32_t k)
{
    const uint64_t magnitude = (uint64_t)(k < 0 ? -(int64_t)k : (int64_t)k);
    const uint64_t product = magnitude * EXP_LN2_Q94_HIGH + ((magnitude * EXP_LN2_Q94_LOW) >> 32);
    return k < 0 ? 0u - product : product;
}

float tvo_expf_integer(float x)
{
    const uint32_t bits = float_bits(x);
    const uint32_t biased = (bits >> 23) & 0xFFu;
    /* x 2^67 modulo 2^64: r is small, so its bits survive the wrap (|x| in [2^-26, 104): shift 18 .. 50). */
    uint64_t x_q67 = (uint64_t)((bits & 0x7FFFFFu) | 0x800000u) << (biased - 83u);
    if ((bits & FLOAT_SIGN) != 0u) {
        x_q67 = 0u - x_q67;
    }
    /* k = floor(x 32/ln2): the float estimate truncated, then moved until r lies in [0, ln2/32) (r
     * stays within (-ln2/32, ln2/16): its top bit is its sign). */
    int32_t k = (int32_t)(x * EXP_32_OVER_LN2);
    uint64_t r_q67 = x_q67 - exp_k_ln2_over_32_q67(k);
    for (unsigned pass = 0u; pass < 2u; ++pass) {
        if ((r_q67 >> 63) != 0u) {
            --k;
        } else if (r_q67 >= EXP_LN2_OVER_32_Q67) {
            ++k;
        } else {
            break;
        }
        r_q67 = x_q67 - exp_k_ln2_over_32_q67(k);
    }
    /* exp(r) - 1 = r + r^2 (1/2 + r (1/6 + ...)), by Horner: from r^5 on in Q38 with r in Q37, then
     * in Q64 with r in Q67. */
    const uint32_t r_q37 = (uint32_t)(r_q67 >> 30);
    uint32_t high_terms = exp_taylor_q38[3];
    for (unsigned n = 3u; n-- > 0u;) {
        high_terms = exp_taylor_q38[n] + (uint32_t)(((uint64_t)r_q37 * high_terms) >> 37);
    }
    uint64_t acc = (uint64_t)high_terms << 26;
    for (unsigned n = 3u; n-- > 0u;) {
        acc = exp_taylor_q64[n] + (wide_mul_high_u64(acc, r_q67) >> 3);
    }
    const uint64_t expm1_q67 = r_q67 + (wide_mul_high_u64(r_q67, wide_mul_high_u64(r_q67, acc)) >> 3);
    const uint32_t j = (uint32_t)k & 31u;
    const uint64_t t_q62 = exp2_q62(j);
    const uint64_t w_q62 = t_q62 + (wide_mul_high_u64(t_q62, expm1_q67) >> 3);
    return round_q62(w_q62, (k - (int32_t)j) / 32);
}

#if EXP_FLOAT_PATH
/* ln2/32 = L1 + L2 + L3: L1 and L2 short enough that k L1, k L2 are exact for |k| < 2^12. */
#define EXP_LN2_OVER_32_1 0x1.62ep-6f
#define EXP_LN2_OVER_32_2 0x1.0cp-20f
#define EXP_LN2_OVER_32_3 -0x1.05c61p-34f
/* Adding it rounds to an integer k (|k| < 2^22) and leaves k in the sum's low bits. */
#define EXP_ROUND_SHIFTER 0x1.8p23f
/* Adding and subtracting it keeps a number below 2^-6 to a multiple of 2^-17: 11 bits at most. */
#define EXP_SPLIT_SHIFTER 0x1.8p6f
/* The float path's domain: |x| in [2^-26, 87), where exp(x) is a normal float. */
#define EXP_FLOAT_LIMIT_BITS 0x42AE0000u
/* y, the float path's result, is exp's rounding when y's residual is at most (1 - 2^-9) half an ulp,
 * whose bits are y's binade's less these (half an ulp is 2^-24 of the binade's least float): the test
 * allows the float path an error of 2^-34 of y. Summing its roundings' worst cases bounds that error
 * by 2^-32.9 only; measured over every float of its domain, the largest error near a midpoint is below
 * 2^-35 (a test allowing 2^-36 misrounds 673 floats, one allowing 2^-35 none), and with this test the
 * two paths give the same bits for every float (tools/agree --accuracy checks it), the float path
 * handing 0.19 % of its domain over. */
#define EXP_ROUNDING_TEST_BITS (0x0C000000u + 0x8000u)
#endif

float tvo_expf(float x)
{
    const uint32_t bits = float_bits(x);
    const uint32_t magnitude = bits & ~FLOAT_SIGN;
#if EXP_FLOAT_PATH
    /* The float path gives the integer path's result in about a quarter of its instructions, or
     * hands over when it cannot tell which float is nearest. */
    if (magnitude - EXP_TINY_BITS < EXP_FLOAT_LIMIT_BITS - EXP_TINY_BITS) {
        /* k = x 32/ln2 rounded, r = x - k ln2/32 = r1 - c: r1 exact, c small. */
        const float shifted = x * EXP_32_OVER_LN2 + EXP_ROUND_SHIFTER;
        const uint32_t shifted_bits = float_bits(shifted);
        const float kf = shifted - EXP_ROUND_SHIFTER;
        const float r1 = (x - kf * EXP_LN2_OVER_32_1) - kf * EXP_LN2_OVER_32_2;
        const float c = kf * EXP_LN2_OVER_32_3;
        const float r = r1 - c;
        /* exp(r) = 1 + r1 + u, u = r^2 (1/2 + r/6 + r^2/24) - c. */
        const float u = r * r * (0.5f + r * (0x1.555556p-3f + r * 0x1.555556p-5f)) - c;
        /* 2^(j/32) exp(r) = s + lo: head + head r1_high exactly, the rest in lo. */
        const exp2_entry_t *entry = &exp2_table[shifted_bits & 31u];
        const float r1_high = (r1 + EXP_SPLIT_SHIFTER) - EXP_SPLIT_SHIFTER;
        const float product = entry->head * r1_high;
        const float s = entry->head + product;
        const float lo = ((product - (s - entry->head)) + entry->head * ((r1 - r1_high) + u)) +
                         (entry->tail + entry->tail * (r1 + u));
        const float y = s + lo;
        const uint32_t y_bits = float_bits(y);
        const uint32_t residual_bits = float_bits(lo - (y - s)); /* s + lo = y + residual exactly */
        /* The neighbour on the residual's side lies an ulp of its binade away: y's binade, or the one
         * below when y is a power of two and the residual negative (y's bits less one give both). */
        const uint32_t binade_bits = (y_bits - (residual_bits >> 31)) & FLOAT_INFINITY;
        if ((residual_bits & ~FLOAT_SIGN) <= binade_bits - EXP_ROUNDING_TEST_BITS) {
            /* times 2^m, m = (k - j)/32: shifted's bits over 32 are m plus a multiple of 2^9 (which vanishes). */
            return float_from_bits(y_bits + ((shifted_bits >> 5) << 23));
        }
        return tvo_expf_integer(x);
    }
#endif
    if (magnitude < EXP_TINY_BITS) {
        return 1.0f; /* exp(x) lies within a quarter ulp of 1 */
    }
    if (magnitude >= EXP_HUGE_BITS) {
        if (magnitude > FLOAT_INFINITY) {
            return float_from_bits(bits | FLOAT_QUIET); /* NaN, quieted */
        }
        return (bits & FLOAT_SIGN) != 0u ? 0.0f : float_from_bits(FLOAT_INFINITY);
    }
    return tvo_expf_integer(x);
}

/* ---- log -----------------------------------------------------------------------------------------
 * x = 2^e m, m in [1, 2); m = (1 + j/16) (1 + u) near the nearest sixteenth (j = 1 .. 15, m c_j = 1 + u,
 * |u| < 2^-5), or m = 1 + u (j = 0), or 2 (1 + u) with -2^-6 <= u < 0 (then e + 1, j = 0):
 * log(x) = e ln2 - log(c_j) + log1p(u). Init-time only in the core: integers throughout, no float path. */

/* c_j 2^10, about 2^10 / (1 + j/16), j = 1 .. 15 (m c_j is exact in integers). */
static const uint16_t log_inverse_q10[15] = {964, 910, 862, 819, 780, 745, 712, 683, 655, 630, 607, 585, 565, 546, 529};
/* -log(c_j) in Q64, rounded. */
static const uint64_t log_minus_log_inverse_q64[15] = {
    UINT64_C(0x0F7518E0035C3DD8), UINT64_C(0x1E3707EE30487B42), UINT64_C(0x2C1662016128EBA9),
    UINT64_C(0x392FF00F3A89D8B1), UINT64_C(0x45AD732EB3EDCD67), UINT64_C(0x516E30285F7C4DDC),
    UINT64_C(0x5D0761DB19EEC585), UINT64_C(0x67AC91B2D3BA84BA), UINT64_C(0x7263E1A6A72EEFA9),
    UINT64_C(0x7C5A3DFEC1714826), UINT64_C(0x85DF97E91EEA0740), UINT64_C(0x8F52FB73875C1748),
    UINT64_C(0x983AB9A278709BE8), UINT64_C(0xA0FC7FC238EB087C), UINT64_C(0xA9157039C51EBE71)};
/* ln2 2^96: its top 64 bits (ln2 in Q64) and the next 32, both truncated. */
#define LOG_LN2_Q64 UINT64_C(0xB17217F7D1CF79AB)
#define LOG_LN2_Q96_LOW UINT64_C(0xC9E3B398)
/* log1p(u)/u's Taylor terms kept: |u|^14/15 < 2^-73 for |u| <= 2^-5. */
#define LOG_TERMS 14u

/* log1p(u)/u in Q63 for |u| = v 2^-64 <= 2^-5: 1 - u/2 + u^2/3 - ..., by Horner (every partial sum
 * positive, so unsigned). */
static uint64_t log1p_ratio_q63(uint64_t v_q64, int u_negative)
{
    uint64_t acc = (UINT64_C(1) << 63) / LOG_TERMS;
    for (uint32_t n = LOG_TERMS - 1u; n-- > 0u;) {
        const uint64_t coefficient = (UINT64_C(1) << 63) / (n + 1u);
        const uint64_t product = wide_mul_high_u64(v_q64, acc);
        acc = u_negative ? coefficient + product : coefficient - product;
    }
    return acc;
}

/* How far w > 0 shifts left until its top bit is set. */
static unsigned leading_zeros_u64(uint64_t w)
{
    unsigned count = 0u;
    for (unsigned step = 32u; step > 0u; step /= 2u) {
        if ((w >> (64u - step)) == 0u) {
            w <<= step;
            count += step;
        }
    }
    return count;
}

/* w 2^exponent for w > 0, rounded. */
static float round_u64(uint64_t w, int32_t exponent)
{
    const unsigned shift = leading_zeros_u64(w);
    return round_q62(w << shift, exponent - (int32_t)shift + 62);
}

float tvo_logf(float x)
{
    const uint32_t bits = float_bits(x);
    if (bits - 1u >= 0x7F7FFFFFu) { /* not a positive finite number */
        if ((bits & ~FLOAT_SIGN) > FLOAT_INFINITY) {
            return float_from_bits(bits | FLOAT_QUIET); /* NaN, quieted */
        }
        if ((bits & ~FLOAT_SIGN) == 0u) {
            return float_from_bits(FLOAT_SIGN | FLOAT_INFINITY); /* log(+-0) = -inf */
        }
        return bits == FLOAT_INFINITY ? x : float_from_bits(FLOAT_INFINITY | FLOAT_QUIET); /* +inf; NaN below 0 */
    }
    /* x = 2^e M 2^-23, M in [2^23, 2^24) (a subnormal normalised). */
    int32_t e = (int32_t)(bits >> 23) - 127;
    uint32_t significand = bits & 0x7FFFFFu;
    if (e == -127) {
        e = -126;
        for (unsigned step = 0u; step < 23u && significand < 0x800000u; ++step) {
            significand <<= 1;
            --e;
        }
    } else {
        significand |= 0x800000u;
    }
    if (bits == 0x3F800000u) {
        return 0.0f; /* log(1) = +0, the one exact case */
    }
    /* u 2^64, exactly, and j. */
    uint32_t j = ((significand - 0x800000u) + 0x40000u) >> 19;
    int64_t u_q64;
    if (j == 16u) {
        ++e;
        j = 0u;
        u_q64 = ((int64_t)significand - 0x1000000) * ((int64_t)1 << 40);
    } else if (j == 0u) {
        u_q64 = (int64_t)(significand - 0x800000u) * ((int64_t)1 << 41);
    } else {
        u_q64 = ((int64_t)significand * log_inverse_q10[j - 1u] - ((int64_t)1 << 33)) * ((int64_t)1 << 31);
    }
    const int u_negative = u_q64 < 0;
    const uint64_t v_q64 = (uint64_t)(u_negative ? -u_q64 : u_q64);
    const uint64_t ratio_q63 = log1p_ratio_q63(v_q64, u_negative);
    if (e == 0 && j == 0u) {
        /* log(x) = log1p(u) = u ratio, u exact and normalised first: relative precision however small u is. */
        const unsigned shift = leading_zeros_u64(v_q64);
        const float magnitude = round_u64(wide_mul_high_u64(v_q64 << shift, ratio_q63), -63 - (int32_t)shift);
        return u_negative ? -magnitude : magnitude;
    }
    /* The sum in 128 bits, Q64: high word the integer part (two's complement), low word the fraction. */
    const uint64_t e_magnitude = (uint64_t)(e < 0 ? -e : e);
    const uint64_t e_ln2_mid = e_magnitude * (LOG_LN2_Q64 >> 32);                           /* 2^32 units */
    const uint64_t e_ln2_low = e_magnitude * (LOG_LN2_Q64 & 0xFFFFFFFFu) + ((e_magnitude * LOG_LN2_Q96_LOW) >> 32);
    uint64_t low = (e_ln2_mid << 32) + e_ln2_low;
    uint64_t high = (e_ln2_mid >> 32) + (low < e_ln2_low ? 1u : 0u);
    if (e < 0) { /* negate */
        low = ~low + 1u;
        high = ~high + (low == 0u ? 1u : 0u);
    }
    const uint64_t minus_log_c = (j == 0u) ? 0u : log_minus_log_inverse_q64[j - 1u];
    const uint64_t log1p_q64 = wide_mul_high_u64(v_q64 << 4, ratio_q63) >> 3;
    const uint64_t before = low;
    low += minus_log_c;
    high += (low < before) ? 1u : 0u;
    if (u_negative) {
        high -= (low < log1p_q64) ? 1u : 0u;
        low -= log1p_q64;
    } else {
        low += log1p_q64;
        high += (low < log1p_q64) ? 1u : 0u;
    }
    const int negative = (high >> 63) != 0u;
    if (negative) {
        low = ~low + 1u;
        high = ~high + (low == 0u ? 1u : 0u);
    }
    /* |log(x)| < 104: the high word holds at most 7 bits; the low word's dropped bits only make it sticky. */
    float magnitude;
    if (high == 0u) {
        magnitude = round_u64(low, -64);
    } else {
        unsigned width = 0u;
        while (width < 8u && (high >> width) != 0u) {
            ++width;
        }
        const uint64_t dropped = low & ((UINT64_C(1) << width) - 1u);
        const uint64_t top = (high << (64u - width)) | (low >> width) | (dropped != 0u ? 1u : 0u);
        magnitude = round_u64(top, (int32_t)width - 64);
    }
    return negative ? -magnitude : magnitude;
}
