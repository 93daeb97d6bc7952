/*
 * The node's session table: what each message does in each state, lcm_types/README.md "Sessions" row
 * by row (test_node checks each row against this table). A session message is first matched to this
 * node's boot (a START or STOP recorded before the node's latest start, or meant for another node, is
 * dropped unanswered), then by its session id.
 */
#include "node_sessions.h"

#include "node_period.h"
#include "node_publish.h"
#include "node_start.h"

#include <string.h>

int tvo_node_names_this_boot(const tvo_node_t *node, const tvo_lcm_session_t *msg)
{
    const int32_t robots = msg->robot_count;
    if (robots < 1 || robots > TVO_LCM_SESSION_T_MAX_ROBOTS) {
        return 0; /* it names no robot, so no boot */
    }
    if (node->own_robot >= 0) {
        return node->own_robot < robots && msg->node_boot_id[node->own_robot] == node->boot_id;
    }
    for (int32_t r = 0; r < robots; ++r) {
        if (msg->node_boot_id[r] != node->boot_id) {
            return 0;
        }
    }
    return 1;
}

tvo_node_event_t tvo_node_session_event(const tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash)
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

tvo_node_event_t tvo_node_stream_event(const tvo_node_t *node, int32_t session_id, tvo_node_event_t own,
                                       tvo_node_event_t other)
{
    const tvo_node_session_t *running = tvo_node_session(node);
    return (running == NULL || session_id == running->session_id) ? own : other;
}

/* What a message does: TVO_OK if it took effect; a session message's answer is filled into *why. */
typedef tvo_status_t (*node_action_fn)(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why);

typedef struct {
    node_action_fn action;                     /* NULL: the message changes nothing but its answer's */
    tvo_node_status_t answer;                  /* ... which says this (TVO_NODE_OK: ignored, unanswered if not acked) */
    uint8_t next_if_taken;                     /* tvo_node_state_t */
    uint8_t next_if_refused;
    uint8_t acked;                             /* answered with a session ack, after the state changed */
    uint8_t reachable;                         /* 0: the event cannot arise in this state */
} node_transition_t;

/* ---- actions ------------------------------------------------------------------------------------ */

static tvo_status_t drop_wrong_boot(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    tvo_node_count(&node->counters.wrong_boot); /* a recording from before a restart, or another node's */
    return TVO_OK;
}

static tvo_status_t start_session(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    const uint8_t spare = (node->state == TVO_NODE_RUNNING) ? (uint8_t)(1u - node->running) : node->running;
    const tvo_status_t st = tvo_node_build_session(&node->slot[spare], in->session, in->content_hash, in->now_us, why);
    if (st != TVO_OK) {
        return st;
    }
    node->running = spare;
    node->stop_requested = 0;
    node->last_target_status = TVO_LCM_COMMAND_HEADER_T_STATUS_OK;
    tvo_node_count(&node->counters.sessions);
    return TVO_OK;
}

/* The plant repeats START until acked: the same content is answered again, not restarted. */
static tvo_status_t repeat_start(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    tvo_node_session_t *s = tvo_node_running_slot(node);
    s->schedule.ops->repeat_start(&s->schedule, in->session);
    return TVO_OK;
}

static tvo_status_t end_session(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    node->stop_requested = 1;
    return TVO_OK;
}

static tvo_status_t serve_sample(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    tvo_node_serve_sample(node, in);
    return TVO_OK;
}

static tvo_status_t take_target(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)why;
    return tvo_node_take_target(node, in);
}

static tvo_status_t drop_idle(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    tvo_node_count(&node->counters.idle); /* no session to serve: the plant learns it from TVO_NODE */
    return TVO_OK;
}

static tvo_status_t count_other_session(tvo_node_t *node, const tvo_node_input_t *in, tvo_session_reject_t *why)
{
    (void)in;
    (void)why;
    tvo_node_count(&node->counters.other_session); /* another plant's: not ours to answer */
    return TVO_OK;
}

/* ---- the table ---------------------------------------------------------------------------------- */

#define IDLE TVO_NODE_IDLE
#define RUNNING TVO_NODE_RUNNING
#define CANNOT_ARISE {NULL, TVO_NODE_OK, IDLE, IDLE, 0, 0}

/* Every transition of the node, lcm_types/README.md "Sessions" row by row (its "any" is both states). */
static const node_transition_t session_table[TVO_NODE_STATE_COUNT][TVO_NODE_EVENT_COUNT] = {
    [TVO_NODE_IDLE] = {
        /* any, a session message naming another boot: dropped, counted (wrong_boot), unanswered */
        [TVO_NODE_EVENT_WRONG_BOOT] = {drop_wrong_boot, TVO_NODE_OK, IDLE, IDLE, 0, 1},
        /* idle, START that passes every check: built and runs / any, START that fails: nothing changes */
        [TVO_NODE_EVENT_START] = {start_session, TVO_NODE_OK, RUNNING, IDLE, 1, 1},
        /* any, STOP of another id: ignored */
        [TVO_NODE_EVENT_STOP_OTHER] = {NULL, TVO_NODE_NO_SESSION, IDLE, IDLE, 1, 1},
        /* any, another action: ignored */
        [TVO_NODE_EVENT_OTHER_ACTION] = {NULL, TVO_NODE_UNKNOWN_ACTION, IDLE, IDLE, 1, 1},
        /* idle, sample or target: dropped, counted (idle), unanswered */
        [TVO_NODE_EVENT_SAMPLE] = {drop_idle, TVO_NODE_OK, IDLE, IDLE, 0, 1},
        [TVO_NODE_EVENT_TARGET] = {drop_idle, TVO_NODE_OK, IDLE, IDLE, 0, 1},
        /* no id runs, so none repeats, conflicts, stops or is another's */
        [TVO_NODE_EVENT_START_REPEAT] = CANNOT_ARISE,
        [TVO_NODE_EVENT_START_CONFLICT] = CANNOT_ARISE,
        [TVO_NODE_EVENT_STOP] = CANNOT_ARISE,
        [TVO_NODE_EVENT_SAMPLE_OTHER] = CANNOT_ARISE,
        [TVO_NODE_EVENT_TARGET_OTHER] = CANNOT_ARISE,
    },
    [TVO_NODE_RUNNING] = {
        /* any, a session message naming another boot: dropped, counted (wrong_boot); A runs on */
        [TVO_NODE_EVENT_WRONG_BOOT] = {drop_wrong_boot, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
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
        /* running A, sample of A: gathered; the period's last robot's is served or refused ("Timing") */
        [TVO_NODE_EVENT_SAMPLE] = {serve_sample, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
        /* running A, sample or target of another session id: ignored, counted (other_session) */
        [TVO_NODE_EVENT_SAMPLE_OTHER] = {count_other_session, TVO_NODE_OK, RUNNING, RUNNING, 0, 1},
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

void tvo_node_dispatch(tvo_node_t *node, tvo_node_event_t event, const tvo_node_input_t *in)
{
    node->last_event = event;
    if ((uint32_t)event >= (uint32_t)TVO_NODE_EVENT_COUNT) {
        return;
    }
    const node_transition_t *t = &session_table[node->state][event];
    if (!t->reachable) {
        return; /* the classification, which knows the state, does not give it */
    }
    tvo_session_reject_t why = {t->answer, TVO_OK, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    const uint8_t before = node->state;
    const int taken = (t->action != NULL) ? t->action(node, in, &why) == TVO_OK : t->answer == TVO_NODE_OK;
    node->state = taken ? t->next_if_taken : t->next_if_refused;
    if (t->acked) {
        tvo_node_publish_ack(node, in->session, &why);
    }
    /* A START taken or a session ended: the plants hear the node's new state at once. */
    if (taken && (event == TVO_NODE_EVENT_START || (event == TVO_NODE_EVENT_STOP && before == TVO_NODE_RUNNING))) {
        tvo_node_announce(node, in->now_us);
    }
}
