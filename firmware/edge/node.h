/*
 * The firmware node's logic, independent of the transport: encoded LCM messages in, encoded LCM
 * messages out through a publish callback. tvo_firmware_node runs it behind LCM on the host; the
 * processor-in-the-loop program runs the same code on the microcontroller behind a serial link.
 *
 * Messages (package tvo_lcm) are decoded and encoded with lcm-gen's generated C, which allocates
 * nothing for these fixed-size types. Per message:
 *   TVO_SESSION      START builds the session (controller + problem) and is acknowledged on
 *                    TVO_SESSION_ACK (a repeated START is answered again, not restarted); STOP ends it.
 *   TVO_MEASUREMENT  one controller step; the command (applied at stamp + delay) on TVO_COMMAND and
 *                    what the controller computed on TVO_TELEMETRY. A jump in the sequence first runs
 *                    the core once per missed period without a measurement (the core holds the
 *                    previous command, as the plant did) and publishes those holding commands too.
 *                    The first usable measurement chooses the barrier slack s0 (the paper's rule).
 *   TVO_TARGET       a streamed target sample.
 */
#ifndef TVO_NODE_H
#define TVO_NODE_H

#include <stdint.h>

#include "channels.h"
#include "lcm_edge.h"

/** Encode buffer size: command, telemetry and ack are each well under 1 kB encoded. */
#define TVO_NODE_BUFFER_BYTES 2048

typedef void (*tvo_node_publish_fn)(void *context, int channel, const uint8_t *data, uint32_t length);

typedef struct {
    tvo_edge_session_t session;
    union {                                  /* the message being handled: decoded in place, not on the stack */
        tvo_lcm_session_t session;
        tvo_lcm_measurement_t measurement;
        tvo_lcm_target_t target;
    } rx;
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];   /* encode buffer: publishing allocates nothing */
    tvo_node_publish_fn publish;
    void *publish_context;
    uint8_t has_start;                       /* a START was processed (session.session_id is set) */
    uint8_t stop_requested;                  /* a STOP for this session arrived */
    uint32_t decode_errors;                  /* messages that did not decode */
    uint32_t target_errors;                  /* streamed target samples rejected */
    uint32_t slack_errors;                   /* first measurements the slack could not be chosen from */
    tvo_status_t last_target_status;
} tvo_node_t;

/** 0 if the encode buffer holds every message the node publishes (sizes are constants). */
int tvo_node_check_buffer(void);

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context);

/**
 * Handles one encoded message on `channel`. Returns the channel it was (or 0 if not ours or not
 * decodable: counted in decode_errors for ours).
 */
int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length);

#endif /* TVO_NODE_H */
