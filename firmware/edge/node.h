/*
 * The firmware node, independent of the transport: encoded LCM messages and the node's own clock
 * in, encoded messages out through a publish callback. tvo_firmware_node runs it behind LCM on the
 * host; the processor-in-the-loop program runs the same code on the microcontroller behind a
 * serial link. README.md ("Sessions", "Timing", "Writing your own plant") is the contract; in short:
 *
 *   TVO_SESSION      START builds a session in a spare slot and switches to it only if every check
 *                    passed (a refused START changes nothing); a repeat of the running START is
 *                    acked again; the running id with other content is refused; STOP ends it.
 *   TVO_MEASUREMENT  (of the running session) one answer per measurement: the controller's command
 *                    applied at the period the sample serves, or, if refused, the command in force
 *                    with the reason; nothing from a refused message is kept. The first accepted
 *                    measurement chooses the barrier slack s0 (the paper's rule).
 *   TVO_TARGET       a streamed target sample.
 *   timer            (CLOCK_NODE) each period that passed without an accepted measurement is counted
 *                    by the core (tvo_controller_miss); once its watchdog stops the robots, a safe
 *                    stop stamped now, every period until measurements are accepted again.
 *
 * Times: the node's clock now_us is int64 microseconds, monotonic, in [0, TVO_WIRE_TIME_MAX_US].
 * Every integer from the wire is range-checked before arithmetic (session_codec.h).
 */
#ifndef TVO_NODE_H
#define TVO_NODE_H

#include <stdint.h>

#include "channels.h"
#include "edge_controller.h"
#include "tvo_lcm_node_counters_t.h"
#include "tvo_lcm_target_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Encode buffer size: command, telemetry and ack are each well under 1 kB encoded. */
#define TVO_NODE_BUFFER_BYTES 2048

/** tvo_node_poll's answer when no deadline is pending. */
#define TVO_NODE_NO_DEADLINE INT64_MAX

typedef void (*tvo_node_publish_fn)(void *context, int channel, const uint8_t *data, uint32_t length);

/** A session: its controller and problem, its timing, and where its schedule stands. */
typedef struct {
    tvo_edge_controller_t controller;
    tvo_problem_t problem;             /* objective, targets and constraint terms the controller points into */
    tvo_session_timing_t timing;
    int64_t session_id;
    uint64_t content_hash;             /* of the START past its utime: a repeat is recognised */
    int64_t start_utime;               /* CLOCK_PLANT: the plant's clock at the START (a repeat's, or the vote's, if later): the first sample's window */
    int64_t offset_us;                 /* schedule clock minus plant clock: 0 in CLOCK_PLANT */
    int64_t epoch_schedule_us;         /* the epoch on the schedule's clock */
    uint8_t has_accepted;              /* a measurement was accepted (anchors sequence and watchdog) */
    int64_t last_period;               /* period index j of the last accepted measurement */
    int64_t last_sequence;             /* its sequence */
    uint32_t refused_in_row;           /* CLOCK_PLANT: refusals since the last accepted measurement */
    int64_t next_miss_period;          /* CLOCK_NODE: the first period not yet served or counted as missed */
    int64_t anchor_candidate_us;       /* what refused measurements agree on, and how many in a row: */
    uint8_t anchor_votes;              /*   CLOCK_NODE the clock offset, CLOCK_PLANT the sequence numbering */
} tvo_node_session_t;

typedef struct {
    tvo_node_session_t slot[2];              /* the running session and a spare to build a START in */
    uint8_t running;                         /* index of the running slot */
    uint8_t has_session;
    union {                                  /* the message being handled: decoded in place, not on the stack */
        tvo_lcm_session_t session;
        tvo_lcm_measurement_t measurement;
        tvo_lcm_target_t target;
    } rx;
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];   /* encode buffer: publishing allocates nothing */
    tvo_node_publish_fn publish;
    void *publish_context;
    uint8_t stop_requested;                  /* a STOP ended the running session */
    tvo_lcm_node_counters_t counters;        /* since the running session started (in telemetry) */
    tvo_lcm_session_ack_t last_ack;          /* the last ack published, for the transport's log */
    uint32_t acks;                           /* acks published since init */
    tvo_status_t last_refusal;               /* why the last refused measurement was refused */
    tvo_status_t last_target_status;         /* outcome of the last streamed target sample */
} tvo_node_t;

/** 0 if the encode buffer holds every message the node publishes (sizes are constants). */
int tvo_node_check_buffer(void);

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context);

/**
 * Handles one encoded message on `channel` at node time now_us. Returns the channel it was, or 0
 * if it is not one the node takes or did not decode (counted in counters.undecodable).
 */
int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us);

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
