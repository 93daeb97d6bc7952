/* The objective as a sum of gradient-jet terms; see tvo/objective.h. */
#include "tvo/objective.h"

tvo_status_t tvo_objective_init(tvo_objective_t *objective, uint8_t dim)
{
    if (objective == NULL) {
        return TVO_ERR_NULL;
    }
    objective->term_count = 0;
    objective->dim = 0;
    if (dim == 0u || dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_DIMENSION;
    }
    objective->dim = dim;
    return TVO_OK;
}

tvo_status_t tvo_objective_add_term(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                    const void *term)
{
    if (objective == NULL || gradient_jet == NULL || term == NULL) {
        return TVO_ERR_NULL;
    }
    if (objective->dim == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (objective->term_count >= TVO_MAX_TERMS) {
        return TVO_ERR_CAPACITY;
    }
    objective->terms[objective->term_count].gradient_jet = gradient_jet;
    objective->terms[objective->term_count].term = term;
    objective->term_count++;
    return TVO_OK;
}

tvo_status_t tvo_objective_gradient_jet(const tvo_objective_t *objective, const tvo_jet_t *y,
                                        const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    if (objective == NULL || y == NULL || t == NULL || grad == NULL) {
        return TVO_ERR_NULL;
    }
    if (objective->dim == 0u || objective->dim > TVO_MAX_OUTPUT_DIM || objective->term_count == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    for (uint8_t i = 0; i < objective->dim; ++i) {
        tvo_jet_constant(TVO_R(0.0), &grad[i]);
    }
    for (uint8_t k = 0; k < objective->term_count && k < TVO_MAX_TERMS; ++k) {
        const tvo_term_t *term = &objective->terms[k];
        const tvo_status_t st = term->gradient_jet(term->term, y, objective->dim, t, order, grad);
        if (st != TVO_OK) {
            return st;
        }
    }
    for (uint8_t i = 0; i < objective->dim; ++i) {
        if (!tvo_jet_is_finite(&grad[i], order)) {
            return TVO_ERR_NUMERIC;
        }
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
