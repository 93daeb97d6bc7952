/* Weighted tracking term; see tvo/tracking.h. */
#include "tvo/tracking.h"

#include "shape.h"

tvo_status_t tvo_tracking_init(tvo_tracking_term_t *term, const tvo_target_t *target,
                               const tvo_real_t weight[2], uint8_t offset)
{
    if (term == NULL || target == NULL || weight == NULL) {
        return TVO_ERR_NULL;
    }
    if (!isfinite(weight[0]) || !isfinite(weight[1])) {
        return TVO_ERR_NOT_FINITE;
    }
    /* W > 0 keeps f0 strongly convex, which the law's Newton step relies on. */
    if (!(weight[0] > TVO_R(0.0)) || !(weight[1] > TVO_R(0.0))) {
        return TVO_ERR_PARAM;
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
    tvo_jet_t target_jet[2];
    const tvo_status_t st = tvo_target_jet(self->target, t, order, target_jet);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_t error;
        tvo_jet_sub(&y[self->offset + axis], &target_jet[axis], order, &error);
        tvo_jet_axpy(self->weight[axis], &error, order, &grad[self->offset + axis]);
    }
    return TVO_OK;
}

/* grad += W (y - y_d) for coefficients 0 .. count-1, y_d's j-th coefficient being deriv[j] scale[j]. */
TVO_SHAPE_BODY void add_weighted_error(const tvo_tracking_term_t *self, const tvo_jet_t *y,
                                        tvo_real_t (*deriv)[2], const tvo_real_t *scale, unsigned count,
                                        tvo_jet_t *grad)
{
    for (unsigned axis = 0; axis < 2u; ++axis) {
        const unsigned i = self->offset + axis;
        const tvo_real_t w = self->weight[axis];
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < count; ++j) {
            grad[i].c[j] += w * (y[i].c[j] - deriv[j][axis] * scale[j]);
        }
    }
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
    /* grad = W (y - y_d(t)) coefficient by coefficient, y_d's j-th coefficient being
     * y_d^(j) rate^j / j!; the Hessian is the constant W. */
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    const tvo_status_t st = tvo_target_derivatives(self->target, t, order, deriv);
    if (st != TVO_OK) {
        return st;
    }
    /* rate^j / j! (rate is 1 along the trajectory, 0 for frozen time). */
    const tvo_real_t rate = t->rate;
    const tvo_real_t scale[4] = {TVO_R(1.0), rate, TVO_R(0.5) * rate * rate, rate * rate * rate / TVO_R(6.0)};
    const unsigned count = tvo_jet_order_clamp(order) + 1u;
#if TVO_SHAPE_COPIES
    if (count == TVO_SHAPE_ORDER + 1u) {
        add_weighted_error(self, y, deriv, scale, TVO_SHAPE_ORDER + 1u, grad);
    } else
#endif
    {
        add_weighted_error(self, y, deriv, scale, count, grad);
    }
    for (unsigned axis = 0; axis < 2u; ++axis) {
        const unsigned i = self->offset + axis;
        hessian->matrix[i][i] += self->weight[axis];
    }
    return TVO_OK;
}
