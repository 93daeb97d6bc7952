/*
 * Internal: chain_controller's functions (the types are in tvo/chain_controller.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_CHAIN_CONTROLLER_H
#define TVO_INTERNAL_CHAIN_CONTROLLER_H

#include "tvo/chain_controller.h"
#include "internal/assert.h"
#include "internal/dirty_derivative.h"
#include "internal/law.h"
#include "internal/objective.h"
#include "internal/sample_clock.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The chain's exact flow over dt >= 0 with u held: d[j] <- sum_{i>=j} d[i] dt^(i-j)/(i-j)! +
 * u dt^(k-j)/(k-j)! for j < k, per output (state may alias out). Used for prediction, and by simulators of the testbed.
 */
tvo_status_t tvo_chain_predict(uint8_t relative_degree, uint8_t dim, const tvo_output_derivs_t *state,
                               const tvo_real_t *u, tvo_real_t dt_s, tvo_output_derivs_t *out);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_CHAIN_CONTROLLER_H */
