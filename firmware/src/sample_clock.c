/* Sampled-data timing shared by the controllers; see tvo/sample_clock.h. */
#include "tvo/sample_clock.h"

#include <string.h>

tvo_param_t tvo_sample_clock_check_timing(uint32_t tick_hz, uint32_t period_ticks, uint32_t delay_ticks)
{
    if (tick_hz == 0u) {
        return TVO_PARAM_TICK_HZ;
    }
    if (period_ticks == 0u || period_ticks > TVO_MAX_TICK_SPAN) {
        return TVO_PARAM_PERIOD;
    }
    if (delay_ticks > period_ticks) {
        return TVO_PARAM_DELAY;
    }
    return TVO_PARAM_NONE;
}

int tvo_sample_clock_watchdog_ok(uint32_t period_ticks, uint32_t watchdog_periods)
{
    return period_ticks > 0u && watchdog_periods >= 1u && watchdog_periods <= TVO_MAX_TICK_SPAN / period_ticks;
}

tvo_status_t tvo_sample_clock_init(tvo_sample_clock_t *clock, uint32_t tick_hz, uint32_t period_ticks,
                                   uint32_t watchdog_periods, uint32_t epoch_tick)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    memset(clock, 0, sizeof(*clock));
    if (tvo_sample_clock_check_timing(tick_hz, period_ticks, 0u) != TVO_PARAM_NONE ||
        !tvo_sample_clock_watchdog_ok(period_ticks, watchdog_periods)) {
        return TVO_ERR_PARAM;
    }
    clock->tick_hz = tick_hz;
    clock->period_ticks = period_ticks;
    clock->watchdog_periods = watchdog_periods;
    clock->epoch_tick = epoch_tick;
    return TVO_OK;
}

tvo_tick_time_t tvo_tick_time_after(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz)
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

tvo_tick_time_t tvo_tick_time_before(const tvo_tick_time_t *t, uint32_t delta_ticks, uint32_t tick_hz)
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

tvo_real_t tvo_tick_time_seconds(const tvo_tick_time_t *t, uint32_t tick_hz)
{
    return (tvo_real_t)t->whole_s + (tvo_real_t)t->frac_ticks / (tvo_real_t)tick_hz;
}

tvo_real_t tvo_ticks_to_seconds32(uint32_t ticks, uint32_t tick_hz)
{
    if (tick_hz == 0u) {
        return TVO_R(0.0);
    }
    /* Whole seconds and the rest separately, so only the final sum rounds. */
    return (tvo_real_t)(ticks / tick_hz) + (tvo_real_t)(ticks % tick_hz) / (tvo_real_t)tick_hz;
}

tvo_status_t tvo_sample_clock_begin(const tvo_sample_clock_t *clock, uint32_t apply_tick, tvo_period_t *period)
{
    if (clock == NULL || period == NULL) {
        return TVO_ERR_NULL;
    }
    period->apply_tick = apply_tick;
    period->periods = 1u;
    if (!clock->started) {
        const uint32_t since_epoch = apply_tick - clock->epoch_tick;
        if (since_epoch > TVO_MAX_TICK_SPAN) {
            return TVO_ERR_OUT_OF_ORDER; /* first application before the epoch */
        }
        const tvo_tick_time_t epoch = {0u, 0u, 0u};
        period->elapsed = tvo_tick_time_after(&epoch, since_epoch, clock->tick_hz);
        return TVO_OK;
    }
    const uint32_t advance = apply_tick - clock->last_apply_tick;
    if (advance == 0u || advance > TVO_MAX_TICK_SPAN) {
        return TVO_ERR_OUT_OF_ORDER;
    }
    period->elapsed = tvo_tick_time_after(&clock->elapsed, advance, clock->tick_hz);
    if (advance / clock->period_ticks > 1u) {
        period->periods = advance / clock->period_ticks;
    }
    return TVO_OK;
}

tvo_status_t tvo_sample_clock_locate(const tvo_sample_clock_t *clock, tvo_period_t *period, uint32_t stamp_tick,
                                     uint8_t delay_compensation, uint8_t zoh_aware)
{
    if (clock == NULL || period == NULL) {
        return TVO_ERR_NULL;
    }
    const uint32_t hz = clock->tick_hz;
    period->age_ticks = period->apply_tick - stamp_tick;
    period->age_s = tvo_ticks_to_seconds32(period->age_ticks, hz);
    period->law_time = delay_compensation ? period->elapsed : tvo_tick_time_before(&period->elapsed, period->age_ticks, hz);
    period->carry_s = delay_compensation ? period->age_s : TVO_R(0.0);
    if (zoh_aware) {
        period->law_time = tvo_tick_time_after(&period->law_time, clock->period_ticks / 2u, hz);
        period->carry_s += TVO_R(0.5) * tvo_ticks_to_seconds32(clock->period_ticks, hz);
    }
    return TVO_OK;
}

tvo_status_t tvo_sample_clock_check_stamp(const tvo_sample_clock_t *clock, uint32_t stamp_tick, uint32_t apply_tick)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    const uint32_t age = apply_tick - stamp_tick;
    if (age > TVO_MAX_TICK_SPAN) {
        return TVO_ERR_FUTURE_STAMP; /* negative age in wrap-around arithmetic */
    }
    if (age > clock->period_ticks) {
        return TVO_ERR_STALE;
    }
    if (clock->has_stamp) {
        const uint32_t advance = stamp_tick - clock->last_stamp_tick;
        if (advance == 0u || advance > TVO_MAX_TICK_SPAN) {
            return TVO_ERR_OUT_OF_ORDER;
        }
    }
    return TVO_OK;
}

/* The period's application instant becomes the clock's present. */
static void end_period(tvo_sample_clock_t *clock, const tvo_period_t *period)
{
    clock->started = 1;
    clock->last_apply_tick = period->apply_tick;
    clock->elapsed = period->elapsed;
}

int tvo_sample_clock_end(tvo_sample_clock_t *clock, const tvo_period_t *period, int good, uint32_t stamp_tick)
{
    if (clock == NULL || period == NULL) {
        return 1;
    }
    end_period(clock, period);
    if (good) {
        clock->last_stamp_tick = stamp_tick;
        clock->has_stamp = 1;
        clock->periods_without_measurement = 0;
        clock->stopped = 0;
        return 0;
    }
    /* Saturating count: no overflow however long the outage. */
    const uint32_t room = clock->watchdog_periods - clock->periods_without_measurement;
    clock->periods_without_measurement =
        (period->periods >= room) ? clock->watchdog_periods : clock->periods_without_measurement + period->periods;
    if (clock->periods_without_measurement >= clock->watchdog_periods) {
        clock->stopped = 1;
    }
    return clock->stopped;
}

tvo_status_t tvo_sample_clock_rebase(tvo_sample_clock_t *clock, uint32_t epoch_tick)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    if (clock->started) {
        return TVO_ERR_OUT_OF_ORDER;
    }
    clock->epoch_tick = epoch_tick;
    return TVO_OK;
}

tvo_status_t tvo_sample_clock_expire(tvo_sample_clock_t *clock)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    clock->periods_without_measurement = clock->watchdog_periods;
    clock->stopped = 1;
    return TVO_OK;
}

tvo_status_t tvo_sample_clock_objective_ticks(const tvo_sample_clock_t *clock, uint32_t tick, uint64_t *objective_ticks)
{
    if (clock == NULL || objective_ticks == NULL) {
        return TVO_ERR_NULL;
    }
    const uint32_t ref_tick = clock->started ? clock->last_apply_tick : clock->epoch_tick;
    const uint64_t ref_elapsed = clock->started ? clock->elapsed.ticks : 0u;
    const uint32_t forward = tick - ref_tick;
    if (forward <= TVO_MAX_TICK_SPAN) {
        *objective_ticks = ref_elapsed + forward;
        return TVO_OK;
    }
    const uint32_t backward = ref_tick - tick;
    if ((uint64_t)backward > ref_elapsed) {
        return TVO_ERR_OUT_OF_ORDER; /* before the epoch */
    }
    *objective_ticks = ref_elapsed - backward;
    return TVO_OK;
}
