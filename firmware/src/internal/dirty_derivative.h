/*
 * Internal: dirty_derivative's functions (the types are in tvo/dirty_derivative.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_DIRTY_DERIVATIVE_H
#define TVO_INTERNAL_DIRTY_DERIVATIVE_H

#include "tvo/dirty_derivative.h"
#include "internal/assert.h"

#ifdef __cplusplus
extern "C" {
#endif

/** tf_s > 0, period_s > 0, 1 <= dim <= TVO_MAX_OUTPUT_DIM. */
tvo_status_t tvo_dirty_derivative_init(tvo_dirty_derivative_t *filter, uint8_t dim, tvo_real_t tf_s,
                                       tvo_real_t period_s);

/**
 * Starts from input u with output y0 (NULL: zero), as if the input had been moving at y0 forever.
 */
tvo_status_t tvo_dirty_derivative_reset(tvo_dirty_derivative_t *filter, const tvo_real_t *input,
                                        const tvo_real_t *initial_output);

/**
 * One sample taken dt_s after the previous one (dt_s > 0). output[0..dim-1] receives the filtered
 * derivative. An unprimed filter primes with zero output.
 */
tvo_status_t tvo_dirty_derivative_step(tvo_dirty_derivative_t *filter, const tvo_real_t *input,
                                       tvo_real_t dt_s, tvo_real_t *output);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_DIRTY_DERIVATIVE_H */
