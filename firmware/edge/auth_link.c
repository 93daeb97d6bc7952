/* The authenticated link in front of the node: check and open what arrives, sign what leaves. */
#include "auth_link.h"

#include <string.h>

#include "channels.h"

static uint64_t get_be64(const uint8_t *p)
{
    const uint32_t high = ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | p[3];
    const uint32_t low = ((uint32_t)p[4] << 24) | ((uint32_t)p[5] << 16) | ((uint32_t)p[6] << 8) | p[7];
    return ((uint64_t)high << 32) | low;
}

tvo_auth_status_t tvo_auth_link_init(tvo_auth_link_t *link, const uint8_t key[TVO_AUTH_KEY_BYTES],
                                     uint32_t own_sender_id, int64_t boot_id, tvo_node_publish_fn transport_publish,
                                     void *transport_context)
{
    if (link == NULL || transport_publish == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    memset(link, 0, sizeof(*link));
    tvo_auth_status_t status = tvo_auth_init(&link->auth, key, own_sender_id, 1u);
    if (status == TVO_AUTH_OK) {
        status = tvo_auth_count_from_boot(&link->auth, boot_id);
    }
    if (status != TVO_AUTH_OK) {
        tvo_auth_clear(&link->auth);
        return status;
    }
    link->transport_publish = transport_publish;
    link->transport_context = transport_context;
    link->last_refusal = TVO_AUTH_OK;
    for (int channel = TVO_NODE_CH_FIRST; channel <= TVO_NODE_CH_LAST; ++channel) {
        const char *name = tvo_node_channel_name(channel);
        const size_t length = name != NULL ? strlen(name) : 0u;
        link->fingerprint[channel] = tvo_node_channel_is_input(channel) ? tvo_node_channel_fingerprint(channel) : 0u;
        link->name_length[channel] = (uint8_t)(length <= TVO_AUTH_MAX_CHANNEL_BYTES ? length : 0u);
    }
    return TVO_AUTH_OK;
}

void tvo_auth_link_publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    tvo_auth_link_t *link = (tvo_auth_link_t *)context;
    const char *name = tvo_node_channel_name(channel);
    size_t signed_length = 0u;
    if (link == NULL) {
        return;
    }
    if (data == NULL || name == NULL || length > TVO_NODE_BUFFER_BYTES) {
        link->unsigned_drops += 1u;
        return;
    }
    memcpy(link->frame, data, length);
    if (tvo_auth_sign_channel(&link->auth, name, link->name_length[channel], link->frame, length, sizeof(link->frame),
                              &signed_length) != TVO_AUTH_OK) {
        link->unsigned_drops += 1u; /* never sent unsigned: a keyed node does not fall back */
        return;
    }
    link->transport_publish(link->transport_context, channel, link->frame, (uint32_t)signed_length);
}

/* Counts a dropped frame in the node's counters and the link's total. */
static tvo_auth_status_t drop(tvo_auth_link_t *link, tvo_node_t *node, tvo_node_drop_t why, tvo_auth_status_t status)
{
    tvo_node_count_drop(node, why);
    link->drops += (link->drops < UINT32_MAX) ? 1u : 0u;
    link->last_refusal = status;
    return status;
}

tvo_auth_status_t tvo_auth_link_open(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame,
                                     uint32_t length, uint32_t *message_length)
{
    if (message_length != NULL) {
        *message_length = 0u;
    }
    if (link == NULL || node == NULL || message_length == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    /* 1-3: the frame's shape, for the price of a comparison or two (no cryptography). */
    if (frame == NULL || !tvo_node_channel_is_input(channel) ||
        length != tvo_node_channel_message_bytes(channel) + TVO_AUTH_TRAILER_BYTES ||
        get_be64(frame) != link->fingerprint[channel]) {
        return drop(link, node, TVO_NODE_DROP_MALFORMED, TVO_AUTH_ERR_ARGUMENT);
    }
    /* 4-6: a used counter before the tag, the tag, then room for a new sender (auth.c). */
    size_t opened = 0u;
    const tvo_auth_status_t status = tvo_auth_open_channel(&link->auth, tvo_node_channel_name(channel),
                                                          link->name_length[channel], frame, length, &opened);
    if (status != TVO_AUTH_OK) {
        return drop(link, node, status == TVO_AUTH_ERR_REPLAY ? TVO_NODE_DROP_REPLAYED : TVO_NODE_DROP_UNAUTHENTICATED,
                    status);
    }
    *message_length = (uint32_t)opened;
    return TVO_AUTH_OK;
}

int tvo_auth_link_receive(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame, uint32_t length,
                          int64_t now_us)
{
    uint32_t message_length = 0u;
    if (tvo_auth_link_open(link, node, channel, frame, length, &message_length) != TVO_AUTH_OK) {
        return 0;
    }
    return tvo_node_handle(node, channel, frame, message_length, now_us);
}
