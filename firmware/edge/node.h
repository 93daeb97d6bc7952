/*
 * The firmware node, independent of the transport: encoded LCM messages and the node's own clock
 * in, encoded messages out through a publish callback. tvo_firmware_node runs it behind LCM on the
 * host; the processor-in-the-loop program runs the same code on the microcontroller behind a
 * serial link. One node drives every robot of its sessions (own_robot -1) or one robot of a fleet
 * (own_robot k): the same program on the same wire, which evaluates the joint law either way and
 * publishes the rows of the robots it drives. lcm_types/README.md ("Sessions", "Timing", "Writing
 * your own plant") is the contract; in short:
 *
 *   TVO_NODE          (out) the node's announcement (node_status_t: its boot, own robot, state,
 *                     counters since it started), at the first poll, every 250 ms idle, every 1 s
 *                     running, and at once when a START is taken or a STOP ends the session.
 *   TVO_SESSION       a START or STOP that names another boot of this node (node_boot_id) is dropped
 *                     unanswered (counted: wrong_boot). Else: START builds a session in a spare slot
 *                     and switches to it only if every check passed (a refused START changes
 *                     nothing); a repeat of the running START is acked again; the running id with
 *                     other content is refused; STOP ends it.
 *   TVO_SAMPLE        one robot's sample (TVO_CHAIN_SAMPLE for a chain session) of the running session:
 *                     gathered per robot; the last robot's (robot_count - 1) steps the period with
 *                     every robot's sample of that period, a missing one predicted (CLOCK_PLANT);
 *                     one command per driven robot answers it (the computed one, or the command in
 *                     force with the refusal's reason): nothing from a refused period is kept.
 *                     Telemetry (one per driven robot) follows the answer to every telemetry_every-th
 *                     sequence. While idle: dropped, counted (idle).
 *   TVO_TARGET        one robot's streamed target sample.
 *   timer             (CLOCK_NODE) each period that passed without an accepted sample is counted by
 *                     the core (tvo_controller_miss); once its watchdog stops the robots, a safe stop
 *                     per driven robot, stamped now, every period until samples are accepted again.
 *
 * The node's files, one job each, in layers: each calls only the files listed below it, through
 * their private headers (node_<file>.h), and none calls node.c.
 *   node.c           these entry points: a frame's size and decoding, the event it is; the timer
 *   node_sessions.c  the session table: what each event does in each state; the boot check
 *   node_period.c    samples gathered per robot, prediction, the period's step; streamed targets;
 *                    the CLOCK_NODE timer's misses
 *   node_start.c     a session built from a START (every check, the core's inits) in a spare slot
 *   node_publish.c   commands (one per driven robot), telemetry at its rate, acks, announcements
 *   node_state.c     the node's state as every file reads and counts it: counters, the running session
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
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_target_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Encode buffer size: every message the node publishes fits (tvo_node_check_buffer; node_status_t,
 *  the largest, is 211 bytes). */
#define TVO_NODE_BUFFER_BYTES 256

/** tvo_node_poll's answer when no deadline is pending: a NULL or unusable node's (a node always has
 *  its next announcement). */
#define TVO_NODE_NO_DEADLINE TVO_SCHEDULE_NO_DEADLINE

/** The most robots a session of this node may have: the build's, within the wire's. */
#define TVO_NODE_MAX_ROBOTS (TVO_MAX_ROBOTS < TVO_LCM_SESSION_T_MAX_ROBOTS ? TVO_MAX_ROBOTS : TVO_LCM_SESSION_T_MAX_ROBOTS)

typedef void (*tvo_node_publish_fn)(void *context, int channel, const uint8_t *data, uint32_t length);

/** Frames a transport (an authenticated link) dropped before the node saw them: counted in its counters. */
typedef enum {
    TVO_NODE_DROP_MALFORMED = 0,      /* not a message of its channel (length, fingerprint) */
    TVO_NODE_DROP_UNAUTHENTICATED = 1, /* keyed: the tag did not verify */
    TVO_NODE_DROP_REPLAYED = 2,       /* keyed: the counter was not above its sender's last */
    TVO_NODE_DROP_COUNT
} tvo_node_drop_t;

/** The node's states (lcm_types/README.md "Sessions"): idle, or running one session. */
typedef enum {
    TVO_NODE_IDLE = 0,
    TVO_NODE_RUNNING = 1,
    TVO_NODE_STATE_COUNT
} tvo_node_state_t;

/** What a decoded message is to the node in its state: a row of the session table (node_sessions.c). */
typedef enum {
    TVO_NODE_EVENT_NONE = 0,           /* nothing handled yet, or a message that did not decode */
    TVO_NODE_EVENT_WRONG_BOOT,         /* a session message that names another boot of this node */
    TVO_NODE_EVENT_START,              /* START of an id that is not running */
    TVO_NODE_EVENT_START_REPEAT,       /* START of the running id, the same content (any utime) */
    TVO_NODE_EVENT_START_CONFLICT,     /* START of the running id with other content */
    TVO_NODE_EVENT_STOP,               /* STOP of the running id */
    TVO_NODE_EVENT_STOP_OTHER,         /* STOP of an id that is not running */
    TVO_NODE_EVENT_OTHER_ACTION,       /* a session message that is neither START nor STOP */
    TVO_NODE_EVENT_SAMPLE,             /* a robot's sample of the running session; when idle, of any */
    TVO_NODE_EVENT_SAMPLE_OTHER,       /* of another session id than the running one */
    TVO_NODE_EVENT_TARGET,             /* a streamed target sample of the running session; when idle, of any */
    TVO_NODE_EVENT_TARGET_OTHER,       /* of another session id than the running one */
    TVO_NODE_EVENT_COUNT
} tvo_node_event_t;

/** The joint command a robot's prediction follows: in force from the period its sequence serves on. */
typedef struct {
    int64_t sequence;                        /* the sample it answered; -1: none (robots at rest) */
    double speed_mps[TVO_MAX_ROBOTS];
    double turn_rate_radps[TVO_MAX_ROBOTS];
} tvo_node_joint_command_t;

/** What the running session knows of its robots between periods (node_period.c). */
typedef struct {
    tvo_lcm_unicycle_sample_t pending[TVO_MAX_ROBOTS]; /* per robot: its newest sample of a period not yet stepped */
    uint8_t has_pending[TVO_MAX_ROBOTS];
    tvo_step_robot_state_t known[TVO_MAX_ROBOTS];      /* per robot: its last state a committed period used */
    uint8_t known_measured[TVO_MAX_ROBOTS];            /* known[r] came from r's own sample */
    int64_t heard[TVO_MAX_ROBOTS];                     /* per robot: the sequence of its newest sample taken; -1 none */
    tvo_node_joint_command_t commands[2];              /* [0] the newest committed joint command, [1] the one before */
    int64_t last_step;                                 /* sequence of the last committed period; -1 none */
} tvo_node_gathering_t;

/** A session: its controller and problem, its schedule, and what it gathered of its robots. */
typedef struct {
    tvo_edge_controller_t controller;
    tvo_problem_t problem;             /* objective, targets and constraint terms the controller points into */
    tvo_schedule_t schedule;
    tvo_node_gathering_t gathering;
    int32_t session_id;
    uint64_t content_hash;             /* of the START past its utime: a repeat is recognised */
} tvo_node_session_t;

/** A period's scratch (node_period.c): written before it is read, nothing between periods. */
typedef struct {
    tvo_step_period_t rows;                  /* every robot's row of the joint measurement */
    tvo_step_robot_state_t next[TVO_MAX_ROBOTS]; /* the robots' states the period commits, if it does */
    uint8_t measured[TVO_MAX_ROBOTS];        /* next[r] is r's own sample of the period */
    int64_t heard[TVO_MAX_ROBOTS];           /* the sequence of r's newest sample the period takes */
    int32_t predicted;                       /* robots predicted (missing or late) */
    int unheard;                             /* a robot could not be predicted */
    tvo_edge_measurement_t measurement;
    tvo_edge_command_t command;
} tvo_node_period_work_t;

typedef struct {
    int8_t own_robot;                        /* the robot this node drives, or -1: every robot */
    int64_t boot_id;                         /* > 0, never the same twice for this node */
    tvo_node_session_t slot[2];              /* the running session and a spare to build a START in */
    uint8_t running;                         /* index of the running slot */
    uint8_t state;                           /* tvo_node_state_t */
    union {                                  /* the message being handled: decoded in place, not on the stack */
        tvo_lcm_session_t session;
        tvo_lcm_unicycle_sample_t unicycle;
        tvo_lcm_chain_sample_t chain;
        tvo_lcm_target_t target;
    } rx;
    tvo_node_period_work_t work;
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];   /* encode buffer: publishing allocates nothing */
    tvo_lcm_node_status_t status;            /* the announcement being encoded */
    tvo_node_publish_fn publish;
    void *publish_context;
    uint8_t stop_requested;                  /* a STOP ended the running session */
    uint8_t announced;                       /* an announcement went out (the first poll makes one) */
    int64_t next_announcement_us;            /* node clock */
    tvo_lcm_node_counters_t counters;        /* since init (node_status_t.counters) */
    tvo_lcm_session_ack_t last_ack;          /* the last ack published, for the transport's log */
    uint32_t acks;                           /* acks published since init */
    tvo_node_event_t last_event;             /* what the last decoded message was, for the transport's log */
    int32_t last_refusal;                    /* why the last sample was refused (command_header_t.STATUS_*) */
    int32_t last_target_status;              /* how the last streamed target sample was taken (command_header_t.STATUS_*) */
} tvo_node_t;

/**
 * A node of boot boot_id (> 0) driving own_robot (0 .. TVO_NODE_MAX_ROBOTS - 1), or every robot of
 * its sessions (-1), publishing through publish. Returns 0, or -1 for a NULL node or publish, or an
 * argument out of range (the node is then unusable: every call on it changes nothing).
 */
int tvo_node_init(tvo_node_t *node, int8_t own_robot, int64_t boot_id, tvo_node_publish_fn publish,
                  void *publish_context);

/**
 * Handles one encoded message on `channel` at node time now_us. Returns the channel it was, or 0 if
 * it is not one the node takes (not counted), or it is no message of its channel (counted:
 * malformed; a frame whose length is not the channel's message size, or that does not decode).
 */
int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us);

/**
 * The node's timer: publishes what is due at now_us (its announcement; a CLOCK_NODE session's safe
 * stops) and returns the next deadline on the node's clock. Call it at least at every deadline it
 * returns; calling it more often is harmless.
 */
int64_t tvo_node_poll(tvo_node_t *node, int64_t now_us);

/** Counts a frame a transport dropped before the node saw it (TVO_NODE_DROP_*). */
void tvo_node_count_drop(tvo_node_t *node, tvo_node_drop_t why);

/** The node's counters since init (node_status_t.counters), or NULL for a NULL node. */
const tvo_lcm_node_counters_t *tvo_node_counters(const tvo_node_t *node);

/** 1 if a STOP ended the running session (tvo_firmware_node then exits), else 0. */
int tvo_node_stop_requested(const tvo_node_t *node);

/** The running session, or NULL. */
const tvo_node_session_t *tvo_node_session(const tvo_node_t *node);

/** One transition of the session table: the state after a message, if its action took effect or not. */
typedef struct {
    tvo_node_state_t next_if_taken;
    tvo_node_state_t next_if_refused;
    uint8_t acked;                           /* answered with a session ack */
    uint8_t reachable;                       /* 0: the event cannot arise in this state */
} tvo_node_transition_info_t;

/** The session table's cell for (state, event) (tests and logs); 0 unless both are in range. */
int tvo_node_transition_info(tvo_node_state_t state, tvo_node_event_t event, tvo_node_transition_info_t *info);

/** 0 if the encode buffer holds every message the node publishes and the channel table's sizes are
 *  the generated code's (a start-up self-check), else -1. */
int tvo_node_check_buffer(void);

#ifdef __cplusplus
}
#endif

#endif /* TVO_NODE_H */
