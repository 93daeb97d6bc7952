/*
 * Internal: equality's functions (the types are in tvo/equality.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_EQUALITY_H
#define TVO_INTERNAL_EQUALITY_H

#include "tvo/equality.h"
#include "internal/assert.h"
#include "internal/objective.h"
#include "internal/target.h"

#ifdef __cplusplus
extern "C" {
#endif

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

#endif /* TVO_INTERNAL_EQUALITY_H */
