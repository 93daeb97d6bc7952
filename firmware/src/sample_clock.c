/* Sampled-data timing shared by the controllers; see internal/sample_clock.h. */
#include "internal/sample_clock.h"

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

void tvo_sample_clock_init(tvo_sample_clock_t *clock, uint32_t tick_hz, uint32_t period_ticks, uint32_t watchdog_periods,
                           uint8_t counts_refusals, uint32_t epoch_tick)
{
    TVO_ASSERT(clock != NULL);
    TVO_ASSERT(tvo_sample_clock_check_timing(tick_hz, period_ticks, 0u) == TVO_PARAM_NONE);
    TVO_ASSERT(tvo_sample_clock_watchdog_ok(period_ticks, watchdog_periods));
    memset(clock, 0, sizeof(*clock));
    clock->tick_hz = tick_hz;
    clock->period_ticks = period_ticks;
    clock->watchdog_periods = watchdog_periods;
    clock->epoch_tick = epoch_tick;
    clock->counts_refusals = counts_refusals;
}

tvo_real_t tvo_ticks_to_seconds32(uint32_t ticks, uint32_t tick_hz)
{
    return ticks_to_seconds32(ticks, tick_hz);
}


int tvo_sample_clock_refuse(tvo_sample_clock_t *clock, const tvo_period_t *period, int measured)
{
    TVO_ASSERT(clock != NULL && (period != NULL || measured));
    const int streak_stops = measured && sample_clock_count_refusal(clock);
    const int counted = period != NULL && (!measured || sample_clock_refusal_stops(clock, period));
    if (counted) {
        sample_clock_end_period(clock, period);
        /* Each below 2^30 (TVO_MAX_TICK_SPAN): no overflow; the expiry caps the count however long the outage. */
        clock->periods_without_measurement += period->periods;
    }
    const int stops = streak_stops || (counted && clock->periods_without_measurement >= clock->watchdog_periods);
    if (stops) {
        sample_clock_expire(clock);
    }
    return stops;
}

tvo_status_t tvo_sample_clock_objective_ticks(const tvo_sample_clock_t *clock, uint32_t tick, uint64_t *objective_ticks)
{
    TVO_ASSERT(clock != NULL && objective_ticks != NULL);
    const uint32_t ref_tick = clock->started ? clock->last_apply_tick : clock->epoch_tick;
    const uint64_t ref_elapsed = clock->started ? clock->elapsed.ticks : 0u;
    const uint32_t forward = tick - ref_tick;
    if (forward <= TVO_MAX_TICK_SPAN) {
        *objective_ticks = ref_elapsed + forward;
        return TVO_OK;
    }
    const uint32_t backward = ref_tick - tick;
    if ((uint64_t)backward > ref_elapsed) {
        return TVO_ERR_BEFORE_EPOCH; /* before the epoch */
    }
    *objective_ticks = ref_elapsed - backward;
    return TVO_OK;
}
