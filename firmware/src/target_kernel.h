/*
 * Private to the core: a target's derivatives for a caller that has checked the pointers and that
 * t's time is finite (the tracking term's closed form). tvo_target_derivatives checks them, then
 * runs the same code.
 */
#ifndef TVO_TARGET_KERNEL_H
#define TVO_TARGET_KERNEL_H

#include "tvo/target.h"

/* tvo_target_derivatives without those checks: an order above TVO_JET_MAX_ORDER and the kind's errors
 * (a streamed target without a sample or with a future one, a time jet without the exact split a
 * periodic phase needs) are still refused. */
tvo_status_t target_derivatives_unchecked(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                          tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2]);

#endif /* TVO_TARGET_KERNEL_H */
