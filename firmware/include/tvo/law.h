/*
 * The TV-O feedback law (paper, Theorem "TVO-based control"), for relative degree k = 1..3:
 *
 *   y^(k) = -H^{-1} [ sum_{i<k} a_i grad^(i) + r ],   H = grad_yy Phi(y, t),
 *
 * where grad^(i) is the i-th total time derivative of grad_y Phi along the trajectory and r is the
 * part of grad^(k) that does not depend on y^(k). Both come from one jet evaluation of the
 * objective's gradient along y(tau) = sum_{j<k} y^(j) tau^j / j!, t(tau) = t + tau: coefficient i
 * times i! is grad^(i) for i < k, and coefficient k times k! is r (y^(k) = 0 on that curve).
 * For k = 2 this is y'' = -H^{-1}(r + k_p g + k_d g').
 *
 * With equality constraints the same law runs on z = (y, nu) and the Lagrangian: H is then the KKT
 * matrix and the solve is tvo_saddle_solve (which also regularises an indefinite primal block).
 */
#ifndef TVO_LAW_H
#define TVO_LAW_H

#include "tvo/objective.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    uint8_t relative_degree;                       /* k */
    uint8_t dim;                                   /* size of z: m (+ q multipliers) */
    tvo_real_t gain[TVO_MAX_RELATIVE_DEGREE];      /* a_0 .. a_{k-1}: s^k + a_{k-1} s^{k-1} + .. + a_0 */
    tvo_real_t gain_by_factorial[TVO_MAX_RELATIVE_DEGREE]; /* a_i i!: they weigh the jets' coefficients */
} tvo_law_t;

/** z^(0..k-1) at the evaluation instant, each in R^dim. */
typedef struct {
    tvo_real_t d[TVO_MAX_RELATIVE_DEGREE][TVO_MAX_Z_DIM];
} tvo_output_derivs_t;

/** What the law computed, for telemetry and tests (entries beyond the used sizes are zero). */
typedef struct {
    tvo_real_t grad[TVO_MAX_RELATIVE_DEGREE + 1][TVO_MAX_Z_DIM]; /* grad^(0..k-1), then r */
    tvo_real_t hessian[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    tvo_real_t regularization;  /* shift mu added to the primal Hessian block (0: none needed) */
} tvo_law_eval_t;

/** What a controller keeps of an evaluation, written in place (no record to clear or copy). */
typedef struct {
    tvo_real_t *gradient;       /* receives grad^(0), count entries; NULL: not wanted */
    tvo_real_t *gradient_rate;  /* receives grad^(1), count entries; NULL: not wanted */
    uint8_t count;
    tvo_real_t regularization;  /* set by the evaluation */
} tvo_law_report_t;

/** Where one evaluation writes besides y_k, set by its entry (NULL or 0: not wanted). */
typedef struct {
    tvo_real_t *grad_rows[TVO_MAX_RELATIVE_DEGREE + 1]; /* grad^(j), grad_count entries each */
    uint8_t grad_count;
    tvo_real_t (*hessian)[TVO_MAX_Z_DIM];
    tvo_real_t *regularization;
} tvo_law_outputs_t;

/** The evaluation's working storage: a controller keeps one beside its law, so the step's stack
 *  holds none of it (its contents mean nothing between evaluations). */
typedef struct {
    tvo_law_outputs_t outputs;                 /* the entry's, so the evaluation's call passes fewer */
    tvo_jet_t y_jet[TVO_MAX_Z_DIM];            /* z along the trajectory, then the Hessian's seeds */
    tvo_jet_t g_jet[TVO_MAX_Z_DIM];            /* the gradient's jets */
    tvo_hessian_t hessian;                     /* with the solve's own scratch */
    tvo_real_t rhs[TVO_MAX_Z_DIM];
    tvo_real_t gamma[TVO_MAX_RANK_ONE_PARTS];
    tvo_time_jet_t time;                       /* along the trajectory, then frozen */
    tvo_shared_values_t shared;                /* what the terms share along time (time.shared) */
    struct {                                   /* the evaluation's arguments, for the general path */
        const tvo_law_t *law;                  /* (tvo_general_path_fn: its one argument is this */
        const tvo_objective_t *objective;      /* workspace, so no record of them on the stack) */
        const tvo_output_derivs_t *y;
        const tvo_time_jet_t *t;
        tvo_real_t *y_k;
    } call;
} tvo_law_workspace_t;

#ifdef __cplusplus
}
#endif

#endif /* TVO_LAW_H */
