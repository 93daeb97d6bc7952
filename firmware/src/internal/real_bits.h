/*
 * Internal: range tests of tvo_real_t values by their bits in float32, where positive floats order as
 * their bit patterns and NaN's and the infinities' lie above every finite one's: one integer
 * comparison instead of the FPU's compares (the same answers, NaN included; in double, the compares).
 */
#ifndef TVO_INTERNAL_REAL_BITS_H
#define TVO_INTERNAL_REAL_BITS_H

#include <string.h>

#include "tvo/config.h"

/* A float's bit pattern, and the float of a pattern (memcpy: no aliasing through pointers). */
static inline uint32_t float_bits(float value)
{
    uint32_t bits;
    memcpy(&bits, &value, sizeof(bits));
    return bits;
}

static inline float float_from_bits(uint32_t bits)
{
    float value;
    memcpy(&value, &bits, sizeof(value));
    return value;
}

#if TVO_USE_DOUBLE
/* |a| <= limit (limit > 0), false for NaN and the infinities. */
#define real_within(a, limit) (TVO_FABS(a) <= (limit))
/* |a| <= limit and |b| <= limit. */
#define real_within2(a, b, limit) (real_within(a, limit) && real_within(b, limit))
/* a and b finite. */
#define real_finite2(a, b) (isfinite(a) && isfinite(b))
/* v finite and > 0 (false for NaN, the infinities and both zeros). */
#define real_positive_finite(v) (isfinite(v) && (v) > TVO_R(0.0))
#else
static inline uint32_t real_magnitude_bits(float value)
{
    return float_bits(value) & 0x7FFFFFFFu;
}

static inline int real_within(float value, float limit)
{
    return real_magnitude_bits(value) <= real_magnitude_bits(limit);
}

static inline int real_within2(float a, float b, float limit)
{
    const uint32_t a_bits = real_magnitude_bits(a);
    const uint32_t b_bits = real_magnitude_bits(b);
    return (a_bits > b_bits ? a_bits : b_bits) <= real_magnitude_bits(limit);
}

static inline int real_finite2(float a, float b)
{
    const uint32_t a_bits = real_magnitude_bits(a);
    const uint32_t b_bits = real_magnitude_bits(b);
    return (a_bits > b_bits ? a_bits : b_bits) < 0x7F800000u; /* the infinities' pattern */
}

/* The positive finite floats are the patterns 1 .. 0x7F7FFFFF. */
static inline int real_positive_finite(float v)
{
    return float_bits(v) - 1u < 0x7F7FFFFFu;
}
#endif

#endif /* TVO_INTERNAL_REAL_BITS_H */
