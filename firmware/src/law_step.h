/*
 * Private to the core: the law's evaluation for the controllers' steps, whose law, objective, state,
 * time and workspace pointers are their own members (never NULL). tvo_law_evaluate_report checks
 * its pointers, then runs the same code.
 */
#ifndef TVO_LAW_STEP_H
#define TVO_LAW_STEP_H

#include "internal/law.h"

/* tvo_law_evaluate_report without the pointer checks; everything else is checked as there. */
tvo_status_t law_evaluate_report_unchecked(const tvo_law_t *law, const tvo_objective_t *objective,
                                           const tvo_output_derivs_t *y, const tvo_time_jet_t *t, tvo_real_t *y_k,
                                           tvo_law_report_t *report, tvo_law_workspace_t *work);

/* The general path (a tvo_general_path_fn; law_workspace points to a tvo_law_workspace_t whose call
 * and outputs are set): what the objective's add functions store, and so the only reference that
 * links it into a firmware. */
tvo_status_t law_general_path(void *law_workspace);

#endif /* TVO_LAW_STEP_H */
