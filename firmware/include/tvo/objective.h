/*
 * The objective Phi(y, t) as a sum of terms behind one interface.
 *
 * A term contributes only its gradient, evaluated on jets: given y(tau) and t(tau) as jets, it adds
 * grad_y phi_term(y(tau), t(tau)) as jets into grad. From that single function the law derives the
 * gradient, its total time derivatives along the trajectory and (with unit-direction jets) the
 * Hessian, so adding a term (barrier, constraint) never touches the law.
 */
#ifndef TVO_OBJECTIVE_H
#define TVO_OBJECTIVE_H

#include "tvo/config.h"
#include "tvo/jet.h"
#include "tvo/status.h"

/**
 * Time along a jet: t(tau) = t_s + rate * tau. rate is 1 along the trajectory and 0 for Hessian
 * columns. ticks is the same instant as an exact tick count since the objective's epoch, for
 * terms that need exact time differences (a streamed target's age).
 */
typedef struct {
    tvo_real_t t_s;
    tvo_real_t rate;
    uint64_t ticks;
    uint32_t tick_hz;
} tvo_time_jet_t;

/**
 * Adds a term's gradient jets into grad[0..dim-1]. Returns TVO_OK or an error; must not write past
 * dim and must leave grad finite on success.
 */
typedef tvo_status_t (*tvo_gradient_jet_fn)(const void *term, const tvo_jet_t *y, uint8_t dim,
                                            const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

typedef struct {
    tvo_gradient_jet_fn gradient_jet;
    const void *term;
} tvo_term_t;

typedef struct {
    tvo_term_t terms[TVO_MAX_TERMS];
    uint8_t term_count;
    uint8_t dim;       /* flat-output dimension m */
} tvo_objective_t;

/** Empty objective over y in R^dim, 1 <= dim <= TVO_MAX_OUTPUT_DIM. */
tvo_status_t tvo_objective_init(tvo_objective_t *objective, uint8_t dim);

/** Appends a term; the term's storage must outlive the objective. */
tvo_status_t tvo_objective_add_term(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                    const void *term);

/**
 * grad[0..dim-1] = sum over terms of their gradient jets at (y, t), to the given order.
 * Returns the first failing term's status, or TVO_ERR_NUMERIC if the sum is not finite.
 */
tvo_status_t tvo_objective_gradient_jet(const tvo_objective_t *objective, const tvo_jet_t *y,
                                        const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/** Seconds since the epoch for an exact tick count (integer part split off to keep precision). */
tvo_real_t tvo_ticks_to_seconds(uint64_t ticks, uint32_t tick_hz);

#endif /* TVO_OBJECTIVE_H */
