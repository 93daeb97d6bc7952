/*
 * Dirty-derivative filter D(s) = s / (T_f s + 1), per channel, discretized exactly for inputs that
 * are linear between samples (ramp-invariant, i.e. first-order-hold equivalent):
 *
 *   y[n+1] = a y[n] + (1 - a) (u[n+1] - u[n]) / dt,   a = exp(-dt / T_f).
 *
 * This reproduces the continuous filter's output at the samples whenever u is piecewise linear
 * between them, so a ramp's velocity is recovered without bias (a zero-order-hold discretization
 * would over-estimate it by about dt / (2 T_f)). dt may vary from sample to sample (a dropped
 * sample doubles it); the nominal period's decay is cached so the usual step needs no exp().
 */
#ifndef TVO_DIRTY_DERIVATIVE_H
#define TVO_DIRTY_DERIVATIVE_H

#include "tvo/config.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tvo_real_t tf_s;
    tvo_real_t period_s;
    tvo_real_t period_decay;                    /* exp(-period_s / tf_s) */
    tvo_real_t last_input[TVO_MAX_OUTPUT_DIM];
    tvo_real_t output[TVO_MAX_OUTPUT_DIM];
    uint8_t dim;
    uint8_t primed;                             /* a first sample has been seen */
} tvo_dirty_derivative_t;

#ifdef __cplusplus
}
#endif

#endif /* TVO_DIRTY_DERIVATIVE_H */
