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

/** out = value (all higher coefficients zero). */
void tvo_jet_constant(tvo_real_t value, tvo_jet_t *out);
/** out = value + slope * tau. */
void tvo_jet_variable(tvo_real_t value, tvo_real_t slope, tvo_jet_t *out);
void tvo_jet_add(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out);
void tvo_jet_sub(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out);
void tvo_jet_scale(const tvo_jet_t *a, tvo_real_t s, uint8_t order, tvo_jet_t *out);
/** out += s * a (fused accumulate). */
void tvo_jet_axpy(tvo_real_t s, const tvo_jet_t *a, uint8_t order, tvo_jet_t *out);
/** Cauchy product; out may alias a or b. */
void tvo_jet_mul(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out);
/** a / b; b->c[0] must be non-zero (the caller checks). out may alias a or b. */
void tvo_jet_div(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out);
/** sqrt(a); a->c[0] must be > 0. */
void tvo_jet_sqrt(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out);
/** log(a); a->c[0] must be > 0. */
void tvo_jet_log(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out);
/** exp(a). */
void tvo_jet_exp(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out);
/** 1 if every coefficient up to order is finite. */
int tvo_jet_is_finite(const tvo_jet_t *a, uint8_t order);

#ifdef __cplusplus
}
#endif

#endif /* TVO_JET_H */
