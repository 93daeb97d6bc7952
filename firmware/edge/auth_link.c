/* The authenticated link in front of the node: open what arrives, sign what leaves. */
#include "auth_link.h"

#include <string.h>

#include "channels.h"

static void count(int32_t *counter)
{
    if (*counter < INT32_MAX) {
        ++*counter;
    }
}

tvo_auth_status_t tvo_auth_link_init(tvo_auth_link_t *link, const uint8_t key[TVO_AUTH_KEY_BYTES],
                                     uint32_t own_sender_id, uint64_t first_counter,
                                     tvo_node_publish_fn transport_publish, void *transport_context)
{
    if (link == NULL || transport_publish == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    memset(link, 0, sizeof(*link));
    const tvo_auth_status_t status = tvo_auth_init(&link->auth, key, own_sender_id, first_counter);
    if (status != TVO_AUTH_OK) {
        return status;
    }
    link->transport_publish = transport_publish;
    link->transport_context = transport_context;
    link->last_refusal = TVO_AUTH_OK;
    return TVO_AUTH_OK;
}

void tvo_auth_link_publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    tvo_auth_link_t *link = (tvo_auth_link_t *)context;
    const char *name = tvo_node_channel_name(channel);
    size_t signed_length = 0u;
    if (link == NULL || data == NULL || name == NULL || length > TVO_NODE_BUFFER_BYTES) {
        if (link != NULL) {
            link->unsigned_drops += 1u;
        }
        return;
    }
    memcpy(link->frame, data, length);
    if (tvo_auth_sign(&link->auth, name, link->frame, length, sizeof(link->frame), &signed_length) != TVO_AUTH_OK) {
        link->unsigned_drops += 1u; /* never sent unsigned: a keyed node does not fall back */
        return;
    }
    link->transport_publish(link->transport_context, channel, link->frame, (uint32_t)signed_length);
}

int tvo_auth_link_receive(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame, uint32_t length,
                          int64_t now_us)
{
    if (link == NULL || node == NULL || frame == NULL) {
        return 0;
    }
    const char *name = tvo_node_channel_name(channel);
    size_t message_length = 0u;
    const tvo_auth_status_t status = (name != NULL)
                                         ? tvo_auth_open(&link->auth, name, frame, length, &message_length)
                                         : TVO_AUTH_ERR_ARGUMENT;
    if (status != TVO_AUTH_OK) {
        link->last_refusal = status;
        count(status == TVO_AUTH_ERR_REPLAY ? &node->counters.replayed : &node->counters.unauthenticated);
        return 0;
    }
    return tvo_node_handle(node, channel, frame, (uint32_t)message_length, now_us);
}
