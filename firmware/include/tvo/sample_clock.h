/*
 * The sampled-data timing shared by every controller: integer ticks of a wrapping uint32 clock,
 * an elapsed-time count that never wraps, measurement-stamp checks and the watchdog.
 *
 * Per period a controller begins the period of its application instant (tvo_sample_clock_begin: one
 * record of the period's timing), checks the measurement's stamp, locates where its law is evaluated
 * (tvo_sample_clock_locate), and ends the period with a good or a missed step
 * (tvo_sample_clock_refuse says when a missed one expires the watchdog). Nothing changes before the end.
 */
#ifndef TVO_SAMPLE_CLOCK_H
#define TVO_SAMPLE_CLOCK_H

#include "tvo/config.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Largest tick difference treated as "forward" in wrap-around arithmetic. */
#define TVO_MAX_TICK_SPAN 0x3FFFFFFFu

/**
 * A time since the epoch: the exact tick count and the same split into whole seconds and ticks
 * (frac_ticks < tick_hz), so seconds come without a 64-bit division and without losing resolution.
 */
typedef struct {
    uint64_t ticks;
    uint32_t whole_s;
    uint32_t frac_ticks;
} tvo_tick_time_t;

/** One period's timing, from tvo_sample_clock_begin (and _locate) to its end. */
typedef struct {
    uint32_t apply_tick;
    uint32_t periods;          /* periods since the last application, >= 1 */
    tvo_tick_time_t elapsed;   /* epoch to apply_tick */
    /* Set by tvo_sample_clock_locate once the measurement is accepted: */
    uint32_t age_ticks;        /* apply_tick - the measurement's stamp */
    tvo_real_t age_s;
    tvo_tick_time_t law_time;  /* where the law is evaluated */
    tvo_real_t carry_s;        /* how far the sampled state is carried (with the held command) to get there */
} tvo_period_t;

typedef struct {
    uint32_t tick_hz;
    uint32_t period_ticks;
    uint32_t watchdog_periods;
    uint32_t epoch_tick;             /* tick at which the objective's t = 0 */
    uint32_t last_apply_tick;
    uint32_t last_stamp_tick;
    uint32_t periods_without_measurement;
    uint32_t refusals_in_row;        /* refused measurements since the last good step (saturating) */
    tvo_tick_time_t elapsed;         /* epoch to the last apply_tick, in ticks (never wraps) and seconds */
    uint8_t started;                 /* a period has ended */
    uint8_t has_stamp;               /* last_stamp_tick is valid */
    uint8_t stopped;                 /* the watchdog expired and no good step since */
    uint8_t counts_refusals;         /* a loop with no timer: refusals stand for periods (watchdog_counts_refusals) */
} tvo_sample_clock_t;

#ifdef __cplusplus
}
#endif

#endif /* TVO_SAMPLE_CLOCK_H */
