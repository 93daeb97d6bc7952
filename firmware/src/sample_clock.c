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

tvo_status_t tvo_sample_clock_schedule(const tvo_sample_clock_t *clock, uint32_t apply_tick, uint64_t *elapsed_ticks,
                                       uint32_t *periods)
{
    if (clock == NULL || elapsed_ticks == NULL || periods == NULL) {
        return TVO_ERR_NULL;
    }
    *periods = 1u;
    if (!clock->started) {
        const uint32_t since_epoch = apply_tick - clock->epoch_tick;
        if (since_epoch > TVO_MAX_TICK_SPAN) {
            return TVO_ERR_OUT_OF_ORDER; /* first application before the epoch */
        }
        *elapsed_ticks = since_epoch;
        return TVO_OK;
    }
    const uint32_t advance = apply_tick - clock->last_apply_tick;
    if (advance == 0u || advance > TVO_MAX_TICK_SPAN) {
        return TVO_ERR_OUT_OF_ORDER;
    }
    *elapsed_ticks = clock->elapsed_ticks + advance;
    if (clock->period_ticks > 0u && advance / clock->period_ticks > 1u) {
        *periods = advance / clock->period_ticks;
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

tvo_status_t tvo_sample_clock_accept_stamp(tvo_sample_clock_t *clock, uint32_t stamp_tick)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    clock->last_stamp_tick = stamp_tick;
    clock->has_stamp = 1;
    return TVO_OK;
}

static void end_period(tvo_sample_clock_t *clock, uint32_t apply_tick, uint64_t elapsed_ticks)
{
    clock->started = 1;
    clock->last_apply_tick = apply_tick;
    clock->elapsed_ticks = elapsed_ticks;
}

tvo_status_t tvo_sample_clock_good(tvo_sample_clock_t *clock, uint32_t apply_tick, uint64_t elapsed_ticks)
{
    if (clock == NULL) {
        return TVO_ERR_NULL;
    }
    end_period(clock, apply_tick, elapsed_ticks);
    clock->periods_without_measurement = 0;
    clock->stopped = 0;
    return TVO_OK;
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

int tvo_sample_clock_missed(tvo_sample_clock_t *clock, uint32_t apply_tick, uint64_t elapsed_ticks, uint32_t periods)
{
    if (clock == NULL) {
        return 1;
    }
    end_period(clock, apply_tick, elapsed_ticks);
    /* Saturating count: no overflow however long the outage. */
    const uint32_t room = clock->watchdog_periods - clock->periods_without_measurement;
    clock->periods_without_measurement =
        (periods >= room) ? clock->watchdog_periods : clock->periods_without_measurement + periods;
    if (clock->periods_without_measurement >= clock->watchdog_periods) {
        clock->stopped = 1;
    }
    return clock->stopped;
}

tvo_status_t tvo_sample_clock_objective_ticks(const tvo_sample_clock_t *clock, uint32_t tick, uint64_t *objective_ticks)
{
    if (clock == NULL || objective_ticks == NULL) {
        return TVO_ERR_NULL;
    }
    const uint32_t ref_tick = clock->started ? clock->last_apply_tick : clock->epoch_tick;
    const uint64_t ref_elapsed = clock->started ? clock->elapsed_ticks : 0u;
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
