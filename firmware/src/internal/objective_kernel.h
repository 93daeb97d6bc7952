/*
 * Internal: the objective's sum over its terms, for the law, which calls it without the
 * public entries' extra frame (its deepest call path runs through it into every term).
 */
#ifndef TVO_OBJECTIVE_KERNEL_H
#define TVO_OBJECTIVE_KERNEL_H

#include "internal/objective.h"

/* Which terms a pass sums, and how. */
typedef enum {
    SUM_ALL_BY_JETS = 0,  /* gradient jets of every term (the reference) */
    SUM_CLOSED_FORMS = 1, /* closed forms add gradient and Hessian; the rest gradient jets */
    SUM_JET_TERMS = 2     /* gradient jets of the terms SUM_CLOSED_FORMS leaves to jets */
} sum_mode_t;

/* grad (and, for SUM_CLOSED_FORMS, the closed forms' Hessian) of the terms mode selects; checks its
 * pointers, the objective's state and the order; *jet_terms (may be NULL) counts the terms summed by
 * their gradient jets. tvo_objective_gradient_jet, _gradient_hessian and _gradient_jet_of_jet_terms
 * are this with mode fixed. */
tvo_status_t objective_sum_terms(const tvo_objective_t *objective, const tvo_jet_t *z, const tvo_time_jet_t *t,
                                 uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian, sum_mode_t mode,
                                 uint8_t *jet_terms);

/* Appends a tracking term (kind TVO_TERM_TRACKING, callbacks NULL), without linking the law's general
 * path (tvo_tracking_add's way; tvo_objective_add calls it for such a term and then sets
 * objective->general_path). Its callbacks, tvo_tracking_gradient_jet and _hessian, are named only
 * where the general path calls them (objective_sum_terms): the law's tracking path needs neither, and
 * a firmware without the general path links neither. A term set to NULL by hand: its callbacks
 * refuse it. */
tvo_status_t objective_append_tracking(tvo_objective_t *objective, const void *tracking_term);

#endif /* TVO_OBJECTIVE_KERNEL_H */
