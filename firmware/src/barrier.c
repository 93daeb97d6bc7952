/* Relaxed logarithmic barrier and its schedules; see tvo/barrier.h. */
#include "internal/barrier.h"

#include <string.h>

#include "tvo/defaults.h"
#include "internal/barrier_kernel.h"
#include "internal/exp_log.h"

/* Stand-in for "never" when c does not grow (alpha_c = 0): far beyond any run, still finite. */
#define BARRIER_NEVER_S TVO_R(1e30)

tvo_status_t tvo_barrier_config_default(tvo_barrier_config_t *cfg)
{
    if (cfg == NULL) {
        return TVO_ERR_NULL;
    }
    cfg->c0 = (tvo_real_t)TVO_DEFAULT_BARRIER_C0;
    cfg->alpha_c_per_s = (tvo_real_t)TVO_DEFAULT_BARRIER_ALPHA_C_PER_S;
    cfg->c_max = (tvo_real_t)TVO_DEFAULT_BARRIER_C_MAX;
    cfg->delta0 = (tvo_real_t)TVO_DEFAULT_BARRIER_DELTA0;
    cfg->alpha_s_per_s = (tvo_real_t)TVO_DEFAULT_BARRIER_ALPHA_S_PER_S;
    cfg->slack_margin = (tvo_real_t)TVO_DEFAULT_BARRIER_SLACK_MARGIN;
    cfg->relaxation_degree = TVO_DEFAULT_BARRIER_RELAXATION_DEGREE;
    return TVO_OK;
}

static int positive_finite(tvo_real_t v)
{
    return isfinite(v) && v > TVO_R(0.0);
}

tvo_status_t tvo_barrier_init(tvo_barrier_t *barrier, const tvo_barrier_config_t *cfg, uint8_t relative_degree)
{
    if (barrier == NULL || cfg == NULL) {
        return TVO_ERR_NULL;
    }
    memset(barrier, 0, sizeof(*barrier));
    if (!positive_finite(cfg->c0) || !isfinite(cfg->alpha_c_per_s) || cfg->alpha_c_per_s < TVO_R(0.0) ||
        !isfinite(cfg->c_max) || cfg->c_max < cfg->c0 || !positive_finite(cfg->delta0) ||
        !positive_finite(cfg->alpha_s_per_s) || !positive_finite(cfg->slack_margin)) {
        return TVO_ERR_PARAM;
    }
    /* m_r >= k + 1: the law differentiates the barrier's gradient k times. */
    if (relative_degree == 0u || relative_degree > TVO_MAX_RELATIVE_DEGREE ||
        cfg->relaxation_degree < relative_degree + 1u || cfg->relaxation_degree > TVO_BARRIER_MAX_DEGREE) {
        return TVO_ERR_PARAM;
    }
    barrier->cfg = *cfg;
    barrier->cap_time_s = (cfg->alpha_c_per_s > TVO_R(0.0))
                              ? TVO_LOG(cfg->c_max / cfg->c0) / cfg->alpha_c_per_s
                              : BARRIER_NEVER_S;
    barrier->initialized = 1;
    return TVO_OK;
}

tvo_status_t tvo_barrier_choose_slack(tvo_barrier_t *barrier, tvo_real_t max_constraint_value)
{
    if (barrier == NULL) {
        return TVO_ERR_NULL;
    }
    if (!barrier->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (!isfinite(max_constraint_value)) {
        return TVO_ERR_NOT_FINITE;
    }
    barrier->slack0 = (max_constraint_value < TVO_R(0.0)) ? TVO_R(0.0)
                                                          : max_constraint_value + barrier->cfg.slack_margin;
    return TVO_OK;
}

/* c(t) and whether it still grows (past the cap it is constant). */
static tvo_real_t barrier_c(const tvo_barrier_t *barrier, tvo_real_t t_s, int *growing)
{
    if (t_s >= barrier->cap_time_s) {
        *growing = 0;
        return barrier->cfg.c_max;
    }
    *growing = barrier->cfg.alpha_c_per_s > TVO_R(0.0);
    return barrier->cfg.c0 * TVO_EXP(barrier->cfg.alpha_c_per_s * t_s);
}

tvo_status_t tvo_barrier_schedule(const tvo_barrier_t *barrier, tvo_real_t t_s, tvo_real_t *c, tvo_real_t *slack,
                                  tvo_real_t *delta)
{
    if (barrier == NULL || c == NULL || slack == NULL || delta == NULL) {
        return TVO_ERR_NULL;
    }
    if (!barrier->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (!isfinite(t_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    int growing = 0;
    *c = barrier_c(barrier, t_s, &growing);
    *slack = barrier->slack0 * TVO_EXP(-barrier->cfg.alpha_s_per_s * t_s);
    *delta = barrier->cfg.delta0 / *c;
    return TVO_OK;
}

tvo_status_t tvo_barrier_derivatives(uint8_t relaxation_degree, tvo_real_t sigma, tvo_real_t delta, uint8_t order,
                                     tvo_real_t *derivs)
{
    if (derivs == NULL) {
        return TVO_ERR_NULL;
    }
    if (relaxation_degree == 0u || relaxation_degree > TVO_BARRIER_MAX_DEGREE || order > TVO_BARRIER_MAX_DEGREE) {
        return TVO_ERR_PARAM;
    }
    if (!isfinite(sigma) || !positive_finite(delta)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (sigma >= delta) {
        /* d^n/dsigma^n (-log sigma) = (-1)^n (n-1)! / sigma^n for n >= 1. */
        derivs[0] = -TVO_LOG(sigma);
        tvo_real_t term = TVO_R(-1.0) / sigma;
        for (uint8_t n = 1; n <= order; ++n) {
            derivs[n] = term;
            term *= -(tvo_real_t)n / sigma;
        }
        return TVO_OK;
    }
    /* With u = (delta - sigma)/delta: B = -log delta + sum_j u^j / j and du/dsigma = -1/delta, so
     * d^n B/dsigma^n = (-1/delta)^n sum_{j>=max(n,1)} (j-1)!/(j-n)! u^(j-n). */
    const tvo_real_t u = (delta - sigma) / delta;
    tvo_real_t chain = TVO_R(1.0);
    for (uint8_t n = 0; n <= order; ++n) {
        tvo_real_t sum = (n == 0u) ? -TVO_LOG(delta) : TVO_R(0.0);
        for (uint8_t j = (n == 0u) ? 1u : n; j <= relaxation_degree; ++j) {
            /* (j-1)!/(j-n)! u^(j-n) / (n==0 ? j : 1): falling product of j-1 down to j-n+1. */
            tvo_real_t coeff = (n == 0u) ? TVO_R(1.0) / (tvo_real_t)j : TVO_R(1.0);
            for (uint8_t f = 1; f < n; ++f) {
                coeff *= (tvo_real_t)(j - f);
            }
            tvo_real_t power = TVO_R(1.0);
            for (uint8_t e = 0; e < j - n; ++e) {
                power *= u;
            }
            sum += coeff * power;
        }
        derivs[n] = chain * sum;
        chain *= TVO_R(-1.0) / delta;
    }
    return TVO_OK;
}

tvo_status_t tvo_barrier_schedule_jet(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, uint8_t order,
                                      tvo_barrier_schedule_jet_t *schedule)
{
    if (barrier == NULL || t == NULL || schedule == NULL) {
        return TVO_ERR_NULL;
    }
    if (!barrier->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    /* c(t + rate tau) and s(t + rate tau) as jets: exponentials in tau. */
    int growing = 0;
    const tvo_real_t c_now = barrier_c(barrier, t->t_s, &growing);
    const tvo_real_t c_rate = growing ? barrier->cfg.alpha_c_per_s * t->rate : TVO_R(0.0);
    /* A feasible start has no slack: no exponential to evaluate. */
    const tvo_real_t s_now = (barrier->slack0 == TVO_R(0.0))
                                 ? TVO_R(0.0)
                                 : barrier->slack0 * TVO_EXP(-barrier->cfg.alpha_s_per_s * t->t_s);
    const tvo_real_t s_rate = -barrier->cfg.alpha_s_per_s * t->rate;
    tvo_jet_constant(TVO_R(0.0), &schedule->c);
    tvo_jet_constant(TVO_R(0.0), &schedule->slack);
    tvo_real_t c_term = c_now;
    tvo_real_t s_term = s_now;
    for (uint8_t j = 0; j <= order; ++j) {
        schedule->c.c[j] = c_term;
        schedule->slack.c[j] = s_term;
        c_term *= c_rate / (tvo_real_t)(j + 1u);
        s_term *= s_rate / (tvo_real_t)(j + 1u);
    }
    return TVO_OK;
}

tvo_status_t tvo_barrier_schedule_shared(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, uint8_t order,
                                        tvo_barrier_schedule_jet_t *local)
{
    if (barrier == NULL || t == NULL || local == NULL) {
        return TVO_ERR_NULL;
    }
    return barrier_schedule(barrier, t, order, local);
}

tvo_status_t tvo_barrier_weight_on_schedule(const tvo_barrier_t *barrier, const tvo_barrier_schedule_jet_t *schedule,
                                            const tvo_jet_t *f_jet, uint8_t order, tvo_jet_t *w_jet,
                                            tvo_real_t *dw_df)
{
    if (barrier == NULL || schedule == NULL || f_jet == NULL || w_jet == NULL) {
        return TVO_ERR_NULL;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
#if TVO_SHAPE_COPIES
    if (order == TVO_SHAPE_ORDER) {
        return barrier_weight(barrier, schedule, f_jet, TVO_SHAPE_ORDER, w_jet, dw_df);
    }
#endif
    return barrier_weight(barrier, schedule, f_jet, order, w_jet, dw_df);
}

tvo_status_t tvo_barrier_weight_jet(const tvo_barrier_t *barrier, const tvo_jet_t *f_jet, const tvo_time_jet_t *t,
                                    uint8_t order, tvo_jet_t *w_jet)
{
    if (barrier == NULL || f_jet == NULL || t == NULL || w_jet == NULL) {
        return TVO_ERR_NULL;
    }
    tvo_barrier_schedule_jet_t schedule;
    const tvo_status_t st = tvo_barrier_schedule_jet(barrier, t, order, &schedule);
    if (st != TVO_OK) {
        return st;
    }
    return tvo_barrier_weight_on_schedule(barrier, &schedule, f_jet, order, w_jet, NULL);
}
