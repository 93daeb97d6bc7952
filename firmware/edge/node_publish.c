/*
 * What the node says (lcm_types/README.md "Channels"): a period's answer as one command per robot it
 * drives (own_robot's, or every robot's), telemetry after the answers to every telemetry_every-th
 * sequence, the acks, and the node's announcement (node_status_t). Everything is encoded into the
 * node's one buffer: publishing allocates nothing.
 */
#include "node_publish.h"

#include <string.h>

static void publish_encoded(tvo_node_t *node, int channel, int length)
{
    if (length > 0 && node->publish != NULL) {
        node->publish(node->publish_context, channel, node->buffer, (uint32_t)length);
    }
}

/* The robots whose rows the node publishes: [first, end). */
static void driven_robots(const tvo_node_t *node, const tvo_node_session_t *s, uint8_t *first, uint8_t *end)
{
    const uint8_t robots = s->schedule.timing.robot_count;
    if (node->own_robot >= 0) {
        /* own_robot < robot_count: a START is taken only if it names this node's boot for its robot */
        *first = (uint8_t)node->own_robot;
        *end = (uint8_t)(node->own_robot + 1);
        *end = *end <= robots ? *end : *first;
    } else {
        *first = 0u;
        *end = robots;
    }
}

void tvo_node_publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, const tvo_session_reject_t *why)
{
    const tvo_node_session_t *s = tvo_node_session(node);
    tvo_session_ack(msg, why, s != NULL ? s->session_id : -1, node->boot_id, node->own_robot, &node->last_ack);
    node->acks++;
    publish_encoded(node, TVO_NODE_CH_SESSION_ACK,
                    tvo_lcm_session_ack_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &node->last_ack));
}

/* The command to every driven robot. */
static void publish_commands(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                             const tvo_step_stamp_t *stamp)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    uint8_t first = 0u, end = 0u;
    driven_robots(node, s, &first, &end);
    for (uint8_t r = first; r < end; ++r) {
        publish_encoded(node, ops->command_channel,
                        ops->encode_command(cmd, stamp, (int32_t)r, node->buffer, TVO_NODE_BUFFER_BYTES));
    }
}

/* A period's safe stops and speed mismatches, counted once per period whatever the robots driven. */
static void count_answer(tvo_node_t *node, const tvo_edge_mark_t *mark)
{
    if (mark->outcome == TVO_OUTCOME_STOPPED) {
        tvo_node_count(&node->counters.safe_stops);
    }
    if ((mark->flags & TVO_FLAG_SPEED_MISMATCH) != 0u) {
        tvo_node_count(&node->counters.speed_mismatch);
    }
}

void tvo_node_publish_answer(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                             const tvo_step_stamp_t *stamp, int32_t predicted)
{
    const tvo_edge_controller_ops_t *ops = s->controller.ops;
    const tvo_edge_mark_t mark = ops->mark(cmd);
    count_answer(node, &mark);
    publish_commands(node, s, cmd, stamp);
    const int64_t every = (int64_t)s->schedule.timing.telemetry_every;
    if (every <= 0 || (int64_t)stamp->sequence % every != 0) {
        return; /* a plant in lockstep knows which answers carry telemetry: those of multiples of every */
    }
    const uint32_t wire_flags = tvo_step_wire_flags(mark.flags, mark.outcome);
    const uint8_t robots = s->schedule.timing.robot_count;
    const int64_t digest = (int64_t)ops->digest(cmd, robots);
    uint8_t first = 0u, end = 0u;
    driven_robots(node, s, &first, &end);
    for (uint8_t r = first; r < end; ++r) {
        tvo_lcm_telemetry_t tel;
        memset(&tel, 0, sizeof(tel));
        tvo_step_header(stamp, wire_flags, (int32_t)r, &tel.header);
        ops->telemetry_to_lcm(&s->controller, &s->problem, r, &tel);
        tel.predicted_robots = (int8_t)(predicted < INT8_MAX ? predicted : INT8_MAX);
        tel.joint_digest = digest;
        publish_encoded(node, TVO_NODE_CH_TELEMETRY, tvo_lcm_telemetry_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel));
    }
}

void tvo_node_publish_own_stop(tvo_node_t *node, const tvo_node_session_t *s, const tvo_edge_command_t *cmd,
                               const tvo_step_stamp_t *stamp)
{
    const tvo_edge_mark_t mark = s->controller.ops->mark(cmd);
    count_answer(node, &mark);
    publish_commands(node, s, cmd, stamp);
}

void tvo_node_announce(tvo_node_t *node, int64_t now_us)
{
    const tvo_node_session_t *s = tvo_node_session(node);
    tvo_lcm_node_status_t *status = &node->status;
    memset(status, 0, sizeof(*status));
    status->utime = now_us;
    status->protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    status->boot_id = node->boot_id;
    status->own_robot = node->own_robot;
    status->max_robots = (int8_t)TVO_NODE_MAX_ROBOTS;
    status->state = (s != NULL) ? TVO_LCM_NODE_STATUS_T_STATE_RUNNING : TVO_LCM_NODE_STATUS_T_STATE_IDLE;
    status->session_id = (s != NULL) ? s->session_id : -1;
    status->counters = node->counters;
    publish_encoded(node, TVO_NODE_CH_NODE, tvo_lcm_node_status_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, status));
    node->announced = 1u;
    /* now_us is within the wire's range (2^60): the sum cannot overflow. */
    node->next_announcement_us =
        now_us + ((s != NULL) ? TVO_LCM_NODE_STATUS_T_RUNNING_PERIOD_US : TVO_LCM_NODE_STATUS_T_IDLE_PERIOD_US);
}
