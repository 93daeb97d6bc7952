/*
 * Internal: the tracking term's closed form, unchecked (TVO_ASSERT in debug builds), for a caller
 * that has validated its inputs (tvo_tracking_gradient_hessian, which checks them, and the law's path
 * for objectives of tracking terms only, which needs no Hessian matrix).
 */
#ifndef TVO_TRACKING_KERNEL_H
#define TVO_TRACKING_KERNEL_H

#include "shape.h"
#include "internal/target_kernel.h"
#include "tvo/tracking.h"

/* grad += W (y - y_d) for coefficients 0 .. count-1, y_d's j-th coefficient being deriv[j] scale[j]. */
TVO_SHAPE_BODY void tracking_add_weighted_error(const tvo_tracking_term_t *self, const tvo_jet_t *y,
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

/*
 * grad += W (y - y_d(t)) coefficient by coefficient (y_d's j-th coefficient being y_d^(j) rate^j / j!,
 * rate being t's: passed apart, so a caller along the trajectory can pass the constant 1) and the
 * constant Hessian W added on the diagonal: diagonal[i * diagonal_stride] += W_ii. For a term whose
 * offset + 2 <= the objective's dimension and a finite t->t_s (its target's pointer is valid from
 * tvo_tracking_init). Returns the target's status.
 */
static inline tvo_status_t tracking_add(const tvo_tracking_term_t *self, const tvo_jet_t *y, const tvo_time_jet_t *t,
                                        tvo_real_t rate, uint8_t order, tvo_jet_t *grad, tvo_real_t *diagonal,
                                        unsigned diagonal_stride)
{
    TVO_ASSERT(self != NULL && self->target != NULL && y != NULL && t != NULL && grad != NULL && diagonal != NULL);
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    const tvo_status_t st = target_derivatives(self->target, t, order, deriv);
    if (st != TVO_OK) {
        return st;
    }
    /* rate^j / j! (rate is 1 along the trajectory, 0 for frozen time). */
    const tvo_real_t scale[4] = {TVO_R(1.0), rate, TVO_R(0.5) * rate * rate, rate * rate * rate / TVO_R(6.0)};
    const unsigned count = tvo_jet_order_clamp(order) + 1u;
#if TVO_SHAPE_COPIES
    if (count == TVO_SHAPE_ORDER + 1u) {
        tracking_add_weighted_error(self, y, deriv, scale, TVO_SHAPE_ORDER + 1u, grad);
    } else
#endif
    {
        tracking_add_weighted_error(self, y, deriv, scale, count, grad);
    }
    for (unsigned axis = 0; axis < 2u; ++axis) {
        diagonal[(self->offset + axis) * diagonal_stride] += self->weight[axis];
    }
    return TVO_OK;
}

/* target_derivatives for a term's target; with shape copies, a periodic target's at the common order in
 * this body (the checks target_derivatives makes for it, then its derivatives: no call). */
TVO_SHAPE_BODY tvo_status_t tracking_target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t,
                                                        const uint8_t order, tvo_real_t (*deriv)[2])
{
#if TVO_SHAPE_COPIES && !TVO_USE_DOUBLE
    if (order == TVO_SHAPE_ORDER && (target->kind == TVO_TARGET_CIRCLE || target->kind == TVO_TARGET_ELLIPSE) &&
        t->tick_hz != 0u && t->frac_ticks < t->tick_hz) {
        ellipse_derivatives(target, t, TVO_SHAPE_ORDER, deriv);
        return TVO_OK;
    }
#endif
    return target_derivatives(target, t, order, deriv);
}

/* tracking_add along the trajectory (rate 1) for outputs given by their derivatives y[j][i], j < order
 * (y^(order) is 0 there): each jet coefficient y^(j)/j! read where it is, the same numbers as
 * trajectory_jets' jets followed by tracking_add (the law's tracking path, which then keeps no jets). */
TVO_SHAPE_BODY tvo_status_t tracking_add_along(const tvo_tracking_term_t *self, const tvo_real_t (*y)[TVO_MAX_Z_DIM],
                                               const tvo_time_jet_t *t, const uint8_t order, tvo_jet_t *grad,
                                               tvo_real_t *diagonal, const unsigned diagonal_stride)
{
    TVO_ASSERT(self != NULL && self->target != NULL && y != NULL && t != NULL && grad != NULL && diagonal != NULL);
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    const tvo_status_t st = tracking_target_derivatives(self->target, t, order, deriv);
    if (st != TVO_OK) {
        return st;
    }
    static const tvo_real_t inv_factorial[4] = {TVO_R(1.0), TVO_R(1.0), TVO_R(0.5), TVO_R(1.0) / TVO_R(6.0)};
    const unsigned count = tvo_jet_order_clamp(order) + 1u;
    for (unsigned axis = 0; axis < 2u; ++axis) {
        const unsigned i = self->offset + axis;
        const tvo_real_t w = self->weight[axis];
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < count; ++j) {
            const tvo_real_t y_j = j < order ? y[j][i] * inv_factorial[j] : TVO_R(0.0);
            grad[i].c[j] += w * (y_j - deriv[j][axis] * inv_factorial[j]);
        }
    }
    for (unsigned axis = 0; axis < 2u; ++axis) {
        diagonal[(self->offset + axis) * diagonal_stride] += self->weight[axis];
    }
    return TVO_OK;
}

#endif /* TVO_TRACKING_KERNEL_H */
