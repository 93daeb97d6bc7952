/*
 * Internal: law's functions (the types are in tvo/law.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_LAW_H
#define TVO_INTERNAL_LAW_H

#include "tvo/law.h"
#include "internal/assert.h"
#include "internal/objective.h"

#ifdef __cplusplus
extern "C" {
#endif

/** 1 if the gains a_0 .. a_{k-1} are finite and make s^k + a_{k-1}s^{k-1} + ... + a_0 Hurwitz (Routh-Hurwitz). */
int tvo_law_gains_hurwitz(uint8_t relative_degree, const tvo_real_t *gain);

/**
 * The law for k in 1..TVO_MAX_RELATIVE_DEGREE, 1 <= dim <= TVO_MAX_Z_DIM and Hurwitz gains (the
 * controllers' inits check them and name the culprit).
 */
void tvo_law_init(tvo_law_t *law, uint8_t relative_degree, uint8_t dim, const tvo_real_t *gain);

tvo_status_t tvo_law_check_sampling_reach(uint8_t relative_degree, const tvo_real_t *gain, tvo_real_t period_s);

/**
 * y_k[0..dim-1] = z^(k) demanded by the law at (z^[k-1], t). eval may be NULL. Its workspace is an
 * automatic tvo_law_workspace_t (tests and tools); the controllers use tvo_law_evaluate_report.
 * An indefinite or singular primal Hessian is regularised (eval->regularization > 0, see
 * tvo/linsolve.h); TVO_ERR_NOT_POSITIVE_DEFINITE if even that fails or the equality constraints are
 * dependent; TVO_ERR_NUMERIC if a result is not finite. On error y_k is zeroed, but where its length
 * is unknown: a law that is not initialised (TVO_ERR_NOT_INITIALIZED). The pointers must be valid (eval may be NULL).
 */
tvo_status_t tvo_law_evaluate(const tvo_law_t *law, const tvo_objective_t *objective,
                              const tvo_output_derivs_t *y, const tvo_time_jet_t *t,
                              tvo_real_t *y_k, tvo_law_eval_t *eval);

/** The same evaluation for the step, in the caller's workspace: only the report's outputs are written. */
tvo_status_t tvo_law_evaluate_report(const tvo_law_t *law, const tvo_objective_t *objective,
                                     const tvo_output_derivs_t *y, const tvo_time_jet_t *t, tvo_real_t *y_k,
                                     tvo_law_report_t *report, tvo_law_workspace_t *work);

/* The general path (a tvo_general_path_fn; law_workspace points to a tvo_law_workspace_t whose call
 * and outputs are set): what the objective's add functions store, and so the only reference that
 * links it into a firmware. */
tvo_status_t law_general_path(void *law_workspace);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_LAW_H */
