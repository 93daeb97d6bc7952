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

/* The link's name for a channel: the namer's, else the node's. */
static int channel_name(const tvo_auth_link_t *link, int channel, char out[TVO_AUTH_LINK_NAME_BYTES])
{
    if (link->namer != NULL) {
        return link->namer(link->namer_context, channel, out, TVO_AUTH_LINK_NAME_BYTES);
    }
    const char *name = tvo_node_channel_name(channel);
    const size_t length = (name != NULL) ? strlen(name) : 0u;
    if (length == 0u || length >= TVO_AUTH_LINK_NAME_BYTES) {
        return -1;
    }
    memcpy(out, name, length + 1u);
    return 0;
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

tvo_auth_status_t tvo_auth_link_set_namer(tvo_auth_link_t *link, tvo_auth_link_namer_fn namer, void *namer_context)
{
    if (link == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    link->namer = namer;
    link->namer_context = namer_context;
    return TVO_AUTH_OK;
}

void tvo_auth_link_publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    tvo_auth_link_t *link = (tvo_auth_link_t *)context;
    char name[TVO_AUTH_LINK_NAME_BYTES];
    size_t signed_length = 0u;
    if (link == NULL || data == NULL || length > TVO_NODE_BUFFER_BYTES || channel_name(link, channel, name) != 0) {
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

tvo_auth_status_t tvo_auth_link_open(tvo_auth_link_t *link, tvo_node_t *node, int channel, const uint8_t *frame,
                                     uint32_t length, uint32_t *message_length)
{
    if (message_length != NULL) {
        *message_length = 0u;
    }
    if (link == NULL || node == NULL || frame == NULL || message_length == NULL) {
        return TVO_AUTH_ERR_ARGUMENT;
    }
    char name[TVO_AUTH_LINK_NAME_BYTES];
    size_t opened = 0u;
    const tvo_auth_status_t status = (channel_name(link, channel, name) == 0)
                                         ? tvo_auth_open(&link->auth, name, frame, length, &opened)
                                         : TVO_AUTH_ERR_ARGUMENT;
    if (status != TVO_AUTH_OK) {
        const int replay = status == TVO_AUTH_ERR_REPLAY;
        link->last_refusal = status;
        count(replay ? &node->counters.replayed : &node->counters.unauthenticated);
        if (replay) {
            link->dropped_replayed += (link->dropped_replayed < UINT32_MAX) ? 1u : 0u;
        } else {
            link->dropped_unauthenticated += (link->dropped_unauthenticated < UINT32_MAX) ? 1u : 0u;
        }
        return status;
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
