/*
 * The sampled-data timing shared by every controller: integer ticks of a wrapping uint32 clock,
 * an elapsed-time count that never wraps, measurement-stamp checks and the watchdog.
 *
 * Per period a controller begins the period of its application instant (tvo_sample_clock_begin: one
 * record of the period's timing), checks the measurement's stamp, locates where its law is evaluated
 * (tvo_sample_clock_locate), and ends the period with a good or a missed step
 * (tvo_sample_clock_end, which says when the watchdog has expired). Nothing changes before the end.
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

/** One period's timing, from tvo_sample_clock_begin (and _locate) to tvo_sample_clock_end. */
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
    tvo_tick_time_t elapsed;         /* epoch to the last apply_tick, in ticks (never wraps) and seconds */
    uint8_t started;                 /* a period has ended */
    uint8_t has_stamp;               /* last_stamp_tick is valid */
    uint8_t stopped;                 /* the watchdog expired and no good step since */
} tvo_sample_clock_t;

/**
 * The timing parameters every controller validates: TVO_PARAM_TICK_HZ (zero), TVO_PARAM_PERIOD
 * (zero or beyond TVO_MAX_TICK_SPAN), TVO_PARAM_DELAY (beyond the period), or TVO_PARAM_NONE.
 */
tvo_param_t tvo_sample_clock_check_timing(uint32_t tick_hz, uint32_t period_ticks, uint32_t delay_ticks);

/** 1 if watchdog_periods >= 1 and the watchdog's span stays within TVO_MAX_TICK_SPAN ticks. */
int tvo_sample_clock_watchdog_ok(uint32_t period_ticks, uint32_t watchdog_periods);

/** TVO_ERR_PARAM unless the timing and watchdog pass the two checks above. */
tvo_status_t tvo_sample_clock_init(tvo_sample_clock_t *clock, uint32_t tick_hz, uint32_t period_ticks,
                           uint32_t watchdog_periods, uint32_t epoch_tick);

/** t + delta ticks (32-bit arithmetic: delta <= TVO_MAX_TICK_SPAN, tick_hz > 0). */
tvo_tick_time_t tvo_tick_time_after(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz);

/** t - delta ticks, or the epoch if t is closer to it than delta. */
tvo_tick_time_t tvo_tick_time_before(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz);

/** Seconds since the epoch: whole_s + frac_ticks / tick_hz (rounded once, to tvo_real_t). */
tvo_real_t tvo_tick_time_seconds(const tvo_tick_time_t *t, uint32_t tick_hz);

/** Seconds of a short tick count (a period, a measurement's age): 32-bit arithmetic. */
tvo_real_t tvo_ticks_to_seconds32(uint32_t ticks, uint32_t tick_hz);

/**
 * Begins the period whose command applies at apply_tick: its timing record (elapsed time, periods
 * since the last one). TVO_ERR_TICK_NOT_ADVANCING if apply_tick does not advance (TVO_ERR_BEFORE_EPOCH if it
 * precedes the epoch on the first call); the clock is not changed until tvo_sample_clock_end.
 */
tvo_status_t tvo_sample_clock_begin(const tvo_sample_clock_t *clock, uint32_t apply_tick, tvo_period_t *period);

/**
 * Where this period's law is evaluated, for a measurement stamped stamp_tick (already checked):
 * at the sample (no compensation), at the application instant (delay compensation), and half a
 * period later when ZOH-aware (the middle of the held interval). Fills the period's age, law_time
 * and carry_s (the state's carry: the age if compensating, plus half a period if ZOH-aware).
 */
tvo_status_t tvo_sample_clock_locate(const tvo_sample_clock_t *clock, tvo_period_t *period, uint32_t stamp_tick,
                                     uint8_t delay_compensation, uint8_t zoh_aware);

/**
 * Ends a begun period: with good = 1 a step used stamp_tick (recorded; the watchdog restarts);
 * with good = 0 nothing usable arrived (stamp_tick ignored). Returns 1 when the watchdog has
 * expired (stop the plant).
 */
int tvo_sample_clock_end(tvo_sample_clock_t *clock, const tvo_period_t *period, int good, uint32_t stamp_tick);

/**
 * A stamp is usable for the command applied at apply_tick when it is not after it
 * (TVO_ERR_FUTURE_STAMP), at most one period before it (TVO_ERR_STALE) and newer than the last
 * accepted stamp (TVO_ERR_STAMP_NOT_NEWER).
 */
tvo_status_t tvo_sample_clock_check_stamp(const tvo_sample_clock_t *clock, uint32_t stamp_tick, uint32_t apply_tick);

/**
 * Ticks from the epoch to a tick near the clock's present (within TVO_MAX_TICK_SPAN either way):
 * the objective time of a stamp. TVO_ERR_BEFORE_EPOCH if it lies before the epoch.
 */
tvo_status_t tvo_sample_clock_objective_ticks(const tvo_sample_clock_t *clock, uint32_t tick, uint64_t *objective_ticks);

/**
 * Moves the epoch before the first period has ended (an edge that learned the plant's clock better);
 * TVO_ERR_CLOCK_STARTED once a period has ended, when the objective's time is already counting.
 */
tvo_status_t tvo_sample_clock_rebase(tvo_sample_clock_t *clock, uint32_t epoch_tick);

/** Expires the watchdog now (a safe stop ordered from outside the step, e.g. the edge's timer). */
tvo_status_t tvo_sample_clock_expire(tvo_sample_clock_t *clock);

#ifdef __cplusplus
}
#endif

#endif /* TVO_SAMPLE_CLOCK_H */
