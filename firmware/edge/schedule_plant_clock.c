/*
 * CLOCK_PLANT (lockstep): the plant's stamps are the schedule's clock; see schedule.h and lcm_types/README.md
 * ("Timing", "The watchdog"). A sample stamped s serves the period whose apply instant is nearest
 * s + tau; the first accepted sample anchors the numbering, and later ones must advance sequence and
 * period alike. With no clock of its own the node has no timer.
 * A sample more than watchdog_periods periods ahead of the last accepted one is a jump: a plant's clock
 * fault or a stray, refused until TVO_SCHEDULE_ANCHOR_VOTES samples in a row agree on it (a genuine
 * stream after a silence longer than the watchdog's span). One wild sample costs its own refusal, not
 * the periods it jumped. With no timer, the core counts refusals for its watchdog (the session's
 * configuration says so: watchdog_counts_refusals).
 */
#include "schedule.h"

#include "tvo/sample_clock.h"

/* The first sample must be stamped within this long after the later of the START and the epoch (or
 * within watchdog_periods periods, if longer). */
#define PLANT_FIRST_SAMPLE_WINDOW_US 1000000

/* From the epoch to stamp + tau, plus half a period, so that its quotient by h is the period whose
 * apply instant is nearest (negative: before the epoch). Wire times: no overflow. */
static int64_t to_apply_us(const tvo_schedule_t *schedule, int64_t stamp_us)
{
    return stamp_us + schedule->timing.delay_us - schedule->anchor.epoch_schedule_us + schedule->timing.period_us / 2;
}

/* What the node knows of the plant's clock before the first accepted sample: the later of the START
 * (or its repeat, or the samples' vote) and the epoch. */
static int64_t first_sample_anchor(const tvo_schedule_t *schedule)
{
    const int64_t window = schedule->anchor.first_window_utime;
    return window > schedule->anchor.epoch_schedule_us ? window : schedule->anchor.epoch_schedule_us;
}

/* ... and the latest stamp a first sample may carry. */
static int64_t first_sample_deadline(const tvo_schedule_t *schedule)
{
    const int64_t watchdog_us = (int64_t)schedule->timing.watchdog_periods * schedule->timing.period_us;
    const int64_t window = watchdog_us > PLANT_FIRST_SAMPLE_WINDOW_US ? watchdog_us : PLANT_FIRST_SAMPLE_WINDOW_US;
    return first_sample_anchor(schedule) + window; /* a wire time and at most 2^30 us: no overflow */
}

/* A first sample's period must lie within the controller's clock span of the epoch. */
static int within_tick_span(const tvo_schedule_t *schedule, int64_t period)
{
    return period * schedule->timing.period_us <= (int64_t)TVO_MAX_TICK_SPAN;
}

static void plant_start(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg, int64_t now_us)
{
    (void)now_us; /* the plant's stamps are the clock */
    schedule->anchor.offset_us = 0;
    schedule->anchor.epoch_schedule_us = schedule->timing.epoch_utime;
    schedule->anchor.first_window_utime = msg->utime;
}

static void plant_repeat_start(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg)
{
    /* Stamped with the plant's clock now (a utime a fresh START could have): the first sample's
     * window opens from it. */
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    if (!schedule->has_accepted && msg->utime > schedule->anchor.first_window_utime &&
        tvo_session_decode_timing(msg, &timing, &why) == TVO_OK) {
        schedule->anchor.first_window_utime = msg->utime;
    }
}

static tvo_node_status_t plant_place(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us,
                                tvo_schedule_placement_t *placement)
{
    (void)now_us;
    placement->stamp_us = msg->utime;
    const int64_t to_apply = to_apply_us(schedule, placement->stamp_us);
    if (to_apply < 0) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* before the epoch */
    }
    placement->period = to_apply / schedule->timing.period_us;
    if (!schedule->has_accepted) {
        /* The first sample anchors the numbering: it must follow the START (or the epoch) closely, or a
         * stray from far ahead would anchor it. */
        return (placement->stamp_us <= first_sample_deadline(schedule) && within_tick_span(schedule, placement->period))
                   ? TVO_NODE_OK
                   : TVO_NODE_IMPLAUSIBLE_STAMP;
    }
    if (placement->period <= schedule->last_period) {
        return TVO_NODE_NOT_LATER_PERIOD; /* a duplicate, or older than the last accepted */
    }
    if (msg->sequence - schedule->anchor.last_sequence != placement->period - schedule->last_period) {
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* stamp and sequence disagree: a stray, or a wild number */
    }
    const int64_t jump = placement->period - schedule->last_period;
    if (jump > (int64_t)schedule->timing.watchdog_periods && !schedule->anchor.jump_agreed &&
        jump <= (int64_t)TVO_MAX_TICK_SPAN / schedule->timing.period_us) { /* beyond: stale, for the caller to say */
        return TVO_NODE_IMPLAUSIBLE_STAMP; /* a jump past the watchdog's span: served once samples agree */
    }
    return TVO_NODE_OK;
}

static void plant_accepted(tvo_schedule_t *schedule, const tvo_schedule_placement_t *placement)
{
    (void)placement;
    schedule->anchor.jump_agreed = 0u;
}

/* A sample no newer than one the node has already seen of its stream: at or before the last accepted
 * period (or before the epoch, once tracking), or, agreeing with the running vote's numbering, at or
 * before its last voter's period (a copy of a voter). It neither votes nor ends the vote: samples
 * "in a row" are the stream's new ones, so a flood of copies cannot hold back its recovery. */
static int plant_late(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t to_apply,
                      int64_t period)
{
    if (schedule->has_accepted && (to_apply < 0 || period <= schedule->last_period)) {
        return 1;
    }
    return schedule->votes > 0u && msg->sequence - period == schedule->vote_value &&
           period <= schedule->clock.plant.vote_period;
}

/*
 * Samples that agree on their own numbering, TVO_SCHEDULE_ANCHOR_VOTES in a row, move the anchor: while
 * tracking, a stray taken as the anchor of the numbering (it came first, or its stamp and sequence
 * happened to agree) is replaced by the genuine stream's; before tracking, samples past the first
 * window move the window to the last of them (a plant that could not be served within it, its
 * robot inside an obstacle or its target stream late, is not refused for ever).
 */
static int plant_vote(tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, const tvo_step_why_t *refusal, int64_t now_us,
                      tvo_schedule_anchor_t *moved)
{
    (void)now_us;
    *moved = schedule->anchor;
    const int in_range = tvo_schedule_wire_time_ok(msg->utime) && tvo_schedule_wire_time_ok(msg->sequence);
    if (!in_range) {
        schedule->votes = 0u;
        return 0;
    }
    const int64_t to_apply = to_apply_us(schedule, msg->utime); /* in range */
    const int64_t period = to_apply / schedule->timing.period_us;
    if (plant_late(schedule, msg, to_apply, period)) {
        return 0; /* late or repeated (a queue flushing): no vote; its refusal counts in the streak */
    }
    if (refusal->node != TVO_NODE_IMPLAUSIBLE_STAMP) {
        schedule->votes = 0u;
        return 0;
    }
    const int votes = to_apply >= 0 && (schedule->has_accepted ? period > schedule->last_period
                                                                : msg->utime > first_sample_deadline(schedule) &&
                                                                      within_tick_span(schedule, period));
    if (!votes) {
        schedule->votes = 0u;
        return 0;
    }
    schedule->clock.plant.vote_period = period;
    if (!tvo_schedule_vote(schedule, msg->sequence - period, 0)) {
        return 0;
    }
    if (schedule->has_accepted) {
        moved->last_sequence = msg->sequence - (period - schedule->last_period); /* the samples' own numbering */
        moved->jump_agreed = 1u;                                                  /* and their period */
    } else {
        moved->first_window_utime = msg->utime; /* the first window opens at the plant's samples */
    }
    return 1;
}

static int64_t plant_refusal_utime(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us)
{
    (void)schedule;
    (void)now_us;
    return tvo_schedule_clamp_time(msg->utime);
}

/* The apply instant of the period after the last accepted one; before the first, after the one a
 * sample stamped at the first sample's anchor would serve (a wire time no earlier than the epoch). */
static int64_t plant_latest_target_us(const tvo_schedule_t *schedule, int64_t now_us)
{
    (void)now_us;
    const int64_t period = schedule->has_accepted
                               ? schedule->last_period
                               : to_apply_us(schedule, first_sample_anchor(schedule)) / schedule->timing.period_us;
    return tvo_schedule_apply_us(schedule, period + 1);
}

static int plant_take_missed(tvo_schedule_t *schedule, int64_t now_us, int64_t *period)
{
    (void)schedule;
    (void)now_us;
    *period = 0;
    return 0; /* no timer: the node acts only when a sample arrives */
}

static int64_t plant_next_deadline(const tvo_schedule_t *schedule)
{
    (void)schedule;
    return TVO_SCHEDULE_NO_DEADLINE;
}

static int64_t plant_telemetry_node_time_us(int64_t now_us)
{
    (void)now_us;
    return 0;
}

const tvo_schedule_ops_t tvo_schedule_plant_clock = TVO_SCHEDULE_OPS(plant, TVO_LCM_SESSION_T_CLOCK_PLANT);
