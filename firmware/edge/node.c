/* The firmware node's transport-independent logic; see node.h. */
#include "node.h"

#include <string.h>

int tvo_node_check_buffer(void)
{
    tvo_lcm_command_t command;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_session_ack_t ack;
    memset(&command, 0, sizeof(command));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&ack, 0, sizeof(ack));
    const int fits = tvo_lcm_command_t_encoded_size(&command) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_telemetry_t_encoded_size(&telemetry) <= TVO_NODE_BUFFER_BYTES &&
                     tvo_lcm_session_ack_t_encoded_size(&ack) <= TVO_NODE_BUFFER_BYTES;
    return fits ? 0 : -1;
}

void tvo_node_init(tvo_node_t *node, tvo_node_publish_fn publish, void *publish_context)
{
    if (node == NULL) {
        return;
    }
    memset(node, 0, sizeof(*node));
    node->publish = publish;
    node->publish_context = publish_context;
}

static void publish_ack(tvo_node_t *node, const tvo_lcm_session_t *msg, tvo_status_t status, tvo_param_t bad,
                        int32_t bad_part)
{
    tvo_lcm_session_ack_t ack;
    tvo_edge_ack_to_lcm(msg->utime, msg->session_id, msg->action, status, bad, bad_part, &ack);
    const int len = tvo_lcm_session_ack_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &ack);
    if (len > 0) {
        node->publish(node->publish_context, TVO_NODE_CH_SESSION_ACK, node->buffer, (uint32_t)len);
    }
}

/* A chain step: the command carries u; the telemetry only the step's outcome (the unicycle
 * controller's telemetry fields do not apply). */
static void publish_chain_step(tvo_node_t *node, const tvo_chain_command_t *cmd, tvo_status_t status,
                               int64_t apply_utime, int64_t sequence)
{
    tvo_lcm_command_t out;
    tvo_edge_chain_command_to_lcm(cmd, status, apply_utime, sequence, node->session.robot_count, &out);
    int len = tvo_lcm_command_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &out);
    if (len > 0) {
        node->publish(node->publish_context, TVO_NODE_CH_COMMAND, node->buffer, (uint32_t)len);
    }
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    tel.utime = apply_utime;
    tel.measurement_sequence = sequence;
    tel.status = (int32_t)status;
    tel.flags = (int32_t)cmd->flags;
    len = tvo_lcm_telemetry_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel);
    if (len > 0) {
        node->publish(node->publish_context, TVO_NODE_CH_TELEMETRY, node->buffer, (uint32_t)len);
    }
}

static void publish_step(tvo_node_t *node, const tvo_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                         int64_t sequence)
{
    tvo_lcm_command_t out;
    tvo_edge_command_to_lcm(cmd, status, apply_utime, sequence, node->session.robot_count, &out);
    int len = tvo_lcm_command_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &out);
    if (len > 0) {
        node->publish(node->publish_context, TVO_NODE_CH_COMMAND, node->buffer, (uint32_t)len);
    }
    tvo_lcm_telemetry_t tel;
    tvo_edge_telemetry_to_lcm(&node->session, status, cmd->flags, apply_utime, sequence, &tel);
    len = tvo_lcm_telemetry_t_encode(node->buffer, 0, TVO_NODE_BUFFER_BYTES, &tel);
    if (len > 0) {
        node->publish(node->publish_context, TVO_NODE_CH_TELEMETRY, node->buffer, (uint32_t)len);
    }
}

/* Runs the core with no measurement for the periods the plant skipped before `sequence`. */
static void step_missed_periods(tvo_node_t *node, int64_t sequence, int64_t apply_utime)
{
    tvo_edge_session_t *s = &node->session;
    if (!s->has_sequence || sequence <= s->last_sequence + 1) {
        return;
    }
    int64_t missed = sequence - s->last_sequence - 1;
    /* Beyond the watchdog more empty steps change nothing: bound the work a wild sequence can cause. */
    const int64_t cap = (int64_t)s->controller.cfg.watchdog_periods + 1;
    if (missed > cap) {
        missed = cap;
    }
    for (int64_t k = missed; k >= 1; --k) {
        const int64_t missed_apply_utime = apply_utime - k * s->period_us;
        if (s->plant_chain) {
            tvo_chain_command_t cmd;
            const tvo_status_t st = tvo_chain_controller_step(&s->chain, NULL, (uint32_t)missed_apply_utime, &cmd);
            publish_chain_step(node, &cmd, st, missed_apply_utime, sequence - k);
        } else {
            tvo_command_t cmd;
            const tvo_status_t st = tvo_controller_step(&s->controller, NULL, (uint32_t)missed_apply_utime, &cmd);
            publish_step(node, &cmd, st, missed_apply_utime, sequence - k);
        }
    }
}

static void on_measurement(tvo_node_t *node, const tvo_lcm_measurement_t *msg)
{
    tvo_edge_session_t *s = &node->session;
    if (!s->active) {
        return;
    }
    /* The node's schedule: sampled at t_{n+1} - tau, applied at t_{n+1}. */
    const int64_t apply_utime = msg->utime + s->delay_us;
    step_missed_periods(node, msg->sequence, apply_utime);
    if (s->plant_chain) {
        tvo_chain_measurement_t chain_meas;
        tvo_chain_command_t chain_cmd;
        const tvo_status_t conv = tvo_edge_chain_measurement_from_lcm(msg, s->robot_count, &chain_meas);
        tvo_status_t st = tvo_chain_controller_step(&s->chain, conv == TVO_OK ? &chain_meas : NULL,
                                                    (uint32_t)apply_utime, &chain_cmd);
        publish_chain_step(node, &chain_cmd, conv != TVO_OK ? conv : st, apply_utime, msg->sequence);
        if (!s->has_sequence || msg->sequence > s->last_sequence) {
            s->last_sequence = msg->sequence;
            s->has_sequence = 1;
        }
        return;
    }

    tvo_measurement_t meas;
    tvo_command_t cmd;
    const tvo_status_t conv = tvo_edge_measurement_from_lcm(msg, s->robot_count, &meas);
    if (conv == TVO_OK && !s->problem.slack_chosen) {
        const tvo_status_t slack = tvo_edge_choose_slack(s, &meas);
        if (slack != TVO_OK && slack != TVO_ERR_NOT_FINITE) {
            node->slack_errors++;
        }
    }
    tvo_status_t st = tvo_controller_step(&s->controller, conv == TVO_OK ? &meas : NULL, (uint32_t)apply_utime,
                                          &cmd);
    if (conv != TVO_OK) {
        st = conv;  /* report why the measurement was unusable, not merely that none arrived */
    }
    publish_step(node, &cmd, st, apply_utime, msg->sequence);
    if (!s->has_sequence || msg->sequence > s->last_sequence) {
        s->last_sequence = msg->sequence;
        s->has_sequence = 1;
    }
}

static void on_target(tvo_node_t *node, const tvo_lcm_target_t *msg)
{
    if (!node->session.active) {
        return;
    }
    node->last_target_status = tvo_edge_target_update(&node->session, msg);
    if (node->last_target_status != TVO_OK) {
        node->target_errors++;
    }
}

static void on_start(tvo_node_t *node, const tvo_lcm_session_t *msg)
{
    tvo_edge_session_t *s = &node->session;
    /* The host repeats START until acked: answer a repeat without restarting the controller. */
    if (node->has_start && msg->session_id == s->session_id) {
        publish_ack(node, msg, s->start_status, s->start_bad_param, s->start_bad_part);
        return;
    }
    tvo_param_t bad = TVO_PARAM_NONE;
    int32_t bad_part = TVO_LCM_SESSION_ACK_T_PART_NONE;
    const tvo_status_t st = tvo_edge_session_start(s, msg, &bad, &bad_part);
    s->start_status = st;
    s->start_bad_param = bad;
    s->start_bad_part = bad_part;
    node->has_start = 1;
    node->target_errors = 0;
    publish_ack(node, msg, st, bad, bad_part);
}

static void on_session(tvo_node_t *node, const tvo_lcm_session_t *msg)
{
    if (msg->action == TVO_LCM_SESSION_T_ACTION_START) {
        on_start(node, msg);
    } else if (msg->action == TVO_LCM_SESSION_T_ACTION_STOP) {
        /* A STOP for another host's session is not ours to obey. */
        if (!node->has_start || msg->session_id == node->session.session_id) {
            node->session.active = 0;
            node->stop_requested = 1;
            publish_ack(node, msg, TVO_OK, TVO_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE);
        }
    } else {
        publish_ack(node, msg, TVO_ERR_PARAM, TVO_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE);
    }
}

int tvo_node_handle(tvo_node_t *node, int channel, const uint8_t *data, uint32_t length)
{
    if (node == NULL || data == NULL || length > (uint32_t)INT32_MAX) {
        return 0;
    }
    const int size = (int)length;
    switch (channel) {
    case TVO_NODE_CH_SESSION:
        if (tvo_lcm_session_t_decode(data, 0, size, &node->rx.session) < 0) {
            break;
        }
        on_session(node, &node->rx.session);
        return channel;
    case TVO_NODE_CH_MEASUREMENT:
        if (tvo_lcm_measurement_t_decode(data, 0, size, &node->rx.measurement) < 0) {
            break;
        }
        on_measurement(node, &node->rx.measurement);
        return channel;
    case TVO_NODE_CH_TARGET:
        if (tvo_lcm_target_t_decode(data, 0, size, &node->rx.target) < 0) {
            break;
        }
        on_target(node, &node->rx.target);
        return channel;
    default:
        return 0;
    }
    node->decode_errors++;
    return 0;
}
