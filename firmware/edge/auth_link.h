/*
 * An authenticated link in front of the node: received frames are opened (auth.h) before the node
 * sees them, and everything the node publishes is signed on its way out. A frame that does not open
 * is dropped unanswered (a forger learns nothing) and counted in the node's counters
 * (node_counters_t.unauthenticated / .replayed); the node never sees it, so it changes nothing.
 * Transport-independent, like node.c: the LCM process and the board's PIL program both use it.
 */
#ifndef TVO_AUTH_LINK_H
#define TVO_AUTH_LINK_H

#include <stdint.h>

#include "auth.h"
#include "node.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tvo_auth_t auth;
    tvo_node_publish_fn transport_publish;   /* where signed frames go (LCM, a serial link) */
    void *transport_context;
    uint8_t frame[TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES];
    uint32_t unsigned_drops;                 /* outgoing messages that could not be signed (not sent) */
    tvo_auth_status_t last_refusal;          /* why the last received frame was dropped */
} tvo_auth_link_t;

/**
 * A keyed link that signs as own_sender_id from first_counter on and forwards to transport_publish.
 * Give tvo_node_init tvo_auth_link_publish and the link as its publisher; counters that continue over
 * restarts: tvo_auth_start_at or tvo_auth_follow_clock on link->auth.
 */
tvo_auth_status_t tvo_auth_link_init(tvo_auth_link_t *link, const uint8_t key[TVO_AUTH_KEY_BYTES],
                                     uint32_t own_sender_id, uint64_t first_counter,
                                     tvo_node_publish_fn transport_publish, void *transport_context);

/** The node's publisher (tvo_node_publish_fn; context: the link): signs and forwards, or drops and counts. */
void tvo_auth_link_publish(void *link, int channel, const uint8_t *data, uint32_t length);

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
