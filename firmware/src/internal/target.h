/*
 * Internal: target's functions (the types are in tvo/target.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_TARGET_H
#define TVO_INTERNAL_TARGET_H

#include "tvo/target.h"
#include "internal/assert.h"
#include "internal/jet.h"
#include "internal/objective.h"
#include "internal/trig.h"

#ifdef __cplusplus
extern "C" {
#endif

/**
 * deriv[j][axis] = j-th time derivative of y_d at time t, j = 0..order (order <= TVO_JET_MAX_ORDER).
 * A streamed target evaluated before its stamp reports TVO_ERR_FUTURE_STAMP (extrapolation is
 * causal only).
 */
tvo_status_t tvo_target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2]);

/** y_d(t(tau)) as one jet per axis, to the given order (c_j = y_d^(j)(t) rate^j / j!). */
tvo_status_t tvo_target_jet(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order, tvo_jet_t out[2]);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_TARGET_H */
