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

#ifdef __cplusplus
}
#endif

#endif /* TVO_EQUALITY_H */
