/*
 * An authenticated link in front of the node: received frames are checked and opened (auth.h) before
 * the node sees them, and everything the node publishes is signed on its way out. A frame that fails
 * is dropped unanswered (a forger learns nothing), counted in the node's counters
 * (tvo_node_count_drop: node_counters_t.malformed / .unauthenticated / .replayed) and changes nothing
 * else: the node never sees it. Cheapest refusal first, so a flood of forged frames costs at most one
 * tag computation each (lcm_types/README.md, "An authenticated bus"):
 *   1. a channel the node does not take                      malformed
 *   2. a length other than the channel's message + trailer    malformed
 *   3. another type's LCM fingerprint                         malformed
 *   4. a known sender's counter not above its last            replayed (no cryptography)
 *   5. the tag                                                unauthenticated
 *   6. a new sender when the sender table is full             unauthenticated (TVO_AUTH_MAX_SENDERS)
 * then the sender's counter is remembered and the message goes to tvo_node_handle.
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

typedef struct {
    tvo_auth_t auth;
    uint64_t fingerprint[TVO_NODE_CH_LAST + 1]; /* of each input channel's type (0: not an input), looked up once */
    uint8_t name_length[TVO_NODE_CH_LAST + 1];  /* each channel's name's bytes (0: no channel), counted once */
    tvo_node_publish_fn transport_publish;   /* where signed frames go (LCM, a serial link) */
    void *transport_context;
    uint8_t frame[TVO_NODE_BUFFER_BYTES + TVO_AUTH_TRAILER_BYTES];
    uint32_t unsigned_drops;                 /* outgoing messages that could not be signed (not sent) */
    tvo_auth_status_t last_refusal;          /* why the last dropped frame was (ARGUMENT: malformed) */
    uint32_t drops;                          /* received frames dropped since init (the node counts each by kind) */
} tvo_auth_link_t;

/**
 * A keyed link of the node of boot boot_id that signs as own_sender_id with counters
 * (boot_id << 40) | n (tvo_auth_count_from_boot) and forwards signed frames to transport_publish.
 * Give tvo_node_init tvo_auth_link_publish and the link as its publisher. TVO_AUTH_ERR_ARGUMENT for a
 * NULL link, key or transport, or a boot id out of range.
 */
tvo_auth_status_t tvo_auth_link_init(tvo_auth_link_t *link, const uint8_t key[TVO_AUTH_KEY_BYTES],
                                     uint32_t own_sender_id, int64_t boot_id, tvo_node_publish_fn transport_publish,
                                     void *transport_context);

/** The node's publisher (tvo_node_publish_fn; context: the link): signs and forwards, or drops and counts. */
void tvo_auth_link_publish(void *link, int channel, const uint8_t *data, uint32_t length);

/**
 * Checks and opens a received frame on `channel` in the order above: on TVO_AUTH_OK *message_length
 * is the message's bytes (the frame's start). Else the frame is counted in the node's counters and
 * must be dropped unanswered; the return says why (a malformed frame: TVO_AUTH_ERR_ARGUMENT).
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
