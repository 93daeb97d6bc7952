/* Truncated Taylor arithmetic; see tvo/jet.h. Recurrences are the standard ones of
 * automatic differentiation (Griewank & Walther, ch. 13). */
#include "internal/jet.h"

#include "internal/exp_log.h"

static unsigned clamp_order(uint8_t order)
{
    return tvo_jet_order_clamp(order);
}

void tvo_jet_sqrt(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out)
{
    /* s^2 = a  <=>  s_j = (a_j - sum_{0<i<j} s_i s_{j-i}) / (2 s_0) */
    const unsigned n = clamp_order(order);
    tvo_jet_t s;
    s.c[0] = TVO_SQRT(a->c[0]);
    for (unsigned j = 1; j <= n; ++j) {
        tvo_real_t acc = a->c[j];
        for (unsigned i = 1; i < j; ++i) {
            acc -= s.c[i] * s.c[j - i];
        }
        s.c[j] = acc / (TVO_R(2.0) * s.c[0]);
    }
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = s.c[j];
    }
}

void tvo_jet_log(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out)
{
    /* l' = a'/a  <=>  j l_j = (j a_j - sum_{0<i<j} i l_i a_{j-i}) / a_0 */
    const unsigned n = clamp_order(order);
    tvo_jet_t l;
    l.c[0] = TVO_LOG(a->c[0]);
    for (unsigned j = 1; j <= n; ++j) {
        tvo_real_t acc = (tvo_real_t)j * a->c[j];
        for (unsigned i = 1; i < j; ++i) {
            acc -= (tvo_real_t)i * l.c[i] * a->c[j - i];
        }
        l.c[j] = acc / ((tvo_real_t)j * a->c[0]);
    }
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = l.c[j];
    }
}

void tvo_jet_exp(const tvo_jet_t *a, uint8_t order, tvo_jet_t *out)
{
    /* e' = a' e  <=>  j e_j = sum_{0<i<=j} i a_i e_{j-i} */
    const unsigned n = clamp_order(order);
    tvo_jet_t e;
    e.c[0] = TVO_EXP(a->c[0]);
    for (unsigned j = 1; j <= n; ++j) {
        tvo_real_t acc = TVO_R(0.0);
        for (unsigned i = 1; i <= j; ++i) {
            acc += (tvo_real_t)i * a->c[i] * e.c[j - i];
        }
        e.c[j] = acc / (tvo_real_t)j;
    }
    for (unsigned j = 0; j <= n; ++j) {
        out->c[j] = e.c[j];
    }
}

int tvo_jet_is_finite(const tvo_jet_t *a, uint8_t order)
{
    const unsigned n = clamp_order(order);
    for (unsigned j = 0; j <= n; ++j) {
        if (!isfinite(a->c[j])) {
            return 0;
        }
    }
    return 1;
}
