/*
 * Internal: a target's derivatives and jet, unchecked (TVO_ASSERT in debug builds), for a caller that
 * has checked the pointers and that t's time is finite (the tracking term's closed form).
 * tvo_target_derivatives and tvo_target_jet check their arguments, then call these.
 */
#ifndef TVO_TARGET_KERNEL_H
#define TVO_TARGET_KERNEL_H

#include "internal/target.h"

/* deriv[j] = y_d^(j)(t), j = 0..order: an order above TVO_JET_MAX_ORDER and the kind's errors (a
 * streamed target without a sample or with a future one, a time jet without the exact split a
 * periodic phase needs) are results, still refused. */
tvo_status_t target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2]);

/* y_d(t(tau)) as one jet per axis, for a target and time as above (inline: its caller's frame holds
 * the derivatives). */
static inline tvo_status_t target_jet(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                      tvo_jet_t out[2])
{
    TVO_ASSERT(target != NULL && t != NULL && out != NULL);
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    /* With time frozen (rate 0: Hessian columns) only the position enters the jet. */
    const uint8_t needed = (t->rate == TVO_R(0.0)) ? 0u : order;
    const tvo_status_t st = target_derivatives(target, t, needed, deriv);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_constant(TVO_R(0.0), &out[axis]);
        tvo_real_t scale = TVO_R(1.0);
        for (uint8_t j = 0; j <= needed && j <= TVO_JET_MAX_ORDER; ++j) {
            out[axis].c[j] = deriv[j][axis] * scale;
            scale *= t->rate / (tvo_real_t)(j + 1u);
        }
    }
    return TVO_OK;
}

#endif /* TVO_TARGET_KERNEL_H */
