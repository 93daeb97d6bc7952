/*
 * Equality constraints through the Lagrangian (paper, "Equality Constrained ..."): the term adds
 * nu^T (A y - b(t)) to the objective, so grad_y += A^T nu and grad_nu = A y - b(t); the law's Hessian
 * over z = (y, nu) becomes the KKT matrix [H A^T; A 0].
 *
 * Formation offset: y_a - y_b = d(t), two equalities (one per axis), d(t) any tvo_target_t
 * (polynomial, circle, ellipse, streamed) used as a time function with derivatives.
 */
#ifndef TVO_EQUALITY_H
#define TVO_EQUALITY_H

#include "tvo/objective.h"
#include "tvo/target.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const tvo_target_t *offset;     /* d(t) */
    uint8_t offset_a;               /* 2 * robot_a */
    uint8_t offset_b;               /* 2 * robot_b */
    uint8_t multiplier_index;       /* z index of nu_x (nu_y follows) */
} tvo_offset_equality_term_t;

/**
 * Reserves the two multipliers in objective and adds the term to it (the term's storage must
 * outlive the objective). robot_a != robot_b, both inside the objective's primal dimension.
 */
tvo_status_t tvo_offset_equality_add(tvo_offset_equality_term_t *term, tvo_objective_t *objective,
                                     const tvo_target_t *offset, uint8_t robot_a, uint8_t robot_b);

tvo_status_t tvo_offset_equality_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim,
                                              const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/** Closed form of tvo_offset_equality_gradient_jet: the same gradient jets plus the KKT coupling. */
tvo_status_t tvo_offset_equality_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim,
                                                  const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                                  tvo_hessian_t *hessian);

#ifdef __cplusplus
}
#endif

#endif /* TVO_EQUALITY_H */
