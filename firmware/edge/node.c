/*
 * The firmware node's transport-independent logic; see node.h and lcm_types/README.md ("Sessions", "Timing").
 * One flow: a message is decoded, classified into an event, and the session table says what it does
 * in the node's state; a measurement's period and times come from the session's schedule (its clock
 * mode's object, schedule.h), and its command from the core's step.
 */
#include "node.h"
#include "internal/constraints.h"

#include <string.h>

_Static_assert(TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS,
               "node_counters_t.refused has a slot per wire status");

int tvo_node_check_buffer(void)
{
    tvo_lcm_command_t command;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_session_ack_t ack;
    memset(&command, 0, sizeof(command));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&ack, 0, sizeof(ack));
    const int fits = tvo_lcm_command_t_encoded_size(&command) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_telemetry_t_encoded_size(&telemetry) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_session_ack_t_encoded_size(&ack) <= TVO_NODE_BUFFER_BYTES;
    return fits ? 0 : -1;
}

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context)
{
    if (node == NULL) {
        return;
    }
    memset(node, 0, sizeof(*node));
    node->state = TVO_NODE_IDLE;
    node->publish = publish;
    node->publish_context = publish_context;
}

int tvo_node_set_answer(tvo_node_t *node, tvo_node_answer_fn answer, void *answer_context)
{
    if (node == NULL || answer == NULL || node->state != TVO_NODE_IDLE) {
        return -1; /* a running session's commands may be a chain's, which the answer cannot carry */
    }
    node->answer = answer;
    node->answer_context = answer_context;
    return 0;
}

uint8_t tvo_node_max_robots(const tvo_node_t *node)
{
    return (node != NULL && node->answer != NULL) ? (uint8_t)TVO_MAX_ROBOTS : (uint8_t)TVO_WIRE_SESSION_ROBOTS;
}

const tvo_node_session_t *tvo_node_session(const tvo_node_t *node)
{
    return (node != NULL && node->state == TVO_NODE_RUNNING) ? &node->slot[node->running] : NULL;
}

static tvo_node_session_t *running_session(tvo_node_t *node)
{
    return node->state == TVO_NODE_RUNNING ? &node->slot[node->running] : NULL;
}

/* The running slot, for the actions the session table runs only in TVO_NODE_RUNNING. */
static tvo_node_session_t *running_slot(tvo_node_t *node)
{
    return &node->slot[node->running];
}

/* Counters saturate: a long run never overflows one (signed overflow would be undefined). */
static void count(int32_t *counter)
{
    if (*counter < INT32_MAX) {
        ++*counter;
    }
}

/* ---- publishing -------------------------------------------------------------------------------- */

static void publish_encoded(tvo_node_t *node, int channel, int length)
{
    if (length > 0 && node->publish != NULL) {
        node->publish(node->publish_context, channel, node->buffer, (uint32_t)length);
    }
}

/* The ack of a session message, naming the session that runs after it. */
static void publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, const tvo_session_reject_t *why)
{
    const tvo_node_session_t *s = tvo_node_session(node);
    tvo_session_ack(msg, why, s != NULL ? s->session_id : -1, &node->last_ack);
    node->acks++;
    publish_encoded(node, TVO_NODE_CH_SESSION_ACK,
                    tvo_lcm_session_ack_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &node->last_ack));
}

/* A command: to the node's answer if it has one (such a node runs unicycle sessions only), else out
 * as command_t by its plant's codec. */
static void publish_command(tvo_node_t *node, const tvo_edge_controller_ops_t *ops, const tvo_edge_command_t *cmd,
                            const tvo_step_stamp_t *stamp, uint32_t wire_flags)
{
    if (node->answer != NULL) {
        node->answer(node->answer_context, stamp, wire_flags, &cmd->unicycle);
        return;
    }
    tvo_lcm_command_t out;
    ops->command_to_lcm(cmd, stamp, &out);
    publish_encoded(node, TVO_NODE_CH_COMMAND, tvo_lcm_command_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &out));
}

/* A command and the telemetry that follows it. */
static void publish_step(tvo_node_t *node, tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                         const tvo_step_stamp_t *stamp, int64_t now_us)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    const tvo_edge_mark_t mark = ops->mark(cmd);
    const uint32_t flags = tvo_step_wire_flags(mark.flags, mark.outcome);
    if (mark.outcome == TVO_OUTCOME_STOPPED) {
        count(&node->counters.safe_stops);
    }
    if ((flags & TVO_FLAG_SPEED_MISMATCH) != 0u) {
        count(&node->counters.speed_mismatch);
    }
    publish_command(node, ops, cmd, stamp, flags);
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    ops->telemetry_to_lcm(&s->controller, &s->problem, &tel);
    tvo_step_telemetry_stamp(stamp, flags, &tel);
    tel.node_time_us = s->schedule.ops->telemetry_node_time_us(now_us);
    tel.counters = node->counters;
    publish_encoded(node, TVO_NODE_CH_TELEMETRY,
                    tvo_lcm_telemetry_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel));
}

/* ---- the session table ------------------------------------------------------------------------- */

/* A decoded message and when it arrived. */
typedef struct {
    const tvo_lcm_session_t *session;          /* TVO_SESSION, else NULL */
    const tvo_step_measurement_t *measurement; /* TVO_MEASUREMENT (or tvo_node_measure), else NULL */
    const tvo_lcm_target_t *target;            /* TVO_TARGET, else NULL */
    uint64_t content_hash;                     /* a session message's, past its utime */
    int64_t now_us;
} node_input_t;

/* What a message does: TVO_OK if it took effect; a session message's answer is filled into *why. */
typedef tvo_status_t (*node_action_fn)(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);

typedef struct {
    node_action_fn action;                     /* NULL: the message changes nothing but its answer's */
    tvo_node_status_t answer;                  /* ... which says this (TVO_NODE_OK: ignored, unanswered if not acked) */
    uint8_t next_if_taken;                     /* tvo_node_state_t */
    uint8_t next_if_refused;
    uint8_t acked;                             /* answered with a session ack, after the state changed */
    uint8_t reachable;                         /* 0: the event cannot arise in this state */
} node_transition_t;

static tvo_status_t start_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t repeat_start(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t end_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t serve_measurement(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t answer_without_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t take_target(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);
static tvo_status_t count_other_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why);

#define IDLE TVO_NODE_IDLE
#define RUNNING TVO_NODE_RUNNING
#define CANNOT_ARISE {NULL, TVO_NODE_OK, IDLE, IDLE, 0, 0}

/* Every transition of the node, lcm_types/README.md "Sessions" row by row (its "any" is both states). */
static const node_transition_t session_table[TVO_NODE_STATE_COUNT][TVO_NODE_EVENT_COUNT] = {
    [TVO_NODE_IDLE] = {
        /* idle, START that passes every check: built and runs / any, START that fails: nothing changes */
        [TVO_NODE_EVENT_START] = {start_session, TVO_NODE_OK, RUNNING, IDLE, 1, 1},
        /* any, STOP of another id: ignored */
        [TVO_NODE_EVENT_STOP_OTHER] = {NULL, TVO_NODE_NO_SESSION, IDLE, IDLE, 1, 1},
        /* any, another action: ignored */
        [TVO_NODE_EVENT_OTHER_ACTION] = {NULL, TVO_NODE_UNKNOWN_ACTION, IDLE, IDLE, 1, 1},
        /* idle, measurement: a safe stop, TVO_NODE_NO_SESSION (START again) */
        [TVO_NODE_EVENT_MEASUREMENT] = {answer_without_session, TVO_NODE_OK, IDLE, IDLE, 0, 1},
        /* idle, target: nothing to feed (not in the README's table) */
        [TVO_NODE_EVENT_TARGET] = {NULL, TVO_NODE_OK, IDLE, IDLE, 0, 1},
        /* no id runs, so none repeats, conflicts, stops or is another's */
        [TVO_NODE_EVENT_START_REPEAT] = CANNOT_ARISE,
        [TVO_NODE_EVENT_START_CONFLICT] = CANNOT_ARISE,
        [TVO_NODE_EVENT_STOP] = CANNOT_ARISE,
        [TVO_NODE_EVENT_MEASUREMENT_OTHER] = CANNOT_ARISE,
        [TVO_NODE_EVENT_TARGET_OTHER] = CANNOT_ARISE,
    },
    [TVO_NODE_RUNNING] = {
        /* running A, START of a new id B that passes: B replaces A / any, START that fails: A runs on */
        [TVO_NODE_EVENT_START] = {start_session, TVO_NODE_OK, RUNNING, RUNNING, 1, 1},
        /* running A, START of A, the same content: a repeat, acked 0 again */
        [TVO_NODE_EVENT_START_REPEAT] = {repeat_start, TVO_NODE_OK, RUNNING, RUNNING, 1, 1},
        /* running A, START of A with other content: a session's parameters never change under it */
        [TVO_NODE_EVENT_START_CONFLICT] = {NULL, TVO_NODE_SESSION_CONFLICT, RUNNING, RUNNING, 1, 1},
        /* running A, STOP of A: the session ends, acked 0, running -1 */
        [TVO_NODE_EVENT_STOP] = {end_session, TVO_NODE_OK, IDLE, RUNNING, 1, 1},
        /* any, STOP of another id: not ours to obey, whatever runs runs on */
        [TVO_NODE_EVENT_STOP_OTHER] = {NULL, TVO_NODE_NO_SESSION, RUNNING, RUNNING, 1, 1},
        /* any, another action: ignored */
        [TVO_NODE_EVENT_OTHER_ACTION] = {NULL, TVO_NODE_UNKNOWN_ACTION, RUNNING, RUNNING, 1, 1},
        /* running A, measurement of A: served or refused ("Timing") */
        [TVO_NODE_EVENT_MEASUREMENT] = {serve_measurement, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
        /* running A, measurement or target of another session id: ignored, counted */
        [TVO_NODE_EVENT_MEASUREMENT_OTHER] = {count_other_session, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
        /* running A, target of A: taken or refused ("Streamed targets") */
        [TVO_NODE_EVENT_TARGET] = {take_target, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
        [TVO_NODE_EVENT_TARGET_OTHER] = {count_other_session, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
    },
};

#undef IDLE
#undef RUNNING
#undef CANNOT_ARISE

int tvo_node_transition_info(tvo_node_state_t state, tvo_node_event_t event, tvo_node_transition_info_t *info)
{
    if (info == NULL || (uint32_t)state >= (uint32_t)TVO_NODE_STATE_COUNT || event <= TVO_NODE_EVENT_NONE ||
        event >= TVO_NODE_EVENT_COUNT) {
        return 0;
    }
    const node_transition_t *t = &session_table[state][event];
    info->next_if_taken = (tvo_node_state_t)t->next_if_taken;
    info->next_if_refused = (tvo_node_state_t)t->next_if_refused;
    info->acked = t->acked;
    info->reachable = t->reachable;
    return 1;
}

/* The event a session message is, given what runs. */
static tvo_node_event_t session_event(const tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash)
{
    const tvo_node_session_t *running = tvo_node_session(node);
    const int of_running = running != NULL && msg->session_id == running->session_id;
    if (msg->action == TVO_LCM_SESSION_T_ACTION_START) {
        if (!of_running) {
            return TVO_NODE_EVENT_START;
        }
        return content_hash == running->content_hash ? TVO_NODE_EVENT_START_REPEAT : TVO_NODE_EVENT_START_CONFLICT;
    }
    if (msg->action == TVO_LCM_SESSION_T_ACTION_STOP) {
        return of_running ? TVO_NODE_EVENT_STOP : TVO_NODE_EVENT_STOP_OTHER;
    }
    return TVO_NODE_EVENT_OTHER_ACTION;
}

/* A measurement's or target's event: of the running session (when idle, of any), or another's. */
static tvo_node_event_t stream_event(const tvo_node_t *node, int64_t session_id, tvo_node_event_t own,
                                     tvo_node_event_t other)
{
    const tvo_node_session_t *running = tvo_node_session(node);
    return (running == NULL || session_id == running->session_id) ? own : other;
}

/* The one place a message changes the node's state: its action, then the table's next state, then
 * the ack (which names the session running after it). */
static void dispatch(tvo_node_t *node, tvo_node_event_t event, const node_input_t *in)
{
    node->last_event = event;
    const node_transition_t *t = &session_table[node->state][event];
    if (!t->reachable) {
        return; /* the classification, which knows the state, does not give it */
    }
    tvo_session_reject_t why = {t->answer, TVO_OK, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    const int taken = (t->action != NULL) ? t->action(node, in, &why) == TVO_OK : t->answer == TVO_NODE_OK;
    node->state = taken ? t->next_if_taken : t->next_if_refused;
    if (t->acked) {
        publish_ack(node, in->session, &why);
    }
}

/* ---- session actions --------------------------------------------------------------------------- */

/* A refused problem's culprit entry, where tvo_problem_init names only the part: the first robot whose
 * tracking weight, or the first obstacle that (with those before it) the core's own term init refuses;
 * -1 if none alone is to blame. A refusal's cold path. */
static int32_t problem_culprit(const tvo_problem_desc_t *desc, const tvo_barrier_t *barrier, int32_t part)
{
    if (part == TVO_LCM_SESSION_ACK_T_PART_ROBOTS) {
        for (uint8_t r = 0; r < desc->robot_count && r < TVO_MAX_ROBOTS; ++r) {
            tvo_tracking_term_t term;
            if (tvo_tracking_init(&term, &desc->target[r], desc->tracking_weight[r], (uint8_t)(2u * r)) != TVO_OK) {
                return (int32_t)r;
            }
        }
    } else if (part == TVO_LCM_SESSION_ACK_T_PART_OBSTACLES) {
        for (uint8_t count = 1u; count <= desc->obstacle_count && count <= TVO_MAX_OBSTACLES; ++count) {
            tvo_free_space_term_t term;
            if (tvo_free_space_term_init(&term, barrier, 0u, desc->robot_radius_m, desc->obstacle, count) != TVO_OK) {
                return (int32_t)count - 1; /* a bad disk, or the later of an overlapping pair */
            }
        }
    }
    return -1;
}

/* Builds a session from a START into `s` (the spare slot); the running one is not touched. */
static tvo_status_t build_session(const tvo_node_t *node, tvo_node_session_t *s, const tvo_lcm_session_t *msg,
                                  uint64_t content_hash, int64_t now_us, tvo_session_reject_t *why)
{
    memset(s, 0, sizeof(*s));
    tvo_session_timing_t timing;
    tvo_status_t st = tvo_session_decode_timing(msg, &timing, why);
    if (st != TVO_OK) {
        return st;
    }
    /* Robots the node's answers carry; a node that answers through its answer drives unicycles. */
    const int too_many_robots = timing.robot_count > tvo_node_max_robots(node);
    if (too_many_robots || (node->answer != NULL && timing.plant_kind != TVO_LCM_SESSION_T_PLANT_UNICYCLE)) {
        why->status = TVO_ERR_PARAM;
        why->param = too_many_robots ? TVO_SESSION_PARAM_ROBOT_COUNT : TVO_SESSION_PARAM_PLANT_KIND;
        return TVO_ERR_PARAM;
    }
    const tvo_edge_controller_ops_t *ops = tvo_edge_controller_ops(timing.plant_kind);
    const tvo_schedule_ops_t *clock = tvo_schedule_ops(timing.clock_source);
    if (ops == NULL || clock == NULL) {
        why->status = TVO_ERR_PARAM;
        why->param = (ops == NULL) ? TVO_SESSION_PARAM_PLANT_KIND : TVO_SESSION_PARAM_CLOCK_SOURCE;
        return TVO_ERR_PARAM;
    }
    tvo_problem_desc_t desc;
    st = tvo_session_decode_problem(msg, &desc, why);
    /* target_t carries the wire's robots: a larger session's targets cannot be streamed. */
    if (st == TVO_OK && timing.robot_count > TVO_WIRE_SESSION_ROBOTS) {
        for (uint8_t r = 0; st == TVO_OK && r < timing.robot_count; ++r) {
            if (desc.target[r].kind == TVO_TARGET_STREAMED) {
                why->status = st = TVO_ERR_DIMENSION;
                why->param = TVO_SESSION_PARAM_OBJECTIVE;
                why->part = TVO_LCM_SESSION_ACK_T_PART_ROBOTS;
                why->index = (int32_t)r;
            }
        }
    }
    if (st == TVO_OK) {
        uint8_t problem_part = 0;
        st = tvo_problem_init(&s->problem, &desc, ops->relative_degree(msg), &problem_part);
        if (st != TVO_OK) {
            why->status = st;
            why->param = TVO_SESSION_PARAM_OBJECTIVE;
            why->part = tvo_session_part_from_problem(problem_part);
            why->index = problem_culprit(&desc, &s->problem.barrier, why->part);
        }
    }
    if (st != TVO_OK) {
        return st;
    }
    tvo_schedule_start(&s->schedule, clock, &timing, msg, now_us);
    s->controller.ops = ops;
    const uint32_t epoch_tick = tvo_schedule_tick(&s->schedule, s->schedule.anchor.epoch_schedule_us);
    st = ops->init(&s->controller, msg, &s->problem.objective, epoch_tick, why);
    if (st != TVO_OK) {
        return st;
    }
    s->session_id = msg->session_id;
    s->content_hash = content_hash;
    return TVO_OK;
}

static tvo_status_t start_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    const uint8_t spare = (node->state == TVO_NODE_RUNNING) ? (uint8_t)(1u - node->running) : node->running;
    const tvo_status_t st = build_session(node, &node->slot[spare], in->session, in->content_hash, in->now_us, why);
    if (st != TVO_OK) {
        return st;
    }
    node->running = spare;
    node->stop_requested = 0;
    memset(&node->counters, 0, sizeof(node->counters));
    node->last_target_status = TVO_LCM_COMMAND_T_STATUS_OK;
    return TVO_OK;
}

/* The plant repeats START until acked: the same content is answered again, not restarted. */
static tvo_status_t repeat_start(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    tvo_node_session_t *s = running_slot(node);
    s->schedule.ops->repeat_start(&s->schedule, in->session);
    return TVO_OK;
}

static tvo_status_t end_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    node->stop_requested = 1;
    return TVO_OK;
}

static tvo_status_t count_other_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    count(&node->counters.other_session); /* another plant's: not ours to answer */
    return TVO_OK;
}

/* ---- measurements ------------------------------------------------------------------------------ */

/* A measurement when no session runs: a safe stop that tells the plant to START again. */
static tvo_status_t answer_without_session(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    const tvo_step_measurement_t *msg = in->measurement;
    const uint8_t robot_count =
        (msg->robot_count >= 1 && msg->robot_count <= TVO_MAX_ROBOTS) ? (uint8_t)msg->robot_count : 0u;
    const tvo_step_stamp_t stamp = {tvo_schedule_clamp_time(msg->utime), msg->session_id, msg->sequence,
                                    {TVO_NODE_NO_SESSION, TVO_OK, TVO_REASON_NONE}, robot_count};
    tvo_edge_command_t stop;
    memset(&stop, 0, sizeof(stop));
    stop.unicycle.outcome = TVO_OUTCOME_STOPPED;
    const int32_t wire = tvo_step_wire_status(&stamp.why);
    count(&node->counters.refused[wire]);
    node->last_refusal = wire;
    publish_command(node, tvo_edge_controller_ops(TVO_LCM_SESSION_T_PLANT_UNICYCLE), &stop, &stamp,
                    tvo_step_wire_flags(stop.unicycle.flags, stop.unicycle.outcome));
    return TVO_OK;
}

/* What one attempt to serve a measurement on a schedule came to. */
typedef struct {
    tvo_step_why_t why;                        /* the edge's refusal, the core's error, or the command's reason */
    tvo_schedule_placement_t placement;
    tvo_edge_command_t cmd;                    /* the core's answer, when it stepped */
    int stepped;
} node_attempt_t;

/* The core took the measurement: its period committed (applied, or the speed mismatch's stop). */
static int attempt_taken(const node_attempt_t *attempt)
{
    return attempt->stepped && attempt->why.error == TVO_OK &&
           (attempt->why.reason == TVO_REASON_NONE || attempt->why.reason == TVO_REASON_SPEED_MISMATCH);
}

/* The node's checks of a measurement judged on `schedule` (the wire's and its schedule's), then the
 * core's step, a transaction that checks the rest once. */
static void attempt_measurement(tvo_node_session_t *s, const tvo_schedule_t *schedule,
                                const tvo_step_measurement_t *msg, int64_t now_us, node_attempt_t *attempt)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    const uint8_t robot_count = schedule->timing.robot_count;
    const tvo_step_why_t none = {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE};
    attempt->stepped = 0;
    attempt->why = none;
    attempt->why.node = (msg->robot_count == (int32_t)robot_count) ? TVO_NODE_OK : TVO_NODE_WRONG_ROBOT_COUNT;
    if (attempt->why.node == TVO_NODE_OK) {
        attempt->why.node = tvo_schedule_place(schedule, msg, now_us, &attempt->placement);
    }
    tvo_edge_measurement_t meas;
    if (attempt->why.node == TVO_NODE_OK) {
        const uint32_t stamp_tick = tvo_schedule_tick(schedule, attempt->placement.stamp_us);
        attempt->why.node = ops->measurement(&s->controller, msg, robot_count, stamp_tick, &meas);
    }
    if (attempt->why.node != TVO_NODE_OK) {
        return;
    }
    /* The core's step is a transaction: the barrier's s0 included (its objective's start rule). */
    attempt->why.error = ops->step(&s->controller, &meas, tvo_schedule_tick(schedule, attempt->placement.apply_us),
                                   &attempt->cmd);
    attempt->why.reason = ops->mark(&attempt->cmd).reason;
    attempt->stepped = 1;
}

/* The sample passed every check, the core's included, and only its law could not serve it (a target
 * sample not there yet). */
static int law_refused(const node_attempt_t *attempt)
{
    const tvo_reason_t r = attempt->why.reason;
    return attempt->stepped && attempt->why.error == TVO_OK &&
           (r == TVO_REASON_TARGET_NOT_READY || r == TVO_REASON_NUMERIC || r == TVO_REASON_NOT_POSITIVE_DEFINITE);
}

/* The refusal's answer, stamped no earlier than the measurement: the core's answer if it stepped (the
 * command in force, or its watchdog's stop), else the command in force; or the safe stop of the
 * clock mode's own rule (CLOCK_PLANT: a streak of refusals). Nothing of the message is kept. */
static void refuse_measurement(tvo_node_t *node, tvo_node_session_t *s, const tvo_step_measurement_t *msg,
                               const node_attempt_t *attempt, int64_t now_us)
{
    const int32_t wire = tvo_step_wire_status(&attempt->why);
    count(&node->counters.refused[(uint32_t)wire < (uint32_t)TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS ? wire : 0]);
    node->last_refusal = wire;
    tvo_step_stamp_t stamp = {s->schedule.ops->refusal_utime(&s->schedule, msg, now_us), s->session_id,
                              msg->sequence, attempt->why, s->schedule.timing.robot_count};
    tvo_edge_command_t cmd;
    if (s->schedule.ops->count_refusal(&s->schedule)) {
        (void)s->controller.ops->safe_stop(&s->controller, &cmd);
        const tvo_step_why_t streak = {TVO_NODE_REFUSAL_STREAK, TVO_OK, TVO_REASON_NONE};
        stamp.why = streak;
    } else if (attempt->stepped) {
        cmd = attempt->cmd;
    } else {
        s->controller.ops->holding(&s->controller, &cmd);
    }
    publish_step(node, s, &cmd, &stamp, now_us);
}

/*
 * One answer per measurement. It is judged on the schedule's anchor in force; if refused, its vote
 * may carry a re-anchor (schedule.h: refused samples that agree), and it is judged again on the moved
 * anchor, computed in a copy of the schedule. The move is committed, by one assignment, only if the
 * sample then passes every check, the core's included (its law may still refuse it): nothing of a
 * failed trial is undone, because nothing of it was kept.
 */
static tvo_status_t serve_measurement(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    tvo_node_session_t *s = running_slot(node);
    const tvo_step_measurement_t *msg = in->measurement;
    node_attempt_t attempt;
    attempt_measurement(s, &s->schedule, msg, in->now_us, &attempt);
    if (!attempt_taken(&attempt)) {
        tvo_schedule_t moved = s->schedule;
        if (s->schedule.ops->vote(&s->schedule, msg, &attempt.why, in->now_us, &moved.anchor)) {
            attempt_measurement(s, &moved, msg, in->now_us, &attempt);
            if (attempt_taken(&attempt) || law_refused(&attempt)) {
                s->schedule.anchor = moved.anchor;
            }
        }
    }
    if (!attempt_taken(&attempt)) {
        refuse_measurement(node, s, msg, &attempt, in->now_us);
        return TVO_OK;
    }
    count(&node->counters.accepted);
    tvo_schedule_accept(&s->schedule, &attempt.placement, msg->sequence);
    const tvo_step_stamp_t stamp = {attempt.placement.apply_us - s->schedule.anchor.offset_us, s->session_id,
                                    msg->sequence, attempt.why, s->schedule.timing.robot_count};
    publish_step(node, s, &attempt.cmd, &stamp, in->now_us);
    return TVO_OK;
}

/* ---- streamed targets -------------------------------------------------------------------------- */

/* A sample is taken if newer than the last and stamped no later than the clock mode allows (one stray
 * from beyond the next period would hold back every genuine one after it: it costs a period or two). */
static tvo_status_t take_target(tvo_node_t *node, const node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    tvo_node_session_t *s = running_slot(node);
    const tvo_schedule_t *schedule = &s->schedule;
    const tvo_lcm_target_t *msg = in->target;
    tvo_step_why_t answer = {tvo_schedule_wire_time_ok(msg->utime) ? TVO_NODE_OK : TVO_NODE_IMPLAUSIBLE_STAMP, TVO_OK,
                             TVO_REASON_NONE};
    const int64_t stamp_us = (answer.node == TVO_NODE_OK) ? msg->utime + schedule->anchor.offset_us : 0;
    if (answer.node == TVO_NODE_OK && stamp_us > schedule->ops->latest_target_us(schedule, in->now_us)) {
        answer.node = TVO_NODE_IMPLAUSIBLE_STAMP;
    }
    /* The objective's time of the sample, in ticks (us) since the epoch, from 64-bit times: a
     * uint32 tick would alias a sample 2^32 us old with one from the future. */
    const int64_t since_epoch_us = (answer.node == TVO_NODE_OK) ? stamp_us - schedule->anchor.epoch_schedule_us : 0;
    if (answer.node == TVO_NODE_OK && since_epoch_us < -schedule->timing.period_us) {
        answer.error = TVO_ERR_BEFORE_EPOCH; /* more than a period before the epoch */
    }
    if (answer.node == TVO_NODE_OK && answer.error == TVO_OK) {
        /* A sample from the period before the epoch (a plant samples its target with the measurement,
         * at epoch - tau) is carried forward to the epoch: the objective's time starts there. */
        const int64_t carry_us = since_epoch_us < 0 ? -since_epoch_us : 0;
        answer.error = tvo_step_target_from_lcm_carried(msg, schedule->timing.robot_count,
                                                        (uint64_t)(since_epoch_us + carry_us),
                                                        (double)carry_us * 1e-6, &s->problem);
    }
    node->last_target_status = tvo_step_wire_status(&answer);
    if (node->last_target_status != TVO_LCM_COMMAND_T_STATUS_OK) {
        count(&node->counters.targets_refused);
        return TVO_ERR_PARAM; /* not taken */
    }
    return TVO_OK;
}

/* ---- entry points ------------------------------------------------------------------------------ */

int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us)
{
    if (node == NULL) {
        return 0;
    }
    if (data == NULL || length > (uint32_t)INT32_MAX) {
        count(&node->counters.undecodable);
        return 0;
    }
    node_input_t in = {NULL, NULL, NULL, 0u, tvo_schedule_clamp_time(now_us)};
    const int size = (int)length;
    tvo_node_event_t event = TVO_NODE_EVENT_NONE;
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        if (tvo_lcm_session_t_decode(data, 0, size, &node->rx.session) == size) {
            in.session = &node->rx.session;
            in.content_hash = tvo_session_content_hash(data, length);
            event = session_event(node, in.session, in.content_hash);
        }
        break; /* malformed, or bytes past the message: not what a sender of this message sends */
    case TVO_NODE_CH_MEASUREMENT:
        if (tvo_lcm_measurement_t_decode(data, 0, size, &node->rx.measurement) == size) {
            tvo_step_measurement_from_wire(&node->rx.measurement, &node->measurement);
            in.measurement = &node->measurement;
            event = stream_event(node, in.measurement->session_id, TVO_NODE_EVENT_MEASUREMENT,
                                 TVO_NODE_EVENT_MEASUREMENT_OTHER);
        }
        break;
    case TVO_NODE_CH_TARGET:
        if (tvo_lcm_target_t_decode(data, 0, size, &node->rx.target) == size) {
            in.target = &node->rx.target;
            event = stream_event(node, in.target->session_id, TVO_NODE_EVENT_TARGET, TVO_NODE_EVENT_TARGET_OTHER);
        }
        break;
    default:
        return 0; /* not a channel the node takes (its own outputs, or unknown) */
    }
    if (event == TVO_NODE_EVENT_NONE) {
        count(&node->counters.undecodable);
        return 0;
    }
    dispatch(node, event, &in);
    return channel;
}

int tvo_node_measure(tvo_node_t *node, const tvo_step_measurement_t *measurement, int64_t now_us)
{
    if (node == NULL || measurement == NULL) {
        return 0;
    }
    node_input_t in = {NULL, measurement, NULL, 0u, tvo_schedule_clamp_time(now_us)};
    dispatch(node, stream_event(node, measurement->session_id, TVO_NODE_EVENT_MEASUREMENT, TVO_NODE_EVENT_MEASUREMENT_OTHER),
             &in);
    return TVO_NODE_CH_MEASUREMENT;
}

int64_t tvo_node_poll(tvo_node_t *node, int64_t now_us)
{
    tvo_node_session_t *s = (node != NULL) ? running_session(node) : NULL;
    if (s == NULL) {
        return TVO_NODE_NO_DEADLINE;
    }
    now_us = tvo_schedule_clamp_time(now_us);
    tvo_schedule_t *schedule = &s->schedule;
    int64_t period = 0;
    if (schedule->ops->take_missed(schedule, now_us, &period)) {
        /* The core counts the missed periods and its watchdog decides; its stop is published, stamped
         * now, every period until a measurement is served. */
        tvo_edge_command_t cmd;
        const uint32_t apply_tick = tvo_schedule_tick(schedule, tvo_schedule_apply_us(schedule, period));
        tvo_step_why_t why = {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE};
        why.error = s->controller.ops->miss(&s->controller, apply_tick, &cmd);
        const tvo_edge_mark_t mark = s->controller.ops->mark(&cmd);
        why.reason = mark.reason;
        if (mark.outcome == TVO_OUTCOME_STOPPED) {
            const tvo_step_stamp_t stamp = {tvo_schedule_plant_utime(schedule, now_us), s->session_id, -1, why,
                                            schedule->timing.robot_count};
            publish_step(node, s, &cmd, &stamp, now_us);
        }
    }
    return schedule->ops->next_deadline(schedule);
}
