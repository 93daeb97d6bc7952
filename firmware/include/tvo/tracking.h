/*
 * Weighted tracking term f0 = 1/2 (y_r - y_d(t))^T W (y_r - y_d(t)) for one robot r, W diagonal > 0.
 *
 * y_r is the robot's pair of coordinates inside the stacked flat output (offset 2r).
 */
#ifndef TVO_TRACKING_H
#define TVO_TRACKING_H

#include "tvo/objective.h"
#include "tvo/target.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const tvo_target_t *target;
    tvo_real_t weight[2];   /* diagonal of W, both > 0 (strong convexity) */
    uint8_t offset;         /* index of the robot's x coordinate in y */
} tvo_tracking_term_t;

tvo_status_t tvo_tracking_init(tvo_tracking_term_t *term, const tvo_target_t *target,
                               const tvo_real_t weight[2], uint8_t offset);

/**
 * Appends the term to the objective with its closed form (tvo_tracking_gradient_hessian), checking
 * that it was initialised (TVO_ERR_NOT_INITIALIZED) and that its output lies within the objective's
 * (TVO_ERR_DIMENSION). An objective of such terms only is evaluated by the law's tracking path: a
 * firmware that adds no other term (no tvo_objective_add*, no multipliers) and does not call
 * tvo_law_evaluate (the tools' entry, which always has it) does not link the law's general path. Every output needs a term then: an output without one has no curvature, and the
 * step refuses it (TVO_ERR_NOT_POSITIVE_DEFINITE) where the general path would regularise it.
 */
tvo_status_t tvo_tracking_add(tvo_objective_t *objective, const tvo_tracking_term_t *term);

/** tvo_gradient_jet_fn of the tracking term (term points to a tvo_tracking_term_t). */
tvo_status_t tvo_tracking_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim,
                                       const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/** Closed form of tvo_tracking_gradient_jet: the same gradient jets plus the Hessian W. */
tvo_status_t tvo_tracking_gradient_hessian(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                           uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian);

#ifdef __cplusplus
}
#endif

#endif /* TVO_TRACKING_H */
