/* Formation-offset equality through Lagrange multipliers; see tvo/equality.h. */
#include "internal/equality.h"

tvo_status_t tvo_offset_equality_add(tvo_offset_equality_term_t *term, tvo_objective_t *objective,
                                     const tvo_target_t *offset, uint8_t robot_a, uint8_t robot_b)
{
    if (term == NULL || objective == NULL || offset == NULL) {
        return TVO_ERR_NULL;
    }
    if (robot_a >= TVO_MAX_ROBOTS || robot_b >= TVO_MAX_ROBOTS || 2u * robot_a + 2u > objective->primal_dim ||
        2u * robot_b + 2u > objective->primal_dim) {
        return TVO_ERR_DIMENSION;
    }
    if (robot_a == robot_b) {
        return TVO_ERR_PARAM;
    }
    uint8_t first = 0;
    const tvo_general_path_fn general_path_before = objective->general_path;
    tvo_status_t st = tvo_objective_reserve_multipliers(objective, 2u, &first);
    if (st != TVO_OK) {
        return st;
    }
    term->offset = offset;
    term->offset_a = (uint8_t)(2u * robot_a);
    term->offset_b = (uint8_t)(2u * robot_b);
    term->multiplier_index = first;
    const tvo_term_t spec = {tvo_offset_equality_gradient_jet, tvo_offset_equality_gradient_hessian, NULL, term,
                             TVO_TERM_GENERAL};
    st = tvo_objective_add(objective, &spec);
    if (st == TVO_OK) {
        objective_add_target(objective, offset); /* a streamed d(t) is checked as a tracking target is */
    } else {
        /* Give the multipliers back, so a failed add leaves the objective as it was. */
        objective->dual_dim = (uint8_t)(objective->dual_dim - 2u);
        objective->dim = (uint8_t)(objective->dim - 2u);
        objective->general_path = general_path_before;
    }
    return st;
}

tvo_status_t tvo_offset_equality_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim,
                                              const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    const tvo_offset_equality_term_t *self = (const tvo_offset_equality_term_t *)term;
    if (self == NULL || z == NULL || t == NULL || grad == NULL) {
        return TVO_ERR_NULL;
    }
    if ((unsigned)self->offset_a + 2u > dim || (unsigned)self->offset_b + 2u > dim ||
        (unsigned)self->multiplier_index + 2u > dim) {
        return TVO_ERR_DIMENSION;
    }
    tvo_jet_t offset[2];
    const tvo_status_t st = tvo_target_jet(self->offset, t, order, offset);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        const uint8_t nu = (uint8_t)(self->multiplier_index + axis);
        /* L = nu^T (y_a - y_b - d(t)): grad_ya = nu, grad_yb = -nu, grad_nu = y_a - y_b - d. */
        tvo_jet_add(&grad[self->offset_a + axis], &z[nu], order, &grad[self->offset_a + axis]);
        tvo_jet_sub(&grad[self->offset_b + axis], &z[nu], order, &grad[self->offset_b + axis]);
        tvo_jet_t residual;
        tvo_jet_sub(&z[self->offset_a + axis], &z[self->offset_b + axis], order, &residual);
        tvo_jet_sub(&residual, &offset[axis], order, &residual);
        tvo_jet_add(&grad[nu], &residual, order, &grad[nu]);
    }
    return TVO_OK;
}

tvo_status_t tvo_offset_equality_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim,
                                                  const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                                  tvo_hessian_t *hessian)
{
    if (hessian == NULL) {
        return TVO_ERR_NULL;
    }
    const tvo_status_t st = tvo_offset_equality_gradient_jet(term, z, dim, t, order, grad);
    if (st != TVO_OK) {
        return st;
    }
    /* L = nu^T (y_a - y_b - d(t)) is bilinear: the constraint Jacobian [I, -I] and its transpose. */
    const tvo_offset_equality_term_t *self = (const tvo_offset_equality_term_t *)term;
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        const uint8_t nu = (uint8_t)(self->multiplier_index + axis);
        const uint8_t a = (uint8_t)(self->offset_a + axis);
        const uint8_t b = (uint8_t)(self->offset_b + axis);
        hessian->matrix[a][nu] += TVO_R(1.0);
        hessian->matrix[nu][a] += TVO_R(1.0);
        hessian->matrix[b][nu] -= TVO_R(1.0);
        hessian->matrix[nu][b] -= TVO_R(1.0);
    }
    return TVO_OK;
}
