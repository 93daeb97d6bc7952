/*
 * The firmware node, independent of the transport: encoded LCM messages and the node's own clock
 * in, encoded messages out through a publish callback. tvo_firmware_node runs it behind LCM on the
 * host; the processor-in-the-loop program runs the same code on the microcontroller behind a
 * serial link. lcm_types/README.md ("Sessions", "Timing", "Writing your own plant") is the contract; in short:
 *
 *   TVO_SESSION      START builds a session in a spare slot and switches to it only if every check
 *                    passed (a refused START changes nothing); a repeat of the running START is
 *                    acked again; the running id with other content is refused; STOP ends it.
 *   TVO_MEASUREMENT  (of the running session) one answer per measurement: the controller's command
 *                    applied at the period the sample serves, or, if refused, the command in force
 *                    with the reason; nothing from a refused message is kept. The first accepted
 *                    measurement chooses the barrier slack s0 (the paper's rule, in the core's step).
 *   TVO_TARGET       a streamed target sample.
 *   timer            (CLOCK_NODE) each period that passed without an accepted measurement is counted
 *                    by the core (tvo_controller_miss); once its watchdog stops the robots, a safe
 *                    stop stamped now, every period until measurements are accepted again.
 *
 * What each message does in each state (idle, running) is one table in node.c, the README's
 * "Sessions" table row by row; which period a measurement serves is the session's schedule, one
 * object per clock mode (schedule.h).
 *
 * Times: the node's clock now_us is int64 microseconds, monotonic, in [0, TVO_WIRE_TIME_MAX_US].
 * Every integer from the wire is range-checked before arithmetic (session_codec.h).
 */
#ifndef TVO_NODE_H
#define TVO_NODE_H

#include <stdint.h>

#include "channels.h"
#include "edge_controller.h"
#include "schedule.h"
#include "tvo_lcm_node_counters_t.h"
#include "tvo_lcm_target_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Encode buffer size: command, telemetry and ack are each well under 1 kB encoded. */
#define TVO_NODE_BUFFER_BYTES 2048

/** tvo_node_poll's answer when no deadline is pending. */
#define TVO_NODE_NO_DEADLINE TVO_SCHEDULE_NO_DEADLINE

typedef void (*tvo_node_publish_fn)(void *context, int channel, const uint8_t *data, uint32_t length);

/**
 * Where a node's commands go instead of command_t (tvo_node_set_answer): a fleet link, which answers
 * with a row of the joint command. stamp: when, which session and measurement, and why
 * (tvo_step_wire_status); wire_flags: command_t.flags; command: every robot's row.
 */
typedef void (*tvo_node_answer_fn)(void *context, const tvo_step_stamp_t *stamp, uint32_t wire_flags,
                                   const tvo_command_t *command);

/** The node's states (lcm_types/README.md "Sessions"): idle, or running one session. */
typedef enum {
    TVO_NODE_IDLE = 0,
    TVO_NODE_RUNNING = 1,
    TVO_NODE_STATE_COUNT
} tvo_node_state_t;

/** What a decoded message is to the node in its state: a row of the session table (node.c). */
typedef enum {
    TVO_NODE_EVENT_NONE = 0,           /* nothing handled yet, or a message that did not decode */
    TVO_NODE_EVENT_START,              /* START of an id that is not running */
    TVO_NODE_EVENT_START_REPEAT,       /* START of the running id, the same content (any utime) */
    TVO_NODE_EVENT_START_CONFLICT,     /* START of the running id with other content */
    TVO_NODE_EVENT_STOP,               /* STOP of the running id */
    TVO_NODE_EVENT_STOP_OTHER,         /* STOP of an id that is not running */
    TVO_NODE_EVENT_OTHER_ACTION,       /* a session message that is neither START nor STOP */
    TVO_NODE_EVENT_MEASUREMENT,        /* of the running session; when idle, of any */
    TVO_NODE_EVENT_MEASUREMENT_OTHER,  /* of another session id than the running one */
    TVO_NODE_EVENT_TARGET,             /* a streamed target sample of the running session; when idle, of any */
    TVO_NODE_EVENT_TARGET_OTHER,       /* of another session id than the running one */
    TVO_NODE_EVENT_COUNT
} tvo_node_event_t;

/** A session: its controller and problem, and its schedule (clock mode, timing, where it stands). */
typedef struct {
    tvo_edge_controller_t controller;
    tvo_problem_t problem;             /* objective, targets and constraint terms the controller points into */
    tvo_schedule_t schedule;
    int64_t session_id;
    uint64_t content_hash;             /* of the START past its utime: a repeat is recognised */
} tvo_node_session_t;

typedef struct {
    tvo_node_session_t slot[2];              /* the running session and a spare to build a START in */
    uint8_t running;                         /* index of the running slot */
    uint8_t state;                           /* tvo_node_state_t */
    union {                                  /* the message being handled: decoded in place, not on the stack */
        tvo_lcm_session_t session;
        tvo_lcm_measurement_t measurement;
        tvo_lcm_target_t target;
    } rx;
    tvo_step_measurement_t measurement;      /* rx.measurement as the node judges it */
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];   /* encode buffer: publishing allocates nothing */
    tvo_node_publish_fn publish;
    void *publish_context;
    tvo_node_answer_fn answer;               /* NULL: commands go out as command_t */
    void *answer_context;
    uint8_t stop_requested;                  /* a STOP ended the running session */
    tvo_lcm_node_counters_t counters;        /* since the running session started (in telemetry) */
    tvo_lcm_session_ack_t last_ack;          /* the last ack published, for the transport's log */
    uint32_t acks;                           /* acks published since init */
    tvo_node_event_t last_event;             /* what the last decoded message was, for the transport's log */
    int32_t last_refusal;                    /* why the last measurement was refused (command_t.STATUS_*) */
    int32_t last_target_status;              /* how the last streamed target sample was taken (command_t.STATUS_*) */
} tvo_node_t;

/** One transition of the session table: the state after a message, if its action took effect or not. */
typedef struct {
    tvo_node_state_t next_if_taken;
    tvo_node_state_t next_if_refused;
    uint8_t acked;                           /* answered with a session ack */
    uint8_t reachable;                       /* 0: the event cannot arise in this state */
} tvo_node_transition_info_t;

/** The session table's cell for (state, event) (tests and logs); 0 unless both are in range. */
int tvo_node_transition_info(tvo_node_state_t state, tvo_node_event_t event, tvo_node_transition_info_t *info);

/** 0 if the encode buffer holds every message the node publishes (sizes are constants). */
int tvo_node_check_buffer(void);

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context);

/**
 * Commands go to `answer` instead of out as command_t, so that sessions may have as many robots as
 * the build drives (TVO_MAX_ROBOTS, beyond the wire's TVO_WIRE_MAX_ROBOTS) and measurements come from
 * tvo_node_measure: a fleet link's. Such a node serves unicycle sessions only; a session of more robots
 * than the wire carries takes no streamed targets, and its telemetry carries no per-output vectors.
 * Set it while the node is idle (before the first START). Returns 0, or -1 for a NULL node or
 * answer, or a node running a session.
 */
int tvo_node_set_answer(tvo_node_t *node, tvo_node_answer_fn answer, void *answer_context);

/** Most robots a session of this node may have: the build's with an answer, else also the wire's. */
uint8_t tvo_node_max_robots(const tvo_node_t *node);

/**
 * Handles one encoded message on `channel` at node time now_us. Returns the channel it was, or 0
 * if it is not one the node takes or did not decode (counted in counters.undecodable).
 */
int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us);

/**
 * A joint measurement already decoded (a fleet link's, gathered from per-robot samples), handled as
 * a measurement on TVO_MEASUREMENT is. Returns TVO_NODE_CH_MEASUREMENT, or 0 for a NULL argument.
 */
int tvo_node_measure(tvo_node_t *node, const tvo_step_measurement_t *measurement, int64_t now_us);

/**
 * The node's timer (CLOCK_NODE sessions): publishes what is due at now_us (a safe stop) and
 * returns the next deadline on the node's clock, or TVO_NODE_NO_DEADLINE. Call it at least at
 * every deadline it returns; calling it more often is harmless.
 */
int64_t tvo_node_poll(tvo_node_t *node, int64_t now_us);

/** The running session, or NULL. */
const tvo_node_session_t *tvo_node_session(const tvo_node_t *node);

#ifdef __cplusplus
}
#endif

#endif /* TVO_NODE_H */
