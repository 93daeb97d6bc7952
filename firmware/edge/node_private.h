/*
 * How the node's files call one another (not part of the node's API, node.h): each file does one job.
 *   node.c           the entry points: a frame's length and decoding, what it is (an event), counters
 *   node_sessions.c  the session table: what each event does in each state, the boot check, the acks
 *   node_start.c     a session built from a START (every check, the core's inits), in a spare slot
 *   node_period.c    samples gathered per robot, prediction, the period's step; streamed targets;
 *                    the CLOCK_NODE timer
 *   node_publish.c   commands (one per driven robot), telemetry at its rate, acks, announcements
 */
#ifndef TVO_NODE_PRIVATE_H
#define TVO_NODE_PRIVATE_H

#include "node.h"

/** A decoded message and when it arrived. */
typedef struct {
    int channel;
    const tvo_lcm_session_t *session;          /* TVO_SESSION, else NULL */
    const tvo_lcm_unicycle_sample_t *unicycle; /* TVO_SAMPLE, else NULL */
    const tvo_lcm_chain_sample_t *chain;       /* TVO_CHAIN_SAMPLE, else NULL */
    const tvo_lcm_target_t *target;            /* TVO_TARGET, else NULL */
    uint64_t content_hash;                     /* a session message's, past its utime */
    int64_t now_us;                            /* clamped to the wire's range */
} tvo_node_input_t;

/* ---- node.c ---- */
/** Adds one to a counter that saturates at INT32_MAX (signed overflow would be undefined). */
void tvo_node_count(int32_t *counter);
/** Counts a refusal under its wire status and keeps it as the last one (for the transport's log). */
void tvo_node_count_refusal(tvo_node_t *node, int32_t wire_status);
/** The running slot (the state says whether it runs). */
tvo_node_session_t *tvo_node_running_slot(tvo_node_t *node);

/* ---- node_sessions.c ---- */
/** 1 if a session message names this node's boot (node_boot_id of its robot, or of every robot). */
int tvo_node_names_this_boot(const tvo_node_t *node, const tvo_lcm_session_t *msg);
/** The event a session message naming this boot is, given what runs. */
tvo_node_event_t tvo_node_session_event(const tvo_node_t *node, const tvo_lcm_session_t *msg, uint64_t content_hash);
/** A sample's or target's event: of the running session (when idle, of any), or another's. */
tvo_node_event_t tvo_node_stream_event(const tvo_node_t *node, int32_t session_id, tvo_node_event_t own,
                                       tvo_node_event_t other);
/** The one place a message changes the node's state: its action, the table's next state, the ack. */
void tvo_node_dispatch(tvo_node_t *node, tvo_node_event_t event, const tvo_node_input_t *in);

/* ---- node_start.c ---- */
/** Builds a session from a START into `s` (the spare slot; the running one is not touched). */
tvo_status_t tvo_node_build_session(tvo_node_session_t *s, const tvo_lcm_session_t *msg, uint64_t content_hash,
                                    int64_t now_us, tvo_session_reject_t *why);

/* ---- node_period.c ---- */
/** A sample of the running session: gathered, or, the period's last robot's, the period served. */
void tvo_node_serve_sample(tvo_node_t *node, const tvo_node_input_t *in);
/** A streamed target sample of the running session: TVO_OK if taken. */
tvo_status_t tvo_node_take_target(tvo_node_t *node, const tvo_node_input_t *in);
/** The CLOCK_NODE timer at now_us (the core counts missed periods; its stop is published); returns
 *  the running schedule's next deadline. */
int64_t tvo_node_serve_timer(tvo_node_t *node, int64_t now_us);

/* ---- node_publish.c ---- */
/** The ack of a session message, naming the session that runs after it. */
void tvo_node_publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, const tvo_session_reject_t *why);
/**
 * A period's answer: `cmd` to every robot the node drives, stamped `stamp`; then, if the answered
 * sequence is a multiple of the session's telemetry_every, one telemetry per driven robot
 * (predicted: robots the period predicted). Counts the safe stops and speed mismatches it carries.
 */
void tvo_node_publish_answer(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                             const tvo_step_stamp_t *stamp, int32_t predicted);
/** The node's own safe stop (the CLOCK_NODE timer's): to every driven robot, no telemetry. */
void tvo_node_publish_own_stop(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                               const tvo_step_stamp_t *stamp);
/** The node's announcement (node_status_t) at now_us; the next is due a state's period later. */
void tvo_node_announce(tvo_node_t *node, int64_t now_us);

#endif /* TVO_NODE_PRIVATE_H */
