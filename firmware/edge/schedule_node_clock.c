/*
 * CLOCK_NODE (real time): the node's own monotonic clock runs the schedule; see schedule.h and
 * lcm_types/README.md ("Timing", "The watchdog"). The START maps the plant's clock onto the node's; a sample
 * serves the first period after its arrival that was not served; a timer hands every period that
 * passes without one to the core's watchdog (tvo_controller_miss), which alone decides the stop.
 */
#include "schedule.h"

#include "tvo/sample_clock.h"

/* A stamp may lead the node's clock by at most half a period (clock offset, jitter). */
#define NODE_FUTURE_TOLERANCE_DIVISOR 2
/* Refused samples re-anchor the offset when they agree on the plant's clock within a quarter period. */
#define NODE_ANCHOR_AGREEMENT_DIVISOR 4

/* Period index of node time t: the smallest j >= 0 with epoch + j h > t (the next apply instant). */
static int64_t next_period_after(const tvo_schedule_t *schedule, int64_t t_us)
{
    const int64_t since = t_us - schedule->anchor.epoch_schedule_us;
    return since < 0 ? 0 : since / schedule->timing.period_us + 1;
}

static void node_start(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg, int64_t now_us)
{
    /* The START's arrival maps the plant's clock onto the node's (its transit counts as age). Both
     * times are within the wire range, so nothing here can overflow. */
    schedule->anchor.offset_us = now_us - msg->utime;
    schedule->anchor.epoch_schedule_us = schedule->timing.epoch_utime + schedule->anchor.offset_us;
    schedule->anchor.first_window_utime = msg->utime;
}

static void node_repeat_start(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg)
{
    (void)schedule; /* the offset comes from the START that started the session (or the samples' vote) */
    (void)msg;
}

static tvo_node_status_t node_place(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us,
                               tvo_schedule_placement_t *placement)
{
    placement->stamp_us = msg->utime + schedule->anchor.offset_us;
    if (placement->stamp_us > now_us + schedule->timing.period_us / NODE_FUTURE_TOLERANCE_DIVISOR) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* from the future by the node's own clock */
    }
    const int64_t next = next_period_after(schedule, now_us);
    placement->period = (schedule->has_accepted && next <= schedule->last_period) ? schedule->last_period + 1 : next;
    return TVO_NODE_OK; /* its age at the apply instant: the core's step judges it */
}

static void node_accepted(tvo_schedule_t *schedule, const tvo_schedule_placement_t *placement)
{
    schedule->clock.node.next_miss_period = placement->period + 1;
}

/*
 * Before tracking starts, the START's transit is taken as the offset's error, but a START can be much
 * slower than a measurement (2 kB against 0.4 kB on a serial link), which makes every measurement look
 * early (or stale) for the whole session: refused samples whose own transit, taken as zero, agree on
 * one offset, TVO_SCHEDULE_ANCHOR_VOTES in a row, re-anchor the schedule to it. Once tracking started
 * the offset is fixed (the objective's time is counting).
 */
static int node_vote(tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, const tvo_step_why_t *refusal, int64_t now_us,
                     tvo_schedule_anchor_t *moved)
{
    *moved = schedule->anchor;
    const int in_range = tvo_schedule_wire_time_ok(msg->utime) && tvo_schedule_wire_time_ok(msg->sequence);
    const int timing_refusal =
        refusal->node == TVO_NODE_IMPLAUSIBLE_STAMP || refusal->node == TVO_NODE_STALE ||
        (refusal->node == TVO_NODE_OK && refusal->error == TVO_OK &&
         (refusal->reason == TVO_REASON_STALE || refusal->reason == TVO_REASON_FUTURE_STAMP));
    if (!in_range || schedule->has_accepted || !timing_refusal) {
        schedule->votes = 0u;
        return 0;
    }
    const int64_t implied_offset_us = now_us - msg->utime;
    if (!tvo_schedule_vote(schedule, implied_offset_us, schedule->timing.period_us / NODE_ANCHOR_AGREEMENT_DIVISOR)) {
        return 0;
    }
    moved->offset_us = implied_offset_us;
    moved->epoch_schedule_us = schedule->timing.epoch_utime + implied_offset_us;
    return 1;
}

/* The measurement's stamp, or the node's now (plant clock) if later. */
static int64_t node_refusal_utime(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us)
{
    const int64_t stamp = tvo_schedule_clamp_time(msg->utime);
    const int64_t plant_now = tvo_schedule_plant_utime(schedule, now_us);
    return stamp > plant_now ? stamp : plant_now;
}

static int64_t node_latest_target_us(const tvo_schedule_t *schedule, int64_t now_us)
{
    return now_us + schedule->timing.period_us / NODE_FUTURE_TOLERANCE_DIVISOR;
}

/* The first period the core could stop the robots at: watchdog_periods after the last served one. */
static int64_t first_period_to_count(const tvo_schedule_t *schedule)
{
    const int64_t first_due = schedule->last_period + (int64_t)schedule->timing.watchdog_periods;
    const int64_t next_miss = schedule->clock.node.next_miss_period;
    return next_miss > first_due ? next_miss : first_due;
}

/* The periods since the last served one passed without a measurement. The core counts them all in one
 * call (every period since its last application) and its watchdog decides; it cannot stop the robots
 * before watchdog_periods have passed, so the node need not call it sooner. */
static int node_take_missed(tvo_schedule_t *schedule, int64_t now_us, int64_t *period)
{
    *period = next_period_after(schedule, now_us) - 1; /* the last apply instant at or before now */
    if (!schedule->has_accepted || *period < first_period_to_count(schedule)) {
        return 0;
    }
    schedule->clock.node.next_miss_period = *period + 1;
    return 1;
}

static int64_t node_next_deadline(const tvo_schedule_t *schedule)
{
    if (!schedule->has_accepted) {
        return TVO_SCHEDULE_NO_DEADLINE; /* the watchdog is armed by the first accepted measurement */
    }
    return tvo_schedule_apply_us(schedule, first_period_to_count(schedule));
}

static int64_t node_telemetry_node_time_us(int64_t now_us)
{
    return now_us;
}

const tvo_schedule_ops_t tvo_schedule_node_clock = TVO_SCHEDULE_OPS(node, TVO_LCM_SESSION_T_CLOCK_NODE);
