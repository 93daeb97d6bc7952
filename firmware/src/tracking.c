/* Weighted tracking term; see tvo/tracking.h. */
#include "tvo/tracking.h"

#include "internal/real_bits.h"
#include "internal/objective_kernel.h"
#include "internal/tracking_kernel.h"

/* W finite and > 0 keeps f0 strongly convex, which the law's Newton step relies on. */
static tvo_status_t check_weight(const tvo_real_t weight[2])
{
    if (!real_finite2(weight[0], weight[1])) {
        return TVO_ERR_NOT_FINITE;
    }
    if (!real_positive_finite(weight[0]) || !real_positive_finite(weight[1])) {
        return TVO_ERR_PARAM;
    }
    return TVO_OK;
}

tvo_status_t tvo_tracking_init(tvo_tracking_term_t *term, const tvo_target_t *target,
                               const tvo_real_t weight[2], uint8_t offset)
{
    if (term == NULL || target == NULL || weight == NULL) {
        return TVO_ERR_NULL;
    }
    const tvo_status_t st = check_weight(weight);
    if (st != TVO_OK) {
        return st;
    }
    if ((unsigned)offset + 2u > TVO_MAX_OUTPUT_DIM) /* a robot's output, never a multiplier */ {
        return TVO_ERR_DIMENSION;
    }
    term->target = target;
    term->weight[0] = weight[0];
    term->weight[1] = weight[1];
    term->offset = offset;
    return TVO_OK;
}

tvo_status_t tvo_tracking_add(tvo_objective_t *objective, const tvo_tracking_term_t *term)
{
    if (objective == NULL || term == NULL) {
        return TVO_ERR_NULL;
    }
    if (term->target == NULL || check_weight(term->weight) != TVO_OK) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (objective->dim == 0u) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if ((unsigned)term->offset + 2u > objective->primal_dim) {
        return TVO_ERR_DIMENSION;
    }
    return objective_append_tracking(objective, term);
}

/* The checks tvo_target_jet and tvo_target_derivatives make, in their order: the target, the order,
 * then the time (the term's own pointers and offset are checked by the caller). */
static tvo_status_t check_target_call(const tvo_tracking_term_t *self, const tvo_time_jet_t *t, uint8_t order)
{
    if (self->target == NULL) {
        return TVO_ERR_NULL;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    if (!isfinite(t->t_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    return TVO_OK;
}

tvo_status_t tvo_tracking_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim,
                                       const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    const tvo_tracking_term_t *self = (const tvo_tracking_term_t *)term;
    if (self == NULL || y == NULL || t == NULL || grad == NULL) {
        return TVO_ERR_NULL;
    }
    if ((unsigned)self->offset + 2u > dim) {
        return TVO_ERR_DIMENSION;
    }
    tvo_status_t st = check_target_call(self, t, order);
    if (st != TVO_OK) {
        return st;
    }
    /* tvo_target_jet's body inline: the deepest call path of the step runs through here. */
    tvo_jet_t desired[2];
    st = target_jet(self->target, t, order, desired);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_t error;
        tvo_jet_sub(&y[self->offset + axis], &desired[axis], order, &error);
        tvo_jet_axpy(self->weight[axis], &error, order, &grad[self->offset + axis]);
    }
    return TVO_OK;
}

tvo_status_t tvo_tracking_gradient_hessian(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                           uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian)
{
    const tvo_tracking_term_t *self = (const tvo_tracking_term_t *)term;
    if (self == NULL || y == NULL || t == NULL || grad == NULL || hessian == NULL) {
        return TVO_ERR_NULL;
    }
    if ((unsigned)self->offset + 2u > dim) {
        return TVO_ERR_DIMENSION;
    }
    const tvo_status_t st = check_target_call(self, t, order);
    if (st != TVO_OK) {
        return st;
    }
    /* The Hessian is the constant W, on the matrix's diagonal. */
    return tracking_add(self, y, t, t->rate, order, grad, &hessian->matrix[0][0], TVO_MAX_Z_DIM + 1u);
}
