/* Ramp-invariant dirty-derivative filter; see tvo/dirty_derivative.h. */
#include "internal/dirty_derivative.h"

#include "internal/exp_log.h"

tvo_status_t tvo_dirty_derivative_init(tvo_dirty_derivative_t *filter, uint8_t dim, tvo_real_t tf_s,
                                       tvo_real_t period_s)
{
    if (filter == NULL) {
        return TVO_ERR_NULL;
    }
    filter->dim = 0;
    filter->primed = 0;
    if (!isfinite(tf_s) || !isfinite(period_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (dim == 0u || dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_DIMENSION;
    }
    if (!(tf_s > TVO_R(0.0)) || !(period_s > TVO_R(0.0))) {
        return TVO_ERR_PARAM;
    }
    filter->tf_s = tf_s;
    filter->period_s = period_s;
    filter->period_decay = TVO_EXP(-period_s / tf_s);
    for (uint8_t i = 0; i < TVO_MAX_OUTPUT_DIM; ++i) {
        filter->last_input[i] = TVO_R(0.0);
        filter->output[i] = TVO_R(0.0);
    }
    filter->dim = dim;
    return TVO_OK;
}

tvo_status_t tvo_dirty_derivative_reset(tvo_dirty_derivative_t *filter, const tvo_real_t *input,
                                        const tvo_real_t *initial_output)
{
    if (filter == NULL || input == NULL) {
        return TVO_ERR_NULL;
    }
    if (filter->dim == 0u || filter->dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    for (uint8_t i = 0; i < filter->dim; ++i) {
        if (!isfinite(input[i]) || (initial_output != NULL && !isfinite(initial_output[i]))) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    for (uint8_t i = 0; i < filter->dim; ++i) {
        filter->last_input[i] = input[i];
        filter->output[i] = (initial_output != NULL) ? initial_output[i] : TVO_R(0.0);
    }
    filter->primed = 1;
    return TVO_OK;
}

tvo_status_t tvo_dirty_derivative_step(tvo_dirty_derivative_t *filter, const tvo_real_t *input,
                                       tvo_real_t dt_s, tvo_real_t *output)
{
    if (filter == NULL || input == NULL || output == NULL) {
        return TVO_ERR_NULL;
    }
    if (filter->dim == 0u || filter->dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (!isfinite(dt_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (!(dt_s > TVO_R(0.0))) {
        return TVO_ERR_PARAM;
    }
    for (uint8_t i = 0; i < filter->dim; ++i) {
        if (!isfinite(input[i])) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    if (!filter->primed) {
        const tvo_status_t st = tvo_dirty_derivative_reset(filter, input, NULL);
        for (uint8_t i = 0; i < filter->dim; ++i) {
            output[i] = filter->output[i];
        }
        return st;
    }
    /* Exact for input linear over dt: y+ = a y + (1 - a) (u+ - u) / dt, a = exp(-dt / T_f). */
    const tvo_real_t a = (dt_s == filter->period_s) ? filter->period_decay : TVO_EXP(-dt_s / filter->tf_s);
    const tvo_real_t gain = (TVO_R(1.0) - a) / dt_s;
    for (uint8_t i = 0; i < filter->dim; ++i) {
        filter->output[i] = a * filter->output[i] + gain * (input[i] - filter->last_input[i]);
        filter->last_input[i] = input[i];
        output[i] = filter->output[i];
    }
    return TVO_OK;
}
