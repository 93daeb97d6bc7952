/*
 * The node's entry points (node.h): a frame is checked against its channel's one message size,
 * decoded once in place, classified into an event, and the session table (node_sessions.c) says what
 * it does in the node's state. The timer announces the node and serves a CLOCK_NODE session's misses.
 */
#include "node_period.h"
#include "node_publish.h"
#include "node_sessions.h"
#include "node_state.h"

#include <string.h>

#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_unicycle_command_t.h"

/* Each published type's encoded size, against the channel table's (the session's, 11 kB, is checked
 * by test_channels: not on a board's stack). */
int tvo_node_check_buffer(void)
{
    tvo_lcm_unicycle_command_t command;
    tvo_lcm_chain_command_t chain;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_session_ack_t ack;
    tvo_lcm_node_status_t status;
    memset(&command, 0, sizeof(command));
    memset(&chain, 0, sizeof(chain));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&ack, 0, sizeof(ack));
    memset(&status, 0, sizeof(status));
    const int sizes[] = {tvo_lcm_unicycle_command_t_encoded_size(&command), tvo_lcm_chain_command_t_encoded_size(&chain),
                         tvo_lcm_telemetry_t_encoded_size(&telemetry), tvo_lcm_session_ack_t_encoded_size(&ack),
                         tvo_lcm_node_status_t_encoded_size(&status)};
    const int channels[] = {TVO_NODE_CH_COMMAND, TVO_NODE_CH_CHAIN_COMMAND, TVO_NODE_CH_TELEMETRY,
                            TVO_NODE_CH_SESSION_ACK, TVO_NODE_CH_NODE};
    for (size_t i = 0; i < sizeof(sizes) / sizeof(sizes[0]); ++i) {
        if (sizes[i] <= 0 || sizes[i] > TVO_NODE_BUFFER_BYTES ||
            (uint32_t)sizes[i] != tvo_node_channel_message_bytes(channels[i])) {
            return -1;
        }
    }
    return 0;
}

int tvo_node_init(tvo_node_t *node, int8_t own_robot, int64_t boot_id, tvo_node_publish_fn publish,
                  void *publish_context)
{
    if (node == NULL) {
        return -1;
    }
    memset(node, 0, sizeof(*node)); /* boot_id 0: unusable until a good init */
    if (publish == NULL || boot_id <= 0 || own_robot < -1 || own_robot >= TVO_NODE_MAX_ROBOTS) {
        return -1;
    }
    node->own_robot = own_robot;
    node->boot_id = boot_id;
    node->state = TVO_NODE_IDLE;
    node->publish = publish;
    node->publish_context = publish_context;
    node->last_target_status = TVO_LCM_COMMAND_HEADER_T_STATUS_OK;
    return 0;
}

void tvo_node_count_drop(tvo_node_t *node, tvo_node_drop_t why)
{
    if (node == NULL || node->boot_id <= 0) {
        return;
    }
    switch (why) {
    case TVO_NODE_DROP_MALFORMED: tvo_node_count(&node->counters.malformed); break;
    case TVO_NODE_DROP_UNAUTHENTICATED: tvo_node_count(&node->counters.unauthenticated); break;
    case TVO_NODE_DROP_REPLAYED: tvo_node_count(&node->counters.replayed); break;
    case TVO_NODE_DROP_COUNT:
    default: break;
    }
}

/* The message decoded into the node's rx, or 0 (its length is the channel's size: checked before). */
static int decode(tvo_node_t *node, int channel, const uint8_t *data, int size, tvo_node_input_t *in)
{
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        in->session = &node->rx.session;
        return tvo_lcm_session_t_decode(data, 0, size, &node->rx.session) == size;
    case TVO_NODE_CH_SAMPLE:
        in->unicycle = &node->rx.unicycle;
        return tvo_lcm_unicycle_sample_t_decode(data, 0, size, &node->rx.unicycle) == size;
    case TVO_NODE_CH_CHAIN_SAMPLE:
        in->chain = &node->rx.chain;
        return tvo_lcm_chain_sample_t_decode(data, 0, size, &node->rx.chain) == size;
    case TVO_NODE_CH_TARGET:
        in->target = &node->rx.target;
        return tvo_lcm_target_t_decode(data, 0, size, &node->rx.target) == size;
    default:
        return 0;
    }
}

int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length, int64_t now_us)
{
    if (node == NULL || node->boot_id <= 0) {
        return 0;
    }
    if (!tvo_node_channel_is_input(channel)) {
        tvo_node_count(&node->counters.malformed); /* a node's own output, or no channel: not for it */
        return 0;
    }
    /* Cheapest first: every message of a channel has one size (fixed arrays only). */
    if (data == NULL || length != tvo_node_channel_message_bytes(channel)) {
        tvo_node_count(&node->counters.malformed);
        return 0;
    }
    tvo_node_input_t in;
    memset(&in, 0, sizeof(in));
    in.channel = channel;
    in.now_us = tvo_schedule_clamp_time(now_us);
    if (!decode(node, channel, data, (int)length, &in)) {
        tvo_node_count(&node->counters.malformed); /* its fingerprint is another type's */
        return 0;
    }
    tvo_node_event_t event = TVO_NODE_EVENT_NONE;
    if (in.session != NULL) {
        in.content_hash = tvo_session_content_hash(data, length);
        event = tvo_node_names_this_boot(node, in.session) ? tvo_node_session_event(node, in.session, in.content_hash)
                                                           : TVO_NODE_EVENT_WRONG_BOOT;
    } else if (in.target != NULL) {
        event = tvo_node_stream_event(node, in.target->header.session_id, TVO_NODE_EVENT_TARGET,
                                      TVO_NODE_EVENT_TARGET_OTHER);
    } else {
        const int32_t session_id = in.unicycle != NULL ? in.unicycle->header.session_id : in.chain->header.session_id;
        event = tvo_node_stream_event(node, session_id, TVO_NODE_EVENT_SAMPLE, TVO_NODE_EVENT_SAMPLE_OTHER);
    }
    tvo_node_dispatch(node, event, &in);
    return channel;
}

int64_t tvo_node_poll(tvo_node_t *node, int64_t now_us)
{
    if (node == NULL || node->boot_id <= 0) {
        return TVO_NODE_NO_DEADLINE;
    }
    now_us = tvo_schedule_clamp_time(now_us);
    const int64_t timer = (node->state == TVO_NODE_RUNNING) ? tvo_node_serve_timer(node, now_us) : TVO_NODE_NO_DEADLINE;
    if (!node->announced || now_us >= node->next_announcement_us) {
        tvo_node_announce(node, now_us);
    }
    return timer < node->next_announcement_us ? timer : node->next_announcement_us;
}
