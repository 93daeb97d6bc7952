/*
 * Internal: objective's functions (the types are in tvo/objective.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_OBJECTIVE_H
#define TVO_INTERNAL_OBJECTIVE_H

#include "tvo/objective.h"
#include "tvo/target.h"
#include "internal/assert.h"
#include "internal/jet.h"
#include "internal/linsolve.h"
#include "internal/sample_clock.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The time jet at an exact instant (the step's way: no division beyond one in tvo_real_t). */
tvo_status_t tvo_time_jet_at(const tvo_tick_time_t *time, uint32_t tick_hz, tvo_real_t rate, tvo_time_jet_t *t);

/** The time jet at a tick count since the epoch (64-bit division: for tools and tests). */
tvo_status_t tvo_time_jet_at_ticks(uint64_t ticks, uint32_t tick_hz, tvo_real_t rate, tvo_time_jet_t *t);

/** Records the target the last term added reads (NULL: none) if it is streamed, for the controllers' check
 *  before their law (tvo_objective_t.targets: the other kinds are always ready). */
static inline void objective_add_target(tvo_objective_t *objective, const struct tvo_target *target)
{
    TVO_ASSERT(objective->target_count < objective->term_count); /* one per term at most */
    if (target != NULL && target->kind == TVO_TARGET_STREAMED && objective->target_count < TVO_MAX_TERMS) {
        objective->targets[objective->target_count++] = target;
    }
}

/** The law's precondition, decided by the loop as the stamp rules are: every streamed target the objective
 *  noted can be evaluated at law_ticks (it has a sample, stamped no later), else the period's reason
 *  (TVO_REASON_TARGET_NOT_READY, TVO_REASON_FUTURE_STAMP). Out of line: the step keeps its registers for
 *  the law. */
tvo_reason_t objective_targets_ready(const tvo_objective_t *objective, uint64_t law_ticks);

/** Appends an inequality-constraint term (constraint_max must not be NULL). */
tvo_status_t tvo_objective_add_constraint(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                          tvo_constraint_max_fn constraint_max, const void *term);

/**
 * Reserves count Lagrange multipliers; *first_index is the z index of the first one. Total at most
 * TVO_MAX_EQUALITIES (TVO_ERR_CAPACITY), and fewer than primal_dim (TVO_ERR_DIMENSION: more
 * independent equalities than outputs leave nothing to optimise).
 */
tvo_status_t tvo_objective_reserve_multipliers(tvo_objective_t *objective, uint8_t count, uint8_t *first_index);

/**
 * grad[0..dim-1] = sum over terms of their gradient jets at (z, t), to the given order.
 * Returns the first failing term's status, or TVO_ERR_NUMERIC if the sum is not finite.
 */
tvo_status_t tvo_objective_gradient_jet(const tvo_objective_t *objective, const tvo_jet_t *z,
                                        const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/**
 * The law's pass: grad[0..dim-1] = sum of every term's gradient jets at (z, t); terms with a closed
 * form (unless jets_only) also add their Hessian into hessian (which the caller clears).
 * *jet_terms = how many terms contributed no Hessian (the law differentiates those by jets).
 * Unlike tvo_objective_gradient_jet it does not check the sum for finiteness: the caller does.
 */
tvo_status_t tvo_objective_gradient_hessian(const tvo_objective_t *objective, const tvo_jet_t *z,
                                            const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                            tvo_hessian_t *hessian, uint8_t *jet_terms);

/** grad = the sum of the gradient jets of only the terms tvo_objective_gradient_hessian left to jets. */
tvo_status_t tvo_objective_gradient_jet_of_jet_terms(const tvo_objective_t *objective, const tvo_jet_t *z,
                                                     const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/**
 * *max_value = max over all inequality constraints of f_i(y, t) (y: primal_dim values);
 * *has_constraints = 0 (and *max_value = 0) when the objective has none.
 */
tvo_status_t tvo_objective_constraint_max(const tvo_objective_t *objective, const tvo_real_t *y, tvo_real_t t_s,
                                          tvo_real_t *max_value, uint8_t *has_constraints);

/** Seconds since the epoch for an exact tick count (integer part split off to keep precision). */
tvo_real_t tvo_ticks_to_seconds(uint64_t ticks, uint32_t tick_hz);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_OBJECTIVE_H */
