/*
 * Internal: the high half of a 64 x 64-bit product from 32-bit halves (no 128-bit type needed, and
 * the same bits on every target: the exact reductions of trig.c and the integer paths of exp_log.c).
 */
#ifndef TVO_INTERNAL_WIDE_MUL_H
#define TVO_INTERNAL_WIDE_MUL_H

#include <stdint.h>

/* floor(a b / 2^64). */
static inline uint64_t wide_mul_high_u64(uint64_t a, uint64_t b)
{
    const uint64_t a_lo = a & 0xFFFFFFFFu;
    const uint64_t a_hi = a >> 32;
    const uint64_t b_lo = b & 0xFFFFFFFFu;
    const uint64_t b_hi = b >> 32;
    const uint64_t lo_lo = a_lo * b_lo;
    const uint64_t hi_lo = a_hi * b_lo;
    const uint64_t lo_hi = a_lo * b_hi;
    const uint64_t carry = ((lo_lo >> 32) + (hi_lo & 0xFFFFFFFFu) + (lo_hi & 0xFFFFFFFFu)) >> 32;
    return a_hi * b_hi + (hi_lo >> 32) + (lo_hi >> 32) + carry;
}

#endif /* TVO_INTERNAL_WIDE_MUL_H */
