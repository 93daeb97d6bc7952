/*
 * Internal: jet's functions (the types are in tvo/jet.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_JET_H
#define TVO_INTERNAL_JET_H

#include "tvo/jet.h"
#include "internal/assert.h"

#ifdef __cplusplus
extern "C" {
#endif

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
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        out->c[0] = a->c[0] + b->c[0]; /* coefficient j needs only a_j and b_j: out may alias a or b */
        out->c[1] = a->c[1] + b->c[1];
        out->c[2] = a->c[2] + b->c[2];
        return;
    }
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = a->c[j] + b->c[j];
    }
}

static inline void tvo_jet_sub(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        out->c[0] = a->c[0] - b->c[0]; /* coefficient j needs only a_j and b_j: out may alias a or b */
        out->c[1] = a->c[1] - b->c[1];
        out->c[2] = a->c[2] - b->c[2];
        return;
    }
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = a->c[j] - b->c[j];
    }
}

static inline void tvo_jet_scale(const tvo_jet_t *a, tvo_real_t s, uint8_t order, tvo_jet_t *out)
{
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        out->c[0] = s * a->c[0];
        out->c[1] = s * a->c[1];
        out->c[2] = s * a->c[2];
        return;
    }
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = s * a->c[j];
    }
}

/** out += s * a (fused accumulate). */
static inline void tvo_jet_axpy(tvo_real_t s, const tvo_jet_t *a, uint8_t order, tvo_jet_t *out)
{
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        const tvo_real_t a0 = a->c[0]; /* all read before out is written: out may alias a */
        const tvo_real_t a1 = a->c[1];
        const tvo_real_t a2 = a->c[2];
        out->c[0] += s * a0;
        out->c[1] += s * a1;
        out->c[2] += s * a2;
        return;
    }
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] += s * a->c[j];
    }
}

/** Cauchy product; out may alias a or b. */
static inline void tvo_jet_mul(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        tvo_real_t r0 = TVO_R(0.0); /* each sum as the loop below forms it, from +0 in the same order */
        r0 += a->c[0] * b->c[0];
        tvo_real_t r1 = TVO_R(0.0);
        r1 += a->c[0] * b->c[1];
        r1 += a->c[1] * b->c[0];
        tvo_real_t r2 = TVO_R(0.0);
        r2 += a->c[0] * b->c[2];
        r2 += a->c[1] * b->c[1];
        r2 += a->c[2] * b->c[0];
        out->c[0] = r0;
        out->c[1] = r1;
        out->c[2] = r2;
        return;
    }
    /* Highest coefficient first: coefficient j reads only coefficients <= j, so out may alias a or b. */
    const unsigned n = tvo_jet_order_clamp(order);
    for (unsigned jj = n + 1u; jj > 0u; --jj) {
        const unsigned j = jj - 1u;
        tvo_real_t acc = TVO_R(0.0);
        for (unsigned i = 0; i <= j; ++i) {
            acc += a->c[i] * b->c[j - i];
        }
        out->c[j] = acc;
    }
}

/** a / b; b->c[0] must be non-zero (the caller checks). out may alias a or b. */
static inline void tvo_jet_div(const tvo_jet_t *a, const tvo_jet_t *b, uint8_t order, tvo_jet_t *out)
{
    /* q = a / b  <=>  q_j = (a_j - sum_{i<j} q_i b_{j-i}) / b_0 */
    if (TVO_JET_ORDER_IS_CONSTANT_2(order)) {
        tvo_real_t q0 = a->c[0];
        q0 = q0 / b->c[0];
        tvo_real_t q1 = a->c[1];
        q1 -= q0 * b->c[1];
        q1 = q1 / b->c[0];
        tvo_real_t q2 = a->c[2];
        q2 -= q0 * b->c[2];
        q2 -= q1 * b->c[1];
        q2 = q2 / b->c[0];
        out->c[0] = q0;
        out->c[1] = q1;
        out->c[2] = q2;
        return;
    }
    const unsigned n = tvo_jet_order_clamp(order);
    tvo_jet_t q;
    tvo_jet_constant(TVO_R(0.0), &q); /* set: not every compiler sees the loop write 0..n first */
    for (unsigned j = 0; j <= n; ++j) {
        tvo_real_t acc = a->c[j];
        for (unsigned i = 0; i < j; ++i) {
            acc -= q.c[i] * b->c[j - i];
        }
        q.c[j] = acc / b->c[0];
    }
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = q.c[j];
    }
}

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

#endif /* TVO_INTERNAL_JET_H */
