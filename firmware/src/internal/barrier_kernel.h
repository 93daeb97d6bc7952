/*
 * Internal: the relaxed barrier's weight jet, unchecked (TVO_ASSERT in debug builds), inline, so that
 * a constraint term's shape copy (src/shape.h) computes it with the jet order a constant.
 * tvo_barrier_weight_on_schedule checks its arguments, then calls it.
 */
#ifndef TVO_BARRIER_KERNEL_H
#define TVO_BARRIER_KERNEL_H

#include "shape.h"
#include "internal/barrier.h"

/* The schedules along t to order (tvo_barrier_schedule_shared for valid arguments): in t's shared values
 * when t has them (computed there by the first term of the evaluation that asks), else in local. */
static inline tvo_status_t barrier_schedule(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, uint8_t order,
                                            tvo_barrier_schedule_jet_t *local)
{
    tvo_shared_values_t *shared = t->shared;
    if (shared == NULL) {
        return tvo_barrier_schedule_jet(barrier, t, order, local);
    }
    if (shared->owner == (const void *)barrier && shared->order == order) {
        return TVO_OK;
    }
    const tvo_status_t st = tvo_barrier_schedule_jet(barrier, t, order, &shared->schedule);
    shared->owner = st == TVO_OK ? (const void *)barrier : NULL;
    shared->order = order;
    return st;
}

/* Where barrier_schedule put the schedules. */
static inline const tvo_barrier_schedule_jet_t *barrier_schedule_of(const tvo_time_jet_t *t,
                                                                    const tvo_barrier_schedule_jet_t *local)
{
    return t->shared != NULL ? &t->shared->schedule : local;
}

/* w(f) on the schedule's c and slack jets, and dw/df at tau = 0 (dw_df may be NULL), for valid
 * arguments (order <= TVO_JET_MAX_ORDER). TVO_ERR_NUMERIC when a result is not finite. */
TVO_SHAPE_BODY tvo_status_t barrier_weight(const tvo_barrier_t *barrier, const tvo_barrier_schedule_jet_t *schedule,
                                           const tvo_jet_t *f_jet, const uint8_t order, tvo_jet_t *w_jet,
                                           tvo_real_t *dw_df)
{
    TVO_ASSERT(barrier != NULL && schedule != NULL && f_jet != NULL && w_jet != NULL);
    TVO_ASSERT(order <= TVO_JET_MAX_ORDER);
    tvo_jet_t sigma;
    tvo_jet_sub(&schedule->slack, f_jet, order, &sigma);
    /* c sigma / delta0 = 1 + x: the branch is the logarithm when it is >= 1 at tau = 0. */
    tvo_jet_t c_sigma;
    tvo_jet_mul(&schedule->c, &sigma, order, &c_sigma);
    const tvo_real_t c0 = schedule->c.c[0];
    const tvo_real_t delta0 = barrier->cfg.delta0;
    tvo_real_t slope = TVO_R(0.0);
    if (c_sigma.c[0] >= delta0) {
        tvo_jet_t one;
        tvo_jet_constant(TVO_R(1.0), &one);
        tvo_jet_div(&one, &c_sigma, order, w_jet); /* w = 1 / (c sigma) */
        slope = c0 * w_jet->c[0] * w_jet->c[0]; /* dw/df = -dw/dsigma = c w^2 */
    } else {
        /* w = (1/delta0) P(u), P(u) = sum_{j<m_r} u^j, u = -x = 1 - c sigma / delta0, by Horner;
         * dw/df = (c / delta0^2) P'(u), also by Horner. */
        tvo_jet_t u;
        tvo_jet_scale(&c_sigma, TVO_R(-1.0) / delta0, order, &u);
        u.c[0] += TVO_R(1.0);
        tvo_jet_t acc;
        tvo_jet_constant(TVO_R(1.0), &acc);
        tvo_real_t derivative = TVO_R(0.0);
        for (uint8_t j = 1; j < barrier->cfg.relaxation_degree && j < TVO_BARRIER_MAX_DEGREE; ++j) {
            derivative = derivative * u.c[0] + acc.c[0]; /* P_j' = P_{j-1} + u P_{j-1}' */
            tvo_jet_mul(&acc, &u, order, &acc);
            acc.c[0] += TVO_R(1.0);
        }
        tvo_jet_scale(&acc, TVO_R(1.0) / delta0, order, w_jet);
        slope = c0 * derivative / (delta0 * delta0);
    }
    if (dw_df != NULL) {
        *dw_df = slope;
    }
    tvo_real_t probe = slope * TVO_R(0.0); /* v * 0 is NaN exactly for a v that is not finite */
    TVO_UNROLL_SMALL
    for (unsigned j = 0; j <= order; ++j) {
        probe += w_jet->c[j] * TVO_R(0.0);
    }
    return isfinite(probe) ? TVO_OK : TVO_ERR_NUMERIC;
}

#endif /* TVO_BARRIER_KERNEL_H */
