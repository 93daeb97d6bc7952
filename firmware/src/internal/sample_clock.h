/*
 * Internal: the sample clock's functions (the types are in tvo/sample_clock.h: the controllers hold them).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds). The arithmetic of
 * a period is inline, for the controllers' steps (their own clock and period records).
 */
#ifndef TVO_INTERNAL_SAMPLE_CLOCK_H
#define TVO_INTERNAL_SAMPLE_CLOCK_H

#include "tvo/sample_clock.h"
#include "internal/assert.h"
#include "tvo/objective.h" /* tvo_time_jet_t */

#ifdef __cplusplus
extern "C" {
#endif

/**
 * The timing parameters every controller validates: TVO_PARAM_TICK_HZ (zero), TVO_PARAM_PERIOD
 * (zero or beyond TVO_MAX_TICK_SPAN), TVO_PARAM_DELAY (beyond the period), or TVO_PARAM_NONE.
 */
tvo_param_t tvo_sample_clock_check_timing(uint32_t tick_hz, uint32_t period_ticks, uint32_t delay_ticks);

/** 1 if watchdog_periods >= 1 and the watchdog's span stays within TVO_MAX_TICK_SPAN ticks. */
int tvo_sample_clock_watchdog_ok(uint32_t period_ticks, uint32_t watchdog_periods);

/** A clock at the epoch, before its first period; the timing and watchdog must pass the two checks above.
 *  counts_refusals 1: watchdog_periods refusals in a row expire the watchdog as periods do (no timer). */
void tvo_sample_clock_init(tvo_sample_clock_t *clock, uint32_t tick_hz, uint32_t period_ticks, uint32_t watchdog_periods,
                           uint8_t counts_refusals, uint32_t epoch_tick);

/** Seconds of a short tick count (a period, a measurement's age): 32-bit arithmetic. */
tvo_real_t tvo_ticks_to_seconds32(uint32_t ticks, uint32_t tick_hz);

/**
 * Ticks from the epoch to a tick near the clock's present (within TVO_MAX_TICK_SPAN either way):
 * the objective time of a stamp. TVO_ERR_BEFORE_EPOCH if it lies before the epoch.
 */
tvo_status_t tvo_sample_clock_objective_ticks(const tvo_sample_clock_t *clock, uint32_t tick, uint64_t *objective_ticks);

/**
 * Ends a begun period without a good step, or counts a refused measurement: 1 when the robots stop (the
 * watchdog has expired). measured 0: a period without a measurement, counted (watchdog_periods of them
 * in a row expire the watchdog). measured 1: a refused measurement, which commits only what stops: on a
 * clock that counts refusals, the watchdog_periods-th in a row (and every one after it); or its period,
 * if counting it would expire the watchdog (period NULL: it has none, tvo_*_refuse). A good step's
 * period ends with sample_clock_end_good.
 */
int tvo_sample_clock_refuse(tvo_sample_clock_t *clock, const tvo_period_t *period, int measured);

static inline tvo_tick_time_t tick_time_after(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz)
{
    tvo_tick_time_t out = *t;
    out.ticks += delta_ticks;
    out.whole_s += delta_ticks / tick_hz;
    out.frac_ticks += delta_ticks % tick_hz;
    if (out.frac_ticks >= tick_hz) {
        out.frac_ticks -= tick_hz;
        out.whole_s += 1u;
    }
    return out;
}

static inline tvo_tick_time_t tick_time_before(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz)
{
    tvo_tick_time_t out = {0u, 0u, 0u};
    if ((uint64_t)delta_ticks >= t->ticks) {
        return out;
    }
    out.ticks = t->ticks - delta_ticks;
    const uint32_t whole = delta_ticks / tick_hz;
    const uint32_t frac = delta_ticks % tick_hz;
    out.whole_s = t->whole_s - whole;
    if (t->frac_ticks >= frac) {
        out.frac_ticks = t->frac_ticks - frac;
    } else {
        out.frac_ticks = t->frac_ticks + (tick_hz - frac);
        out.whole_s -= 1u; /* cannot go below 0: ticks > delta */
    }
    return out;
}

static inline tvo_real_t tick_time_seconds(const tvo_tick_time_t *t, uint32_t tick_hz)
{
    return (tvo_real_t)t->whole_s + (tvo_real_t)t->frac_ticks / (tvo_real_t)tick_hz;
}

/* ticks_to_seconds32 at a clock's rate (tick_hz > 0: init validated it). */
static inline tvo_real_t clock_ticks_to_seconds(uint32_t ticks, uint32_t tick_hz)
{
    TVO_ASSERT(tick_hz > 0u);
    if (ticks < tick_hz) {
        return (tvo_real_t)ticks / (tvo_real_t)tick_hz; /* the same: no whole second to add (an age, a period) */
    }
    /* Whole seconds and the rest separately, so only the final sum rounds. */
    return (tvo_real_t)(ticks / tick_hz) + (tvo_real_t)(ticks % tick_hz) / (tvo_real_t)tick_hz;
}

static inline tvo_real_t ticks_to_seconds32(uint32_t ticks, uint32_t tick_hz)
{
    return (tick_hz == 0u) ? TVO_R(0.0) : clock_ticks_to_seconds(ticks, tick_hz);
}

static inline tvo_status_t sample_clock_begin(const tvo_sample_clock_t *clock, uint32_t apply_tick,
                                              tvo_period_t *period)
{
    period->apply_tick = apply_tick;
    period->periods = 1u;
    if (!clock->started) {
        const uint32_t since_epoch = apply_tick - clock->epoch_tick;
        if (since_epoch > TVO_MAX_TICK_SPAN) {
            return TVO_ERR_BEFORE_EPOCH; /* first application before the epoch */
        }
        const tvo_tick_time_t epoch = {0u, 0u, 0u};
        period->elapsed = tick_time_after(&epoch, since_epoch, clock->tick_hz);
        return TVO_OK;
    }
    const uint32_t advance = apply_tick - clock->last_apply_tick;
    if (advance == 0u || advance > TVO_MAX_TICK_SPAN) {
        return TVO_ERR_TICK_NOT_ADVANCING;
    }
    period->elapsed = tick_time_after(&clock->elapsed, advance, clock->tick_hz);
    if (advance / clock->period_ticks > 1u) {
        period->periods = advance / clock->period_ticks;
    }
    return TVO_OK;
}

static inline void sample_clock_locate(const tvo_sample_clock_t *clock, tvo_period_t *period, uint32_t stamp_tick,
                                       uint8_t delay_compensation, uint8_t zoh_aware)
{
    const uint32_t hz = clock->tick_hz;
    period->age_ticks = period->apply_tick - stamp_tick;
    period->age_s = clock_ticks_to_seconds(period->age_ticks, hz);
    period->law_time = delay_compensation ? period->elapsed : tick_time_before(&period->elapsed, period->age_ticks, hz);
    period->carry_s = delay_compensation ? period->age_s : TVO_R(0.0);
    if (zoh_aware) {
        period->law_time = tick_time_after(&period->law_time, clock->period_ticks / 2u, hz);
        period->carry_s += TVO_R(0.5) * clock_ticks_to_seconds(clock->period_ticks, hz);
    }
}

/* The stamp rules of a measurement applied at apply_tick: TVO_REASON_NONE when accepted, else the
 * period's reason (the loop holds for it as it is). */
static inline tvo_reason_t sample_clock_check_stamp(const tvo_sample_clock_t *clock, uint32_t stamp_tick,
                                                    uint32_t apply_tick)
{
    const uint32_t age = apply_tick - stamp_tick;
    if (age > TVO_MAX_TICK_SPAN) {
        return TVO_REASON_FUTURE_STAMP; /* negative age in wrap-around arithmetic */
    }
    if (age > clock->period_ticks) {
        return TVO_REASON_STALE;
    }
    if (clock->has_stamp) {
        const uint32_t advance = stamp_tick - clock->last_stamp_tick;
        if (advance == 0u || advance > TVO_MAX_TICK_SPAN) {
            return TVO_REASON_STAMP_NOT_NEWER;
        }
    }
    return TVO_REASON_NONE;
}

/* A refused step commits nothing unless counting its period would expire the watchdog: then the period
 * is counted and the robots stop. */
static inline int sample_clock_refusal_stops(const tvo_sample_clock_t *clock, const tvo_period_t *period)
{
    return clock->stopped || period->periods >= clock->watchdog_periods - clock->periods_without_measurement;
}

/* The period's application instant becomes the clock's present. */
static inline void sample_clock_end_period(tvo_sample_clock_t *clock, const tvo_period_t *period)
{
    clock->started = 1;
    clock->last_apply_tick = period->apply_tick;
    clock->elapsed = period->elapsed;
}

/* A period with a good step ends: stamp_tick is recorded and the watchdog restarts. The watchdog's
 * count after a period without one is tvo_sample_clock_refuse's. */
static inline void sample_clock_end_good(tvo_sample_clock_t *clock, const tvo_period_t *period, uint32_t stamp_tick)
{
    sample_clock_end_period(clock, period);
    clock->last_stamp_tick = stamp_tick;
    clock->has_stamp = 1;
    clock->periods_without_measurement = 0;
    clock->refusals_in_row = 0;
    clock->stopped = 0;
}

/* The watchdog expired now (a stop ordered from outside the period, or a refusal that stops): the
 * count full, the robots stopped until a good step. */
static inline void sample_clock_expire(tvo_sample_clock_t *clock)
{
    clock->periods_without_measurement = clock->watchdog_periods;
    clock->stopped = 1;
}

/* A refused measurement counted (a clock that counts refusals only): 1 when watchdog_periods refusals
 * in a row have expired the watchdog, as that many periods would. */
static inline int sample_clock_count_refusal(tvo_sample_clock_t *clock)
{
    if (!clock->counts_refusals) {
        return 0;
    }
    if (clock->refusals_in_row < UINT32_MAX) {
        clock->refusals_in_row++;
    }
    return clock->refusals_in_row >= clock->watchdog_periods;
}

/* The objective's time at a tick time of the clock (frac_ticks < tick_hz, tick_hz > 0); t's shared values
 * are left to the caller (the controllers' time jet is their law's, which sets them). */
static inline void time_jet_at_tick_time(const tvo_tick_time_t *time, uint32_t tick_hz, tvo_real_t rate,
                                         tvo_time_jet_t *t)
{
    t->ticks = time->ticks;
    t->tick_hz = tick_hz;
    t->whole_s = time->whole_s;
    t->frac_ticks = time->frac_ticks;
    t->frac_s = (tvo_real_t)time->frac_ticks / (tvo_real_t)tick_hz;
    t->t_s = (tvo_real_t)time->whole_s + t->frac_s; /* tick_time_seconds */
    t->rate = rate;
}

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_SAMPLE_CLOCK_H */
