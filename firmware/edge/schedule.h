/*
 * The node's schedule: which period a measurement serves, when that period's command applies, and
 * what a refusal or a silence does, on the session's clock (session_t.clock_source). Each clock mode
 * is one small object behind this interface: a const table of its functions and its own state.
 *
 *   CLOCK_PLANT  (schedule_plant_clock.c) the plant's stamps are the clock: a sample serves the period
 *                whose apply instant is nearest stamp + tau, and the samples are numbered by period.
 *   CLOCK_NODE   (schedule_node_clock.c) the node's own monotonic clock: a sample serves the first
 *                period after its arrival, and a timer counts the periods that pass without one.
 *
 * Times are int64 microseconds on the schedule's clock (the node's in CLOCK_NODE, the plant's in
 * CLOCK_PLANT): schedule time = plant time + anchor.offset_us. The core's ticks are plant time, so a
 * re-anchor (a new offset) moves nothing in the core: it is computed into a copy of the anchor and
 * committed, or not, by one assignment. lcm_types/README.md ("Timing", "The watchdog") is the contract.
 */
#ifndef TVO_SCHEDULE_H
#define TVO_SCHEDULE_H

#include <stdint.h>

#include "session_codec.h"
#include "step_codec.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What a vote of refused measurements can move: how the plant's clock and numbering map onto the schedule. */
typedef struct {
    int64_t offset_us;            /* schedule clock minus plant clock: 0 in CLOCK_PLANT */
    int64_t epoch_schedule_us;    /* the epoch on the schedule's clock */
    int64_t first_window_utime;   /* CLOCK_PLANT: the plant time the first sample's window opens at */
    int64_t last_sequence;        /* the sequence of the last accepted measurement (CLOCK_PLANT: by period) */
    uint8_t jump_agreed;          /* CLOCK_PLANT: samples agreed on a jump past the watchdog's span (vote) */
} tvo_schedule_anchor_t;

/** Where a measurement stands on the schedule: the period it serves and its times (schedule clock). */
typedef struct {
    int64_t period;               /* j: its command applies at epoch + j h */
    int64_t stamp_us;
    int64_t apply_us;
} tvo_schedule_placement_t;

typedef struct tvo_schedule tvo_schedule_t;

/** One clock mode's functions. */
typedef struct {
    int32_t clock_source;         /* TVO_LCM_SESSION_T_CLOCK_* */
    /** The anchor of a START that arrived at node time now_us (the clocks' mapping, the first window). */
    void (*start)(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg, int64_t now_us);
    /** A repeat of the running START (same content): what a later one may still move. */
    void (*repeat_start)(tvo_schedule_t *schedule, const tvo_lcm_session_t *msg);
    /** The period a measurement (wire times already in range) serves and its stamp, or why none. */
    tvo_node_status_t (*place)(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us,
                          tvo_schedule_placement_t *placement);
    /** A measurement was served at *placement: what the clock mode restarts from it. */
    void (*accepted)(tvo_schedule_t *schedule, const tvo_schedule_placement_t *placement);
    /** A refused measurement's vote on the anchor: 1 when the vote carries and *moved holds the anchor
     *  it agrees on (the schedule keeps only the vote's count until the caller commits *moved). */
    int (*vote)(tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, const tvo_step_why_t *refusal, int64_t now_us,
                tvo_schedule_anchor_t *moved);
    /** The plant time a refusal is stamped with: never before the measurement. */
    int64_t (*refusal_utime)(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us);
    /** The latest stamp (schedule clock) a streamed target sample may carry. */
    int64_t (*latest_target_us)(const tvo_schedule_t *schedule, int64_t now_us);
    /** The timer at now_us: 1 and *period when periods passed unserved up to period, which the caller
     *  hands to the core's watchdog now (the schedule counts them as handed). */
    int (*take_missed)(tvo_schedule_t *schedule, int64_t now_us, int64_t *period);
    /** The next instant (node clock) the timer must run, or TVO_SCHEDULE_NO_DEADLINE. */
    int64_t (*next_deadline)(const tvo_schedule_t *schedule);
    /** The node's clock as the telemetry reports it (0 where the node's clock is not the schedule's). */
    int64_t (*telemetry_node_time_us)(int64_t now_us);
} tvo_schedule_ops_t;

/** next_deadline's answer when no timer runs. */
#define TVO_SCHEDULE_NO_DEADLINE INT64_MAX

struct tvo_schedule {
    const tvo_schedule_ops_t *ops;
    tvo_session_timing_t timing;
    tvo_schedule_anchor_t anchor;
    uint8_t has_accepted;         /* a measurement was accepted (anchors the sequence and the watchdog) */
    int64_t last_period;          /* period index j of the last accepted measurement */
    int64_t vote_value;           /* what refused measurements agree on (the offset, or the numbering), */
    uint8_t votes;                /*   and how many in a row */
    union {                       /* each clock mode's own state */
        struct {
            int64_t vote_period;         /* the period of the running vote's last sample */
        } plant;
        struct {
            int64_t next_miss_period;    /* the first period not yet served or counted as missed */
        } node;
    } clock;
};

/** A clock mode's table from its functions, named <mode>_start, <mode>_place, ...: every mode
 *  defines every function, and the list is written once. */
#define TVO_SCHEDULE_OPS(mode, clock)                                   \
    {                                                                   \
        .clock_source = (clock),                                        \
        .start = mode##_start,                                          \
        .repeat_start = mode##_repeat_start,                            \
        .place = mode##_place,                                          \
        .accepted = mode##_accepted,                                    \
        .vote = mode##_vote,                                            \
        .refusal_utime = mode##_refusal_utime,                          \
        .latest_target_us = mode##_latest_target_us,                    \
        .take_missed = mode##_take_missed,                              \
        .next_deadline = mode##_next_deadline,                          \
        .telemetry_node_time_us = mode##_telemetry_node_time_us,        \
    }

/** The two clock modes (schedule_plant_clock.c, schedule_node_clock.c). */
extern const tvo_schedule_ops_t tvo_schedule_plant_clock;
extern const tvo_schedule_ops_t tvo_schedule_node_clock;

/** The clock mode of session_t.clock_source, or NULL. */
const tvo_schedule_ops_t *tvo_schedule_ops(int32_t clock_source);

/** A new schedule for a START (timing checked by tvo_session_decode_timing) arriving at node time now_us. */
void tvo_schedule_start(tvo_schedule_t *schedule, const tvo_schedule_ops_t *ops, const tvo_session_timing_t *timing,
                        const tvo_lcm_session_t *msg, int64_t now_us);

/**
 * Where a measurement stands, judged on `schedule`: its wire times, its period (the clock mode's
 * rule), and that its command could be stamped on the wire and its age counted by the core's
 * uint32 ticks. TVO_NODE_IMPLAUSIBLE_STAMP, _NOT_LATER_PERIOD or _STALE say why it serves no period.
 */
tvo_node_status_t tvo_schedule_place(const tvo_schedule_t *schedule, const tvo_lcm_sample_header_t *msg, int64_t now_us,
                                tvo_schedule_placement_t *placement);

/** A measurement was served at `placement`: the sequence and the watchdog are anchored on it. */
void tvo_schedule_accept(tvo_schedule_t *schedule, const tvo_schedule_placement_t *placement, int64_t sequence);

/** Period j's apply instant on the schedule's clock. */
int64_t tvo_schedule_apply_us(const tvo_schedule_t *schedule, int64_t period);

/** The core's uint32 tick of a schedule time: plant time (wrapping like a free-running counter). */
uint32_t tvo_schedule_tick(const tvo_schedule_t *schedule, int64_t schedule_us);

/** A schedule time as plant time, clamped to the wire's range. */
int64_t tvo_schedule_plant_utime(const tvo_schedule_t *schedule, int64_t schedule_us);

/* For the clock modes (schedule_*_clock.c): */

/** 1 if t lies in the wire's range [0, TVO_WIRE_TIME_MAX_US]. */
int tvo_schedule_wire_time_ok(int64_t t);

/** t clamped to the wire's range. */
int64_t tvo_schedule_clamp_time(int64_t t);

/**
 * One vote of a refused measurement for `value` (agreeing within `tolerance` with the ones before);
 * 1 once TVO_SCHEDULE_ANCHOR_VOTES in a row agree (the count then restarts).
 */
int tvo_schedule_vote(tvo_schedule_t *schedule, int64_t value, int64_t tolerance);

/** Votes in a row that re-anchor the schedule: a lone stray cannot do it. */
#define TVO_SCHEDULE_ANCHOR_VOTES 3u

#ifdef __cplusplus
}
#endif

#endif /* TVO_SCHEDULE_H */
