/* What both clock modes of the node's schedule share; see schedule.h. */
#include "schedule.h"

#include <string.h>

#include "tvo/sample_clock.h"

const tvo_schedule_ops_t *tvo_schedule_ops(int32_t clock_source)
{
    switch (clock_source) {
    case TVO_LCM_SESSION_T_CLOCK_PLANT: return &tvo_schedule_plant_clock;
    case TVO_LCM_SESSION_T_CLOCK_NODE: return &tvo_schedule_node_clock;
    default: return NULL;
    }
}

int tvo_schedule_wire_time_ok(int64_t t)
{
    return t >= 0 && t <= TVO_WIRE_TIME_MAX_US;
}

int64_t tvo_schedule_clamp_time(int64_t t)
{
    return t < 0 ? 0 : (t > TVO_WIRE_TIME_MAX_US ? TVO_WIRE_TIME_MAX_US : t);
}

void tvo_schedule_start(tvo_schedule_t *schedule, const tvo_schedule_ops_t *ops, const tvo_session_timing_t *timing,
                        const tvo_lcm_session_t *msg, int64_t now_us)
{
    memset(schedule, 0, sizeof(*schedule));
    schedule->ops = ops;
    schedule->timing = *timing;
    ops->start(schedule, msg, now_us);
}

int64_t tvo_schedule_apply_us(const tvo_schedule_t *schedule, int64_t period)
{
    return schedule->anchor.epoch_schedule_us + period * schedule->timing.period_us;
}

uint32_t tvo_schedule_tick(const tvo_schedule_t *schedule, int64_t schedule_us)
{
    return (uint32_t)(uint64_t)(schedule_us - schedule->anchor.offset_us);
}

int64_t tvo_schedule_plant_utime(const tvo_schedule_t *schedule, int64_t schedule_us)
{
    return tvo_schedule_clamp_time(schedule_us - schedule->anchor.offset_us);
}

tvo_node_status_t tvo_schedule_place(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us,
                                tvo_schedule_placement_t *placement)
{
    memset(placement, 0, sizeof(*placement));
    if (!tvo_schedule_wire_time_ok(msg->utime) || !tvo_schedule_wire_time_ok(msg->sequence)) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* only wire-range-checked values enter the arithmetic */
    }
    const tvo_node_status_t st = schedule->ops->place(schedule, msg, now_us, placement);
    if (st != TVO_NODE_OK) {
        return st;
    }
    placement->apply_us = tvo_schedule_apply_us(schedule, placement->period);
    if (!tvo_schedule_wire_time_ok(placement->apply_us - schedule->anchor.offset_us)) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* its command could not be stamped on the wire */
    }
    if (placement->apply_us - placement->stamp_us > (int64_t)TVO_MAX_TICK_SPAN) {
        return TVO_NODE_STALE; /* older than the controller's ticks span: as uint32 it could look fresh */
    }
    if (schedule->has_accepted &&
        (placement->period - schedule->last_period) > (int64_t)TVO_MAX_TICK_SPAN / schedule->timing.period_us) {
        return TVO_NODE_STALE; /* a silence longer than the clock spans: START a new session */
    }
    return TVO_NODE_OK;
}

void tvo_schedule_accept(tvo_schedule_t *schedule, const tvo_schedule_placement_t *placement, int64_t sequence)
{
    schedule->has_accepted = 1;
    schedule->last_period = placement->period;
    schedule->anchor.last_sequence = sequence;
    schedule->votes = 0u; /* votes count refusals in a row: a served sample ends a streak of strays */
    schedule->ops->accepted(schedule, placement);
}

int tvo_schedule_vote(tvo_schedule_t *schedule, int64_t value, int64_t tolerance)
{
    const int64_t gap = value - schedule->vote_value;
    if (schedule->votes == 0u || gap > tolerance || gap < -tolerance) {
        schedule->vote_value = value;
        schedule->votes = 1u;
        return 0;
    }
    if (++schedule->votes < TVO_SCHEDULE_ANCHOR_VOTES) {
        return 0;
    }
    schedule->votes = 0u;
    return 1;
}
