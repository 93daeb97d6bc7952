/*
 * An authenticated link in front of the node: received frames are opened (auth.h) before the node
 * sees them, and everything the node publishes is signed on its way out. A frame that does not open
 * is dropped unanswered (a forger learns nothing) and counted in the node's counters
 * (node_counters_t.unauthenticated / .replayed); the node never sees it, so it changes nothing.
 * Transport-independent, like node.c: the LCM process and the board's PIL program both use it.
 */
#ifndef TVO_AUTH_LINK_H
#define TVO_AUTH_LINK_H

#include <stddef.h>
#include <stdint.h>

#include "auth.h"
#include "node.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Writes the LCM name of `channel` (authenticated with the message); 0, or -1 if unknown. */
typedef int (*tvo_auth_link_namer_fn)(void *context, int channel, char *out, size_t size);

/** Longest channel name a link signs or opens, with its terminator. */
#define TVO_AUTH_LINK_NAME_BYTES 32u

typedef struct {
    tvo_auth_t auth;
    tvo_auth_link_namer_fn namer;            /* NULL: the node's channels (tvo_node_channel_name) */
    void *namer_context;
    tvo_node_publish_fn transport_publish;   /* where signed frames go (LCM, a serial link) */
    void *transport_context;
    uint8_t frame[TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES];
    uint32_t unsigned_drops;                 /* outgoing messages that could not be signed (not sent) */
    tvo_auth_status_t last_refusal;          /* why the last received frame was dropped */
    uint32_t dropped_unauthenticated;        /* since init (the node's counters restart with a session) */
    uint32_t dropped_replayed;
} tvo_auth_link_t;

/**
 * A keyed link that signs as own_sender_id from first_counter on and forwards to transport_publish.
 * Give tvo_node_init tvo_auth_link_publish and the link as its publisher; counters that continue over
 * restarts: tvo_auth_start_at or tvo_auth_follow_clock on link->auth.
 */
tvo_auth_status_t tvo_auth_link_init(tvo_auth_link_t *link, const uint8_t key[TVO_AUTH_KEY_BYTES],
                                     uint32_t own_sender_id, uint64_t first_counter,
                                     tvo_node_publish_fn transport_publish, void *transport_context);

/**
 * Names the link's channels with `namer` (a fleet node's carry its robot: fleet_link.h) instead of
 * the node's own; NULL restores those. Returns TVO_AUTH_ERR_ARGUMENT for a NULL link.
 */
tvo_auth_status_t tvo_auth_link_set_namer(tvo_auth_link_t *link, tvo_auth_link_namer_fn namer, void *namer_context);

/** The node's publisher (tvo_node_publish_fn; context: the link): signs and forwards, or drops and counts. */
void tvo_auth_link_publish(void *link, int channel, const uint8_t *data, uint32_t length);

/**
 * Opens a received frame on `channel`: on TVO_AUTH_OK *message_length is the message's bytes (the
 * frame's start); a refusal is counted in the node's counters and the link's totals, and the frame
 * must be dropped unanswered.
 */
tvo_auth_status_t tvo_auth_link_open(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame,
                                     uint32_t length, uint32_t *message_length);

/**
 * A received frame on `channel`: opened and handed to tvo_node_handle, or dropped and counted.
 * Returns tvo_node_handle's answer, or 0 for a dropped frame.
 */
int tvo_auth_link_receive(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame, uint32_t length,
                          int64_t now_us);

#ifdef __cplusplus
}
#endif

#endif /* TVO_AUTH_LINK_H */
