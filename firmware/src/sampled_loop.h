/*
 * Private to the core: the sampled-data loop, written once for every plant's controller. Every hold
 * and every stop a period can end in is decided here, and nowhere else.
 *
 * What a period does (one call, one selected answer; a later line takes precedence over an earlier):
 *   1. applied    the measurement passed every check, the law and the limits: the period is committed.
 *   2. held       the command in force, repeated, for the reason of a refusal: the core's own checks
 *                 (the measurement's, then, if its objective reads a streamed target, its targets'
 *                 at the law's time), its law's (no result: a numeric failure), or the caller's
 *                 (tvo_*_refuse: refused before the core saw it);
 *                 or no measurement at all (tvo_*_miss). Nothing of the period is kept.
 *   3. plant stop the measurement was taken, but the plant's own finding stops the robots (the
 *                 unicycle's speed mismatch: its commit piece reports it, this file makes the stop).
 *   4. watchdog   watchdog_periods periods without a good step, or, on a clock that counts refusals
 *                 (a lockstep plant: no timer), watchdog_periods refusals in a row: the stop, until a
 *                 good step; the one thing a refusal commits.
 *   5. requested  tvo_*_safe_stop: the stop now, the watchdog expired.
 *   6. misuse     a call the core cannot serve (NULL, not initialised, a tick that does not advance):
 *                 an error, nothing changed, and a command safe to apply (the stop, or the one in force).
 *
 * The loop owns the period's clock, the command in force (held), the watchdog and the commit. A step
 * begins the period of its application instant; the plant prepares the law's state from the
 * measurement (checking it), computes the command it would hold (the law, its output mapped to the
 * plant's input, the limits); then either the whole period is committed (the clock, the plant's
 * state, the held command) or nothing changes and the answer is the command in force. The one thing
 * a refusal commits is the watchdog's stop: a refused step whose period would expire it counts the
 * period and stops (tvo/controller.h states the contract). The objective's start rule (the barrier's
 * s0, tvo/objective.h) is part of the period until a sample is accepted: it sees the measurement as
 * the period begins, and a refused period takes back what it chose. Every command the loop delivers carries
 * its outcome and reason (tvo/status.h); the public calls return an error only when they changed
 * nothing, and this file is the one place that writes an outcome.
 *
 * A plant (unicycle, integrator chain) supplies a tvo_loop_plant_t: the sizes of its controller and
 * command, accessors written with its own types for where the loop's parts live in them (the loop's
 * state, tvo/loop_state.h; the step's period record; the command in force; a command's mark; a
 * measurement's stamp and positions), and its pieces. Each controller calls the loop with its
 * own static const table, so the compiler folds the table and calls the pieces directly (no indirect
 * call is left: tools/footprint.py refuses one it does not know of, the check that it was folded).
 */
#ifndef TVO_SAMPLED_LOOP_H
#define TVO_SAMPLED_LOOP_H

#include <stddef.h>
#include <string.h>

#include "internal/sample_clock.h"
#include "internal/objective.h"
#include "internal/target.h"
#include "tvo/defaults.h"
#include "shape.h"

/* A body compiled into each of its callers, so that a constant argument folds there: a NULL option,
 * or a plant's table (folded before the compiler decides which functions to emit, so the pieces the
 * table names are not emitted again beside their inlined copies). */
#if defined(__GNUC__)
#define TVO_LOOP_ENTRY static inline __attribute__((always_inline))
#else
#define TVO_LOOP_ENTRY static inline
#endif

/* What a period's pieces pass each other, in registers when the loop is compiled into the step. */
typedef struct {
    uint32_t flags;    /* the command's TVO_FLAG_* so far */
    uint8_t note;      /* the plant's own, from prepare to commit */
    uint8_t from_rest; /* the watchdog stopped the plant: the command in force is zero */
    uint8_t shape;     /* the plant's count for its loops (a constant in the shape copies) */
} tvo_loop_frame_t;

/* Where a plant's command says what its period did: its TVO_FLAG_*, outcome and reason, after its
 * inputs. */
typedef struct {
    uint32_t *flags;
    uint8_t *outcome;   /* tvo_outcome_t */
    uint8_t *reason;    /* tvo_reason_t */
    size_t inputs_size; /* the bytes of the command's inputs, which come first */
} tvo_loop_mark_t;

typedef struct {
    size_t controller_size; /* sizeof the plant's controller (a refused init leaves it zeroed) */
    size_t command_size;    /* sizeof the plant's command (copied whole: the held one to the caller's) */
    /* Where the loop's parts live in the plant's types, each read through the plant's own typed member
     * access (the table is folded: these compile to the members' addresses). */
    /** The loop's state in the plant's controller, to change (state) or to read (state_of). */
    tvo_loop_state_t *(*state)(void *ctl);
    const tvo_loop_state_t *(*state_of)(const void *ctl);
    /** The step's record of its period, in the controller's work area (scratch: no state between steps). */
    tvo_period_t *(*period)(void *ctl);
    /** The command in force, in the plant's controller (a command of the plant's type). */
    void *(*held)(void *ctl);
    /** The mark of a command of the plant's type. */
    tvo_loop_mark_t (*mark)(void *cmd);
    /** The measurement's stamp, and its positions (2 tvo_real_t per robot in a row). */
    uint32_t (*stamp_tick)(const void *meas);
    const tvo_real_t *(*positions)(const void *meas);
    /** The measurement's checks, clock's stamp rules included (NULL measurements never reach it):
     *  TVO_REASON_NONE or the refusal, before any refinement by refusal. */
    tvo_reason_t (*check)(const void *ctl, const void *meas, uint32_t apply_tick);
    /** The refusal's reason as the caller sees it (e.g. implausible or not finite); NULL: as it is. */
    tvo_reason_t (*refusal)(const void *ctl, const void *meas, tvo_reason_t reason);
    /** For a begun period: the measurement checked, the state and time the law is evaluated at, the
     *  frame's flags and note (nothing committed). */
    tvo_reason_t (*prepare)(void *ctl, const void *meas, uint32_t apply_tick, tvo_loop_frame_t *frame);
    /** The law, evaluated there (in the step's frame: its call chain is the step's deepest). */
    tvo_reason_t (*law)(void *ctl, tvo_loop_frame_t *frame);
    /** The law's output mapped to the command the step would hold, limits applied (in the plant's work
     *  area; nothing committed). */
    tvo_reason_t (*command)(void *ctl, tvo_loop_frame_t *frame);
    /** The period accepted (the clock already committed, the held command marked applied): the plant's
     *  state and the held command with the frame's flags. TVO_REASON_NONE, or the plant's finding that
     *  stops the robots (its states already at rest; the loop makes the held command the stop). */
    tvo_reason_t (*commit)(void *ctl, const tvo_loop_frame_t *frame);
    /** loop_refuse with this table, kept out of line in the plant (a cold path: the step's registers
     *  and layout do not pay for it). */
    void (*refuse)(void *ctl, const void *meas, const tvo_period_t *period, tvo_reason_t reason, void *cmd);
    /** The plant stops: its states at rest (the loop zeroes the held command); NULL: nothing more. */
    void (*rest)(void *ctl);
} tvo_loop_plant_t;

/* A command's storage holds a uint32_t, so it is word-aligned: its copies may move whole words
 * (ldm/stm on Arm) as a typed struct assignment would. */
#if defined(__GNUC__)
#define LOOP_WORDS(ptr) __builtin_assume_aligned((ptr), sizeof(uint32_t))
#else
#define LOOP_WORDS(ptr) (ptr)
#endif

TVO_LOOP_ENTRY tvo_sample_clock_t *loop_clock(const tvo_loop_plant_t *p, void *ctl)
{
    return &p->state(ctl)->clock;
}

TVO_LOOP_ENTRY int loop_initialized(const tvo_loop_plant_t *p, const void *ctl)
{
    return p->state_of(ctl)->initialized != 0u;
}

/* A command's outcome and reason. */
TVO_LOOP_ENTRY void loop_mark_outcome(const tvo_loop_plant_t *p, void *cmd, tvo_outcome_t outcome, tvo_reason_t reason)
{
    const tvo_loop_mark_t mark = p->mark(cmd);
    *mark.outcome = (uint8_t)outcome;
    *mark.reason = (uint8_t)reason;
}

/* A command's flags, outcome and reason. */
TVO_LOOP_ENTRY void loop_mark(const tvo_loop_plant_t *p, void *cmd, uint32_t flags, tvo_outcome_t outcome,
                              tvo_reason_t reason)
{
    *p->mark(cmd).flags = flags;
    loop_mark_outcome(p, cmd, outcome, reason);
}

/* The stop: every input zero, no flags (the memset's). */
TVO_LOOP_ENTRY void loop_stop_command(const tvo_loop_plant_t *p, void *cmd, tvo_reason_t reason)
{
    memset(LOOP_WORDS(cmd), 0, p->command_size);
    const tvo_loop_mark_t mark = p->mark(cmd);
    *mark.outcome = (uint8_t)TVO_OUTCOME_STOPPED;
    if (reason != TVO_REASON_NONE) {
        *mark.reason = (uint8_t)reason; /* NONE is the memset's: a constant NONE stores nothing */
    }
}

/* The command in force, held (zero once the plant was stopped). */
TVO_LOOP_ENTRY void loop_hold(const tvo_loop_plant_t *p, void *ctl, void *cmd, tvo_reason_t reason)
{
    memcpy(LOOP_WORDS(cmd), LOOP_WORDS(p->held(ctl)), p->command_size);
    loop_mark(p, cmd, 0u, TVO_OUTCOME_HELD, reason);
}

/* A taken period the plant's finding stops (its states already at rest): the held command the stop, its
 * flags kept (they say what the plant found): its inputs zero. */
TVO_LOOP_ENTRY void loop_plant_stop(const tvo_loop_plant_t *p, void *held, tvo_reason_t reason)
{
    memset(LOOP_WORDS(held), 0, p->mark(held).inputs_size);
    loop_mark_outcome(p, held, TVO_OUTCOME_STOPPED, reason);
}

/* The plant stops: its states, and the held command, at rest; cmd the stop, for `reason` (a copy of
 * the held one). */
TVO_LOOP_ENTRY void loop_drop_to_rest(const tvo_loop_plant_t *p, void *ctl, void *cmd, tvo_reason_t reason)
{
    if (p->rest != NULL) {
        p->rest(ctl);
    }
    void *held = p->held(ctl);
    loop_stop_command(p, held, reason);
    memcpy(LOOP_WORDS(cmd), LOOP_WORDS(held), p->command_size);
}

/* A public call's guard: cmd NULL is TVO_ERR_NULL; an instance NULL or not initialised answers with
 * the stop (a command safe to apply) and the error naming which. TVO_OK when the call may go on. */
TVO_LOOP_ENTRY tvo_status_t loop_ready(const tvo_loop_plant_t *p, const void *ctl, void *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    const tvo_status_t st = (ctl == NULL)                 ? TVO_ERR_NULL
                            : !loop_initialized(p, ctl) ? TVO_ERR_NOT_INITIALIZED
                                                        : TVO_OK;
    if (st != TVO_OK) {
        loop_stop_command(p, cmd, TVO_REASON_NONE); /* one copy of the stop for both errors */
    }
    return st;
}

/* The stop now, the watchdog expired (without counting a period: the clock does not advance). */
TVO_LOOP_ENTRY void loop_stop_now(const tvo_loop_plant_t *p, void *ctl, void *cmd, tvo_reason_t reason)
{
    sample_clock_expire(loop_clock(p, ctl));
    loop_drop_to_rest(p, ctl, cmd, reason);
}

/* A period the clock cannot begin (apply_tick does not advance, or precedes the epoch): a call error,
 * nothing changed, cmd the command in force. */
TVO_LOOP_ENTRY tvo_status_t loop_begin(const tvo_loop_plant_t *p, void *ctl, uint32_t apply_tick,
                                       tvo_period_t *period, void *cmd)
{
    const tvo_status_t st = sample_clock_begin(loop_clock(p, ctl), apply_tick, period);
    if (st != TVO_OK) {
        loop_hold(p, ctl, cmd, TVO_REASON_NONE);
    }
    return st;
}

/* tvo_*_miss (and a step without a measurement, which calls it: its period record is in its own
 * frame, not on the step's deepest chain). The period is counted by the plant's refuse piece, which
 * counts every period without a measurement (loop_refuse). */
TVO_LOOP_ENTRY tvo_status_t loop_miss(const tvo_loop_plant_t *p, void *ctl, uint32_t apply_tick, void *cmd)
{
    tvo_status_t st = loop_ready(p, ctl, cmd);
    tvo_period_t period;
    if (st == TVO_OK) {
        st = loop_begin(p, ctl, apply_tick, &period, cmd);
    }
    if (st == TVO_OK) {
        p->refuse(ctl, NULL, &period, TVO_REASON_NO_MEASUREMENT, cmd);
    }
    return st;
}

/* What a piece reports when a computation produced nothing (a cold path): its reason; the misuses the
 * unchecked pieces cannot meet, a numeric failure. A value not finite is a computed one here (the check
 * piece refused every measured one, TVO_REASON_NOT_FINITE): numeric. The period's other reasons are
 * decided before the law, as reasons (the stamp rules, objective_targets_ready). */
TVO_LOOP_ENTRY tvo_reason_t loop_reason_of(tvo_status_t st)
{
    static const uint8_t reason_of[TVO_STATUS_COUNT] = {
        [TVO_OK] = TVO_REASON_NONE,
        [TVO_ERR_NULL] = TVO_REASON_NUMERIC,
        [TVO_ERR_NOT_FINITE] = TVO_REASON_NUMERIC,
        [TVO_ERR_DIMENSION] = TVO_REASON_NUMERIC,
        [TVO_ERR_PARAM] = TVO_REASON_NUMERIC,
        [TVO_ERR_CAPACITY] = TVO_REASON_NUMERIC,
        [TVO_ERR_NOT_INITIALIZED] = TVO_REASON_NUMERIC,
        [TVO_ERR_TICK_NOT_ADVANCING] = TVO_REASON_NUMERIC,
        [TVO_ERR_BEFORE_EPOCH] = TVO_REASON_NUMERIC,
        [TVO_ERR_NOT_POSITIVE_DEFINITE] = TVO_REASON_NOT_POSITIVE_DEFINITE,
        [TVO_ERR_NUMERIC] = TVO_REASON_NUMERIC,
    };
    return ((uint32_t)st < TVO_STATUS_COUNT) ? (tvo_reason_t)reason_of[st] : TVO_REASON_NUMERIC;
}

/* A step that cannot use its measurement (or its law's result), committing nothing: the command in
 * force, held for the refusal's reason; or, when counting the period would expire the watchdog, the
 * period counted and the stop (the state the plant is left in). meas NULL: a period without a
 * measurement (tvo_*_miss), always counted. The body of the plant's refuse piece. */
TVO_LOOP_ENTRY void loop_refuse(const tvo_loop_plant_t *p, void *ctl, const void *meas, const tvo_period_t *period,
                                tvo_reason_t reason, void *cmd)
{
    if (tvo_sample_clock_refuse(loop_clock(p, ctl), period, meas != NULL)) {
        loop_drop_to_rest(p, ctl, cmd, TVO_REASON_WATCHDOG);
    } else {
        loop_hold(p, ctl, cmd, (meas != NULL && p->refusal != NULL) ? p->refusal(ctl, meas, reason) : reason);
    }
}

/* The reasons a caller may refuse a measurement for (tvo_*_refuse): a measurement's, not a stop's. */
TVO_LOOP_ENTRY int loop_is_refusal_reason(tvo_reason_t reason)
{
    return (reason >= TVO_REASON_NOT_FINITE && reason <= TVO_REASON_SOURCE_NOT_LINKED) ||
           reason == TVO_REASON_REFUSED;
}

/* tvo_*_refuse: a measurement the caller refused before the core saw it, with no period of its own
 * (its stamp is what was wrong): the command in force held for `reason`, nothing changed; on a clock
 * that counts refusals, the watchdog_periods-th in a row is the watchdog's stop. TVO_ERR_PARAM for a
 * reason that is not a refusal's (cmd the command in force). */
TVO_LOOP_ENTRY tvo_status_t loop_refuse_unplaced(const tvo_loop_plant_t *p, void *ctl, tvo_reason_t reason, void *cmd)
{
    const tvo_status_t st = loop_ready(p, ctl, cmd);
    if (st != TVO_OK) {
        return st;
    }
    if (!loop_is_refusal_reason(reason)) {
        loop_hold(p, ctl, cmd, TVO_REASON_NONE);
        return TVO_ERR_PARAM;
    }
    if (tvo_sample_clock_refuse(loop_clock(p, ctl), NULL, 1)) {
        loop_drop_to_rest(p, ctl, cmd, TVO_REASON_WATCHDOG);
    } else {
        loop_hold(p, ctl, cmd, reason);
    }
    return TVO_OK;
}

/* The objective's start rule (tvo/objective.h), if it has one: as a period begins, with the
 * measurement's positions y; with NULL, as that period is refused. Called only until a sample is
 * accepted (the clock has no stamp), so a running loop pays one test of a byte. */
TVO_OFF_CHAIN_BODY void loop_start_rule(const tvo_objective_t *objective, const tvo_real_t *y)
{
    if (objective->start_rule != NULL) {
        objective->start_rule(objective, y);
    }
}

/* The controller's objective. */
TVO_LOOP_ENTRY const tvo_objective_t *loop_objective(const tvo_loop_plant_t *p, const void *ctl)
{
    return p->state_of(ctl)->objective;
}

/* objective_targets_ready at the period's law time. A speed build tests first whether the objective noted a
 * streamed target (the only kind that can be unready), so the common period pays one load and compare and
 * no call; a size build calls at once (its flash is the smaller). */
TVO_LOOP_ENTRY tvo_reason_t loop_targets_ready(const tvo_objective_t *objective, const tvo_period_t *period)
{
#if defined(__OPTIMIZE_SIZE__)
    return objective_targets_ready(objective, period->law_time.ticks);
#else
    return objective->target_count != 0u ? objective_targets_ready(objective, period->law_time.ticks)
                                         : TVO_REASON_NONE;
#endif
}

/* One period with a measurement, for an instance loop_ready passed: begin, prepare, command, and the
 * commit or the refusal. shape: the plant's loop count, a constant in the shape copies. TVO_OK when
 * cmd is the period's answer (its outcome says which), else the clock could not begin the period. */
TVO_LOOP_ENTRY tvo_status_t loop_period(const tvo_loop_plant_t *p, void *ctl, const void *meas, uint32_t apply_tick,
                                        void *cmd, const uint8_t shape)
{
    tvo_sample_clock_t *clock = loop_clock(p, ctl);
    tvo_period_t *period = p->period(ctl);
    const tvo_status_t begun = loop_begin(p, ctl, apply_tick, period, cmd);
    if (begun != TVO_OK) {
        return begun;
    }
    tvo_loop_frame_t frame = {0u, 0u, clock->stopped, shape};
    tvo_reason_t reason = p->prepare(ctl, meas, apply_tick, &frame);
    if (reason == TVO_REASON_NONE) {
        reason = loop_targets_ready(loop_objective(p, ctl), period); /* prepare located it */
    }
    if (reason == TVO_REASON_NONE) {
        if (!clock->has_stamp) { /* no sample accepted yet: this checked one may be the state at t = 0 */
            loop_start_rule(loop_objective(p, ctl), p->positions(meas));
        }
        reason = p->law(ctl, &frame);
    }
    if (reason == TVO_REASON_NONE) {
        reason = p->command(ctl, &frame);
    }
    if (reason != TVO_REASON_NONE) {
        p->refuse(ctl, meas, period, reason, cmd);
        if (!clock->has_stamp) { /* a refusal accepts nothing: the clock has no stamp still */
            loop_start_rule(loop_objective(p, ctl), NULL);
        }
        return TVO_OK;
    }
    /* The step succeeded: from here on its working copies become the controller's state. */
    sample_clock_end_good(clock, period, p->stamp_tick(meas));
    void *held = p->held(ctl);
    loop_mark_outcome(p, held, TVO_OUTCOME_APPLIED, TVO_REASON_NONE); /* the commit sets the flags */
    const tvo_reason_t plant_stop = p->commit(ctl, &frame);
    if (plant_stop != TVO_REASON_NONE) {
        loop_plant_stop(p, held, plant_stop);
    }
    memcpy(LOOP_WORDS(cmd), LOOP_WORDS(held), p->command_size);
    return TVO_OK;
}

/* tvo_*_check: what the step would say of this measurement (*reason), changing nothing. */
TVO_LOOP_ENTRY tvo_status_t loop_check(const tvo_loop_plant_t *p, const void *ctl, const void *meas,
                                       uint32_t apply_tick, tvo_reason_t *reason)
{
    if (ctl == NULL || reason == NULL) {
        return TVO_ERR_NULL;
    }
    *reason = TVO_REASON_NONE;
    if (!loop_initialized(p, ctl)) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    tvo_period_t period;
    const tvo_status_t st = sample_clock_begin(&p->state_of(ctl)->clock, apply_tick, &period);
    if (st != TVO_OK) {
        return st;
    }
    if (meas == NULL) {
        *reason = TVO_REASON_NO_MEASUREMENT;
        return TVO_OK;
    }
    const tvo_reason_t why = p->check(ctl, meas, apply_tick);
    *reason = (why == TVO_REASON_NONE || p->refusal == NULL) ? why : p->refusal(ctl, meas, why);
    return TVO_OK;
}

/* tvo_*_safe_stop: the plant at rest now, as the watchdog leaves it; the clock does not advance. */
TVO_LOOP_ENTRY tvo_status_t loop_safe_stop(const tvo_loop_plant_t *p, void *ctl, void *cmd)
{
    const tvo_status_t st = loop_ready(p, ctl, cmd);
    if (st != TVO_OK) {
        return st;
    }
    loop_stop_now(p, ctl, cmd, TVO_REASON_STOP_REQUESTED);
    return TVO_OK;
}

/* The first half of an init: the pointers checked, the instance zeroed (the caller clears its
 * bad_param: each configuration names its own). */
TVO_LOOP_ENTRY tvo_status_t loop_init_begin(const tvo_loop_plant_t *p, void *ctl, const void *cfg,
                                           const tvo_objective_t *objective)
{
    if (ctl == NULL || cfg == NULL || objective == NULL) {
        return TVO_ERR_NULL;
    }
    memset(ctl, 0, p->controller_size);
    return TVO_OK;
}

/* The second half: a refused init leaves the instance zeroed; else the clock starts at epoch_tick (its
 * timing validated by the plant), the command in force is marked applied and the instance is
 * initialised. */
TVO_LOOP_ENTRY tvo_status_t loop_init_end(const tvo_loop_plant_t *p, void *ctl, tvo_status_t st, uint32_t tick_hz,
                                         uint32_t period_ticks, uint32_t watchdog_periods, uint8_t counts_refusals,
                                         uint32_t epoch_tick)
{
    if (st != TVO_OK) {
        memset(ctl, 0, p->controller_size);
        return st;
    }
    tvo_sample_clock_init(loop_clock(p, ctl), tick_hz, period_ticks, watchdog_periods, counts_refusals, epoch_tick);
    p->state(ctl)->initialized = 1u;
    return TVO_OK;
}

/* The loop's parameters at their defaults (tvo/defaults.h), designated initialisers of a plant's
 * configuration (its fields carry these names), with delay compensation on. */
#define TVO_LOOP_CONFIG_DEFAULTS                                                                               \
    .tick_hz = TVO_DEFAULT_TICK_HZ, .period_ticks = TVO_DEFAULT_PERIOD_US, .delay_ticks = TVO_DEFAULT_DELAY_US, \
    .delay_compensation = 1u, .watchdog_periods = TVO_DEFAULT_WATCHDOG_PERIODS

#endif /* TVO_SAMPLED_LOOP_H */
