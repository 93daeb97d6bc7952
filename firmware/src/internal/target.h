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
 * A streamed target is misused without a sample (TVO_ERR_NOT_INITIALIZED) and at a time before its
 * sample's stamp (TVO_ERR_PARAM: extrapolation is causal only); a controller's step asks
 * target_ready_at first, and holds for its reason instead.
 */
tvo_status_t tvo_target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2]);

/** y_d(t(tau)) as one jet per axis, to the given order (c_j = y_d^(j)(t) rate^j / j!). */
tvo_status_t tvo_target_jet(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order, tvo_jet_t out[2]);

/** Whether a target can be evaluated at `ticks` (objective time): TVO_REASON_NONE, or the period's reason
 *  for a streamed target without a sample (TVO_REASON_TARGET_NOT_READY) or stamped after it
 *  (TVO_REASON_FUTURE_STAMP). The controllers' precondition on their law. */
static inline tvo_reason_t target_ready_at(const tvo_target_t *target, uint64_t ticks)
{
    if (target->kind != TVO_TARGET_STREAMED) {
        return TVO_REASON_NONE;
    }
    if (!target->u.streamed.has_sample) {
        return TVO_REASON_TARGET_NOT_READY;
    }
    return (ticks < target->u.streamed.stamp_ticks) ? TVO_REASON_FUTURE_STAMP : TVO_REASON_NONE;
}

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_TARGET_H */
