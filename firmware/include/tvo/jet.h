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

/** The order clamped to TVO_JET_MAX_ORDER (every loop stays bounded). */
static inline unsigned tvo_jet_order_clamp(uint8_t order)
{
    return order > TVO_JET_MAX_ORDER ? (unsigned)TVO_JET_MAX_ORDER : (unsigned)order;
}

/** out = value (all higher coefficients zero). */
static inline void tvo_jet_constant(tvo_real_t value, tvo_jet_t *out)
{
    for (unsigned j = 1; j <= TVO_JET_MAX_ORDER; ++j) {
        out->c[j] = TVO_R(0.0);
    }
    out->c[0] = value;
}

/** out = value + slope * tau. */
static inline void tvo_jet_variable(tvo_real_t value, tvo_real_t slope, tvo_jet_t *out)
{
    tvo_jet_constant(value, out);
    out->c[1] = slope;
}

static inline void tvo_jet_add(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = a->c[j] + b->c[j];
    }
}

static inline void tvo_jet_sub(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = a->c[j] - b->c[j];
    }
}

static inline void tvo_jet_scale(const tvo_jet_t *a, tvo_real_t s, uint8_t order, tvo_jet_t *out)
{
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = s * a->c[j];
    }
}

/** out += s * a (fused accumulate). */
static inline void tvo_jet_axpy(tvo_real_t s, const tvo_jet_t *a, uint8_t order, tvo_jet_t *out)
{
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] += s * a->c[j];
    }
}

/** Cauchy product; out may alias a or b. */
static inline void tvo_jet_mul(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    const unsigned n = tvo_jet_order_clamp(order);
    tvo_jet_t r;
    for (unsigned j = 0; j <= n; ++j) {
        tvo_real_t acc = TVO_R(0.0);
        for (unsigned i = 0; i <= j; ++i) {
            acc += a->c[i] * b->c[j - i];
        }
        r.c[j] = acc;
    }
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = r.c[j];
    }
}

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
