/*
 * The objective Phi(z, t) as a sum of terms behind one interface.
 *
 * A term contributes only its gradient, evaluated on jets: given z(tau) and t(tau) as jets, it adds
 * grad_z phi_term(z(tau), t(tau)) as jets into grad. From that single function the law derives the
 * gradient, its total time derivatives along the trajectory and (with unit-direction jets) the
 * Hessian, so adding a term (barrier, constraint) never touches the law.
 *
 * The variable is z = (y, nu): the flat output y (primal_dim entries, 2 per robot) followed by the
 * Lagrange multipliers nu of equality constraints (dual_dim entries, reserved by the equality terms).
 * Without equality constraints z = y and the objective is f0 plus barrier terms; with them it is the
 * Lagrangian and its Hessian is the KKT matrix (paper, "Equality Constrained ...").
 *
 * An inequality-constraint term can also report max_i f_i(y, t), which chooses the barrier's slack
 * s0 from the first measurement (tvo_objective_constraint_max), through the objective's start rule.
 */
#ifndef TVO_OBJECTIVE_H
#define TVO_OBJECTIVE_H

#include "tvo/config.h"
#include "tvo/jet.h"
#include "tvo/linsolve.h"
#include "tvo/sample_clock.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** c(t) and s(t), the relaxed barrier's schedules (tvo/barrier.h), along a time jet. */
typedef struct {
    tvo_jet_t c;
    tvo_jet_t slack;
} tvo_barrier_schedule_jet_t;

/**
 * What every term of one evaluation shares, computed once for all of them: the barrier's schedules along
 * the evaluation's time jet, filled by the first term that needs them (tvo_barrier_schedule_shared) and
 * read by the others. The law keeps one and empties it for each time jet it evaluates along.
 */
typedef struct {
    const void *owner;                   /* the barrier the schedules are of; NULL: empty */
    uint8_t order;                       /* the jet order they were computed to */
    tvo_barrier_schedule_jet_t schedule;
} tvo_shared_values_t;

/**
 * Time along a jet: t(tau) = t_s + rate * tau. rate is 1 along the trajectory and 0 for Hessian
 * columns. ticks is the same instant as an exact tick count since the objective's epoch, for
 * terms that need exact time differences (a streamed target's age), and whole_s + frac_ticks the
 * same split into seconds, for terms that need exact phases after hours (periodic targets); frac_s is
 * the fraction in seconds, as t_s adds it.
 */
typedef struct {
    tvo_real_t t_s;
    tvo_real_t rate;
    uint64_t ticks;
    uint32_t tick_hz;
    uint32_t whole_s;
    uint32_t frac_ticks;
    tvo_real_t frac_s;               /* frac_ticks / tick_hz: t_s = whole_s + frac_s */
    tvo_shared_values_t *shared;     /* this time jet's shared values (the law's); NULL: every term computes
                                        its own */
} tvo_time_jet_t;

/**
 * Adds a term's gradient jets into grad[0..dim-1] (dim = the objective's z dimension). Returns
 * TVO_OK or an error; must not write past dim and must leave grad finite on success.
 */
typedef tvo_status_t (*tvo_gradient_jet_fn)(const void *term, const tvo_jet_t *z, uint8_t dim,
                                            const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);

/** *max_value = max_i f_i(y, t) over the term's inequality constraints f_i(y, t) <= 0. */
typedef tvo_status_t (*tvo_constraint_max_fn)(const void *term, const tvo_real_t *y, uint8_t primal_dim,
                                              tvo_real_t t_s, tvo_real_t *max_value);

/**
 * A term's closed form (optional): adds its gradient jets along z, as gradient_jet would, and its
 * Hessian at z's constant coefficients with time frozen (into hessian->matrix, or as a rank-one part
 * through tvo_hessian_add_rank_one: a barrier's curvature along its constraint's gradient), so the
 * law needs no Hessian passes over jets for it. It must agree with gradient_jet to rounding; the
 * differential test (tests/unit/test_closed_forms.c) holds every closed form to that.
 */
typedef tvo_status_t (*tvo_gradient_hessian_fn)(const void *term, const tvo_jet_t *z, uint8_t dim,
                                                const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                                tvo_hessian_t *hessian);

/**
 * The law's general path (every kind of term, the Hessian from jets and closed forms, the KKT solve),
 * reached through the objective: every public add function (tvo_objective_add*, for any term, a
 * TVO_TERM_TRACKING term included) and tvo_objective_reserve_multipliers set it; only tvo_tracking_add
 * does not, so a firmware whose objective holds tracking terms only does not link it. The argument is
 * the law's workspace (tvo_law_workspace_t), which holds the call's arguments.
 */
typedef tvo_status_t (*tvo_general_path_fn)(void *law_workspace);

/** What a term is, which the law and the objective dispatch on. */
typedef enum {
    /** Any term, through its callbacks. */
    TVO_TERM_GENERAL = 0,
    /** A tracking term (tvo/tracking.h, term a tvo_tracking_term_t) by its closed form: the callbacks
     *  are not used (stored NULL); they are named only where the general path calls them, so the law's
     *  tracking path for objectives of tracking terms only links neither. */
    TVO_TERM_TRACKING = 1
} tvo_term_kind_t;

struct tvo_objective;
struct tvo_target; /* tvo/target.h */

/**
 * An objective's start rule, the paper's s0 (tvo_problem_init sets it when its problem has inequality
 * constraints; the problem, which holds the objective, keeps its state). Until a controller has
 * accepted its first sample, its step calls it once the measurement has passed its checks, with the
 * measurement's positions y (2 per robot), before the law; and, if that period is then refused, again
 * with y NULL, which takes back what the first call chose (a refused period changes nothing). So the
 * first accepted sample is the state at t = 0; if its constraint values are not finite, s0 stays 0.
 */
typedef void (*tvo_start_rule_fn)(const struct tvo_objective *objective, const tvo_real_t *y);

typedef struct {
    tvo_gradient_jet_fn gradient_jet;         /* required for a general term: the general mechanism and
                                                 the reference */
    tvo_gradient_hessian_fn gradient_hessian; /* NULL: the Hessian comes from jets */
    tvo_constraint_max_fn constraint_max;     /* NULL for terms without inequality constraints */
    const void *term;
    uint8_t kind;                             /* tvo_term_kind_t */
} tvo_term_t;

typedef struct tvo_objective {
    uint8_t term_count;
    uint8_t primal_dim;  /* flat-output dimension m (2 per robot) */
    uint8_t dual_dim;    /* equality multipliers q, reserved by tvo_objective_reserve_multipliers */
    uint8_t dim;         /* m + q: the size of z, of the gradient and of the law's solve */
    uint8_t jets_only;   /* 1: closed forms ignored, every term through jets (the reference path); needs
                            the general path, which tvo_tracking_add alone does not link (the step then
                            refuses with TVO_ERR_NOT_INITIALIZED) */
    uint8_t tracking_only; /* kept by the add functions: every term so far a tracking term's closed form
                              (the law re-checks the terms before it relies on it) */
    uint8_t target_count;  /* targets[0 .. target_count - 1] */
    tvo_general_path_fn general_path; /* NULL: tracking terms only, and the law has only its tracking path */
    tvo_start_rule_fn start_rule;     /* NULL: no start rule (the step chooses nothing) */
#if TVO_BLOCK_SOLVE
    const tvo_solve_plan_t *plan;     /* the block solve's plan of the terms' coupling (tvo_problem_init sets
                                         it); NULL: the dense solve. Any term or multiplier added drops it */
#endif
    tvo_term_t terms[TVO_MAX_TERMS]; /* as the add functions keep them (a tracking term: its kind, and the
                                        term; callbacks NULL) */
    /* The streamed targets the terms read, as their terms were added (a tracking term's, by its kind or its
     * callback tvo_tracking_gradient_jet; an offset equality's d(t)), which a controller's step checks can
     * be evaluated at its law's time before the law (one may have no sample yet); another term
     * declares none. After the terms, so the fields above have short offsets. */
    const struct tvo_target *targets[TVO_MAX_TERMS];
} tvo_objective_t;

/** Empty objective over y in R^primal_dim, 1 <= primal_dim <= TVO_MAX_OUTPUT_DIM, no multipliers. */
tvo_status_t tvo_objective_init(tvo_objective_t *objective, uint8_t primal_dim);

/** Appends a term; the term's storage must outlive the objective. */
tvo_status_t tvo_objective_add_term(tvo_objective_t *objective, tvo_gradient_jet_fn gradient_jet,
                                    const void *term);

/** Appends a term described in full: term required; a general term needs gradient_jet (the rest may
 *  be NULL); a TVO_TERM_TRACKING term (a tvo_tracking_term_t) needs no callback. Another kind is
 *  TVO_ERR_PARAM. */
tvo_status_t tvo_objective_add(tvo_objective_t *objective, const tvo_term_t *term);

#ifdef __cplusplus
}
#endif

#endif /* TVO_OBJECTIVE_H */
