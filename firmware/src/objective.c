/* The objective as a sum of gradient-jet terms; see tvo/objective.h. */
#include "internal/objective.h"

#include "internal/law.h"
#include "internal/objective_kernel.h"
#include "internal/sample_clock.h"
#include "internal/target.h"
#include "tvo/tracking.h"

tvo_status_t tvo_objective_init(tvo_objective_t *objective, uint8_t primal_dim)
{
    if (objective == NULL) {
        return TVO_ERR_NULL;
    }
    objective->term_count = 0;
    objective->primal_dim = 0;
    objective->dual_dim = 0;
    objective->dim = 0;
    objective->jets_only = 0;
    objective->tracking_only = 0;
    objective->target_count = 0;
    objective->general_path = NULL;
    objective->start_rule = NULL;
#if TVO_BLOCK_SOLVE
    objective->plan = NULL;
#endif
    if (primal_dim == 0u || primal_dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_DIMENSION;
    }
    objective->primal_dim = primal_dim;
    objective->dim = primal_dim;
    return TVO_OK;
}

static tvo_status_t append_slot(tvo_objective_t *objective, const tvo_term_t *spec)
{
    if (objective->dim == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (objective->term_count >= TVO_MAX_TERMS) {
        return TVO_ERR_CAPACITY;
    }
    objective->terms[objective->term_count] = *spec;
#if TVO_BLOCK_SOLVE
    objective->plan = NULL; /* the plan knows only the coupling of the terms it was made for */
#endif
    /* Tracking terms alone need no Hessian matrix in the law (its diagonal path). */
    const int tracking = spec->kind == TVO_TERM_TRACKING;
    objective->tracking_only = (uint8_t)((objective->term_count == 0u || objective->tracking_only) && tracking);
    objective->term_count++;
    return TVO_OK;
}

tvo_reason_t objective_targets_ready(const tvo_objective_t *objective, uint64_t law_ticks)
{
    const uint8_t count = objective->target_count;
    for (uint8_t i = 0; i < count && i < TVO_MAX_TERMS; ++i) {
        const tvo_reason_t reason = target_ready_at(objective->targets[i], law_ticks);
        if (reason != TVO_REASON_NONE) {
            return reason;
        }
    }
    return TVO_REASON_NONE;
}

tvo_status_t objective_append_tracking(tvo_objective_t *objective, const void *tracking_term)
{
    const tvo_term_t slot = {NULL, NULL, NULL, tracking_term, TVO_TERM_TRACKING};
    const tvo_status_t st = append_slot(objective, &slot);
    if (st == TVO_OK) {
        objective_add_target(objective, ((const tvo_tracking_term_t *)tracking_term)->target);
    }
    return st;
}

/* The public add functions take any term: their objective may need the law's general path. A tracking
 * term is kept as tvo_tracking_add keeps it (objective_kernel.h). */
static tvo_status_t append_general_term(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                        tvo_gradient_hessian_fn gradient_hessian,
                                        tvo_constraint_max_fn constraint_max, const void *term, uint8_t kind)
{
    const tvo_term_t spec = {gradient_jet, gradient_hessian, constraint_max, term, TVO_TERM_GENERAL};
    const tvo_status_t st =
        (kind == TVO_TERM_TRACKING) ? objective_append_tracking(objective, term) : append_slot(objective, &spec);
    if (st == TVO_OK) {
        objective->general_path = law_general_path;
        if (kind != TVO_TERM_TRACKING && gradient_jet == tvo_tracking_gradient_jet) {
            /* A tracking term by its callbacks reads its target as the closed form does. */
            objective_add_target(objective, ((const tvo_tracking_term_t *)term)->target);
        }
    }
    return st;
}

tvo_status_t tvo_objective_add_term(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                    const void *term)
{
    if (objective == NULL || gradient_jet == NULL || term == NULL) {
        return TVO_ERR_NULL;
    }
    return append_general_term(objective, gradient_jet, NULL, NULL, term, TVO_TERM_GENERAL);
}

tvo_status_t tvo_objective_add_constraint(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                          tvo_constraint_max_fn constraint_max, const void *term)
{
    if (objective == NULL || gradient_jet == NULL || constraint_max == NULL || term == NULL) {
        return TVO_ERR_NULL;
    }
    return append_general_term(objective, gradient_jet, NULL, constraint_max, term, TVO_TERM_GENERAL);
}

tvo_status_t tvo_objective_add(tvo_objective_t *objective, const tvo_term_t *term)
{
    if (objective == NULL || term == NULL || term->term == NULL ||
        (term->kind == TVO_TERM_GENERAL && term->gradient_jet == NULL)) {
        return TVO_ERR_NULL;
    }
    if (term->kind != TVO_TERM_GENERAL && term->kind != TVO_TERM_TRACKING) {
        return TVO_ERR_PARAM;
    }
    return append_general_term(objective, term->gradient_jet, term->gradient_hessian, term->constraint_max, term->term,
                               term->kind);
}

tvo_status_t tvo_objective_reserve_multipliers(tvo_objective_t *objective, uint8_t count, uint8_t *first_index)
{
    if (objective == NULL || first_index == NULL) {
        return TVO_ERR_NULL;
    }
    if (objective->dim == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (count == 0u || (unsigned)objective->dual_dim + count > TVO_MAX_EQUALITIES) {
        return TVO_ERR_CAPACITY;
    }
    if ((unsigned)objective->dual_dim + count >= objective->primal_dim) {
        return TVO_ERR_DIMENSION;
    }
    *first_index = objective->dim;
#if TVO_BLOCK_SOLVE
    objective->plan = NULL;
#endif
    objective->dual_dim = (uint8_t)(objective->dual_dim + count);
    objective->dim = (uint8_t)(objective->primal_dim + objective->dual_dim);
    objective->general_path = law_general_path; /* the KKT solve */
    return TVO_OK;
}


tvo_status_t objective_sum_terms(const tvo_objective_t *objective, const tvo_jet_t *z, const tvo_time_jet_t *t,
                                 uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian, sum_mode_t mode,
                                 uint8_t *jet_terms)
{
    if (objective == NULL || z == NULL || t == NULL || grad == NULL) {
        return TVO_ERR_NULL;
    }
    if (objective->dim == 0u || objective->dim > TVO_MAX_Z_DIM || objective->term_count == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    for (uint8_t i = 0; i < objective->dim; ++i) {
        tvo_jet_constant(TVO_R(0.0), &grad[i]);
    }
    uint8_t left_to_jets = 0u;
    for (uint8_t k = 0; k < objective->term_count && k < TVO_MAX_TERMS; ++k) {
        const tvo_term_t *term = &objective->terms[k];
        /* A tracking term's callbacks are named here (the general path), so a firmware without the
         * general path links neither. */
        tvo_gradient_jet_fn gradient_jet = term->gradient_jet;
        tvo_gradient_hessian_fn gradient_hessian = term->gradient_hessian;
        if (term->kind == TVO_TERM_TRACKING) {
            gradient_jet = tvo_tracking_gradient_jet;
            gradient_hessian = tvo_tracking_gradient_hessian;
        }
        const int closed = (mode != SUM_ALL_BY_JETS) && gradient_hessian != NULL && !objective->jets_only;
        tvo_status_t st = TVO_OK;
        if (mode == SUM_CLOSED_FORMS && closed) {
            st = gradient_hessian(term->term, z, objective->dim, t, order, grad, hessian);
        } else if (!(mode == SUM_JET_TERMS && closed)) {
            st = gradient_jet(term->term, z, objective->dim, t, order, grad);
            left_to_jets++;
        }
        if (st != TVO_OK) {
            return st;
        }
    }
    /* The law's pass leaves this check to the law, which checks the one vector it combines them into. */
    for (uint8_t i = 0; mode != SUM_CLOSED_FORMS && i < objective->dim; ++i) {
        if (!tvo_jet_is_finite(&grad[i], order)) {
            return TVO_ERR_NUMERIC;
        }
    }
    if (jet_terms != NULL) {
        *jet_terms = left_to_jets;
    }
    return TVO_OK;
}

tvo_status_t tvo_objective_gradient_jet(const tvo_objective_t *objective, const tvo_jet_t *z,
                                        const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    return objective_sum_terms(objective, z, t, order, grad, NULL, SUM_ALL_BY_JETS, NULL);
}

tvo_status_t tvo_objective_gradient_hessian(const tvo_objective_t *objective, const tvo_jet_t *z,
                                            const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                            tvo_hessian_t *hessian, uint8_t *jet_terms)
{
    if (hessian == NULL || jet_terms == NULL) {
        return TVO_ERR_NULL;
    }
    return objective_sum_terms(objective, z, t, order, grad, hessian, SUM_CLOSED_FORMS, jet_terms);
}

tvo_status_t tvo_objective_gradient_jet_of_jet_terms(const tvo_objective_t *objective, const tvo_jet_t *z,
                                                     const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    return objective_sum_terms(objective, z, t, order, grad, NULL, SUM_JET_TERMS, NULL);
}

tvo_status_t tvo_objective_constraint_max(const tvo_objective_t *objective, const tvo_real_t *y, tvo_real_t t_s,
                                          tvo_real_t *max_value, uint8_t *has_constraints)
{
    if (objective == NULL || y == NULL || max_value == NULL || has_constraints == NULL) {
        return TVO_ERR_NULL;
    }
    *max_value = TVO_R(0.0);
    *has_constraints = 0;
    if (objective->dim == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (!isfinite(t_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    for (uint8_t i = 0; i < objective->primal_dim; ++i) {
        if (!isfinite(y[i])) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    for (uint8_t k = 0; k < objective->term_count && k < TVO_MAX_TERMS; ++k) {
        const tvo_term_t *term = &objective->terms[k];
        if (term->constraint_max == NULL) {
            continue;
        }
        tvo_real_t value = TVO_R(0.0);
        const tvo_status_t st = term->constraint_max(term->term, y, objective->primal_dim, t_s, &value);
        if (st != TVO_OK) {
            return st;
        }
        if (!isfinite(value)) {
            return TVO_ERR_NUMERIC;
        }
        if (!*has_constraints || value > *max_value) {
            *max_value = value;
        }
        *has_constraints = 1;
    }
    return TVO_OK;
}

tvo_real_t tvo_ticks_to_seconds(uint64_t ticks, uint32_t tick_hz)
{
    if (tick_hz == 0u) {
        return TVO_R(0.0);
    }
    /* Whole seconds and the fraction convert separately, so only the final sum rounds. */
    const uint64_t whole_s = ticks / tick_hz;
    const uint64_t frac_ticks = ticks % tick_hz;
    return (tvo_real_t)whole_s + (tvo_real_t)frac_ticks / (tvo_real_t)tick_hz;
}

tvo_status_t tvo_time_jet_at(const tvo_tick_time_t *time, uint32_t tick_hz, tvo_real_t rate, tvo_time_jet_t *t)
{
    if (time == NULL || t == NULL) {
        return TVO_ERR_NULL;
    }
    if (tick_hz == 0u || time->frac_ticks >= tick_hz) {
        return TVO_ERR_PARAM;
    }
    time_jet_at_tick_time(time, tick_hz, rate, t);
    t->shared = NULL; /* a caller's time jet: every term computes its own */
    return TVO_OK;
}

tvo_status_t tvo_time_jet_at_ticks(uint64_t ticks, uint32_t tick_hz, tvo_real_t rate, tvo_time_jet_t *t)
{
    if (t == NULL) {
        return TVO_ERR_NULL;
    }
    if (tick_hz == 0u || ticks / tick_hz > UINT32_MAX) {
        return TVO_ERR_PARAM;
    }
    const tvo_tick_time_t time = {ticks, (uint32_t)(ticks / tick_hz), (uint32_t)(ticks % tick_hz)};
    return tvo_time_jet_at(&time, tick_hz, rate, t);
}
