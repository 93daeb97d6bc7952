/*
 * The sampled-data loop's own state, one copy inside each controller's private member (not part of
 * the API: a firmware reads a controller through its calls). The loop (src/sampled_loop.h) serves
 * every plant from it: the objective the law is evaluated on, h in seconds, the clock (ticks,
 * stamps, watchdog) and whether init accepted the controller.
 */
#ifndef TVO_LOOP_STATE_H
#define TVO_LOOP_STATE_H

#include "tvo/objective.h"
#include "tvo/sample_clock.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    const tvo_objective_t *objective; /* bound by init; outlives the controller */
    tvo_real_t period_s;              /* h */
    tvo_sample_clock_t clock;         /* ticks, elapsed time, stamps, watchdog */
    uint8_t initialized;              /* init accepted the configuration */
} tvo_loop_state_t;

#ifdef __cplusplus
}
#endif

#endif /* TVO_LOOP_STATE_H */
