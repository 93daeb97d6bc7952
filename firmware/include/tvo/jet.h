/*
 * Truncated Taylor polynomials ("jets") in one variable tau.
 *
 * A jet of order n holds c[0..n] with f(tau) = sum_j c[j] tau^j + O(tau^(n+1)), i.e. c[j] is the
 * j-th derivative divided by j!. Pushing the curve y(tau) = y + y' tau + ..., t(tau) = t + tau through
 * an objective's gradient gives the gradient's total time derivatives along the trajectory; that is
 * how the law gets grad, its rates and the y^(k)-free remainder without hand-written derivatives.
 *
 * These are arithmetic primitives on the hot path: they do not validate (callers pass valid
 * pointers); the order is clamped to TVO_JET_MAX_ORDER so every loop stays bounded. Output may
 * alias an input except where noted.
 */
#ifndef TVO_JET_H
#define TVO_JET_H

#include "tvo/config.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tvo_real_t c[TVO_JET_MAX_ORDER + 1];
} tvo_jet_t;

/* The arithmetic of the hot path is inline: a handful of coefficients per call, where a call would
 * cost as much as the work. */

/* True where order is the compile-time constant 2 (the k = 2 law in the core's shape copies): the
 * arithmetic below is then written out, with the same operations in the same order as its loops. */
#if TVO_SPECIALIZE_SHAPES && defined(__GNUC__) && TVO_JET_MAX_ORDER >= 2
#define TVO_JET_ORDER_IS_CONSTANT_2(order) (__builtin_constant_p(order) && (order) == 2u)
#else
#define TVO_JET_ORDER_IS_CONSTANT_2(order) 0
#endif

#ifdef __cplusplus
}
#endif

#endif /* TVO_JET_H */
