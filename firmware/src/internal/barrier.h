/*
 * Internal: barrier's functions (the types are in tvo/barrier.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_BARRIER_H
#define TVO_INTERNAL_BARRIER_H

#include "tvo/barrier.h"
#include "internal/assert.h"
#include "internal/jet.h"
#include "internal/objective.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Validates cfg (TVO_ERR_PARAM names nothing finer: every field's range is above) against k. */
tvo_status_t tvo_barrier_init(tvo_barrier_t *barrier, const tvo_barrier_config_t *cfg, uint8_t relative_degree);

/**
 * The paper's s0 rule from max_i f_i(y(0), 0): s0 = 0 if it is < 0 (strictly feasible start),
 * else max + slack_margin.
 */
tvo_status_t tvo_barrier_choose_slack(tvo_barrier_t *barrier, tvo_real_t max_constraint_value);

/** c(t), s(t), delta(t) at t_s >= 0. */
tvo_status_t tvo_barrier_schedule(const tvo_barrier_t *barrier, tvo_real_t t_s, tvo_real_t *c,
                                  tvo_real_t *slack, tvo_real_t *delta);

/**
 * derivs[n] = d^n/dsigma^n B_delta(sigma), n = 0..order (order <= TVO_BARRIER_MAX_DEGREE), for a
 * relaxation of degree m_r. A scalar reference, for tests and tools.
 */
tvo_status_t tvo_barrier_derivatives(uint8_t relaxation_degree, tvo_real_t sigma, tvo_real_t delta, uint8_t order,
                                     tvo_real_t *derivs);

/** The schedules c(t + rate tau), s(t + rate tau) to the given order. */
tvo_status_t tvo_barrier_schedule_jet(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, uint8_t order,
                                      tvo_barrier_schedule_jet_t *schedule);

/**
 * The schedules along t to the given order: in t's shared values when t has them (the first term that
 * asks computes them there; the rest of the evaluation's terms find them), else in local, computed. The
 * same values either way; t->shared ? &t->shared->schedule : local is where they are.
 */
tvo_status_t tvo_barrier_schedule_shared(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, uint8_t order,
                                        tvo_barrier_schedule_jet_t *local);

/**
 * w_jet = w(tau) for f_jet on the schedule, and, if dw_df is not NULL, dw/df at tau = 0 with time
 * frozen (the barrier's curvature along grad f, for closed-form Hessians).
 */
tvo_status_t tvo_barrier_weight_on_schedule(const tvo_barrier_t *barrier, const tvo_barrier_schedule_jet_t *schedule,
                                            const tvo_jet_t *f_jet, uint8_t order, tvo_jet_t *w_jet,
                                            tvo_real_t *dw_df);

/**
 * The barrier weight w = -(1/c) B'_delta(s - f) along a jet: f_jet is f_i(y(tau), t(tau)), t the
 * time jet (rate 0 freezes the schedules, as in Hessian columns). w_jet receives w(tau).
 */
tvo_status_t tvo_barrier_weight_jet(const tvo_barrier_t *barrier, const tvo_jet_t *f_jet, const tvo_time_jet_t *t,
                                    uint8_t order, tvo_jet_t *w_jet);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_BARRIER_H */
