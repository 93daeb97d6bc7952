/*
 * tvo_firmware_node: the control core behind LCM, as a host process (hardware-in-the-loop edge).
 *
 * Subscribes TVO_SESSION, TVO_MEASUREMENT and TVO_TARGET; answers every measurement with a
 * command on TVO_COMMAND (applied at stamp + delay) and telemetry on TVO_TELEMETRY. A session
 * STOP, SIGINT or SIGTERM ends the process with exit code 0.
 *
 * Missed periods: the plant numbers its measurements one per period. When the sequence jumps,
 * the node first runs the core once per missed period with no measurement (the core holds the
 * previous command, as the plant did, and its watchdog counts the gap) and publishes those
 * holding commands too, so the plant side sees and counts the fault.
 *
 * Constraints: the barrier's slack s0 is chosen once, from the first measurement the node can use
 * (the paper's rule on f_i(y(0), 0)), before the first step that uses it.
 */
#define _POSIX_C_SOURCE 200809L

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "lcm_edge.h"

/* The only global: set by SIGINT/SIGTERM, polled by the main loop. */
static volatile sig_atomic_t g_stop_signal = 0;

/* Encode buffer for what the node publishes (command, telemetry, ack: each under 1 kB encoded; the
 * larger session_t is only decoded). main() checks the encoded sizes against it at start-up. */
#define NODE_BUFFER_BYTES 2048
/* How long one lcm_handle_timeout call may block before the stop flag is checked again. */
#define NODE_POLL_MS 100
/* Streamed-target errors reported at most this many times (the rest are only counted). */
#define NODE_MAX_TARGET_WARNINGS 5

typedef struct {
    lcm_t *lcm;
    tvo_edge_session_t session;
    uint8_t buffer[NODE_BUFFER_BYTES];  /* encode buffer: publishing allocates nothing */
    uint8_t has_start;                  /* a START was processed (session.session_id is set) */
    uint8_t stop_requested;             /* a STOP for this session arrived */
    unsigned target_errors;
} node_t;

static void on_signal(int signo)
{
    (void)signo;
    g_stop_signal = 1;
}

static void publish_ack(node_t *node, const tvo_lcm_session_t *msg, tvo_status_t status, tvo_param_t bad,
                        int32_t bad_part)
{
    tvo_lcm_session_ack_t ack;
    tvo_edge_ack_to_lcm(msg->utime, msg->session_id, msg->action, status, bad, bad_part, &ack);
    const int len = tvo_lcm_session_ack_t_encode(node->buffer, 0, NODE_BUFFER_BYTES, &ack);
    if (len > 0) {
        lcm_publish(node->lcm, TVO_CHANNEL_SESSION_ACK, node->buffer, (unsigned)len);
    }
}

static void publish_step(node_t *node, const tvo_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                         int64_t sequence)
{
    tvo_lcm_command_t out;
    tvo_edge_command_to_lcm(cmd, status, apply_utime, sequence, node->session.robot_count, &out);
    int len = tvo_lcm_command_t_encode(node->buffer, 0, NODE_BUFFER_BYTES, &out);
    if (len > 0) {
        lcm_publish(node->lcm, TVO_CHANNEL_COMMAND, node->buffer, (unsigned)len);
    }
    tvo_lcm_telemetry_t tel;
    tvo_edge_telemetry_to_lcm(&node->session, status, cmd->flags, apply_utime, sequence, &tel);
    len = tvo_lcm_telemetry_t_encode(node->buffer, 0, NODE_BUFFER_BYTES, &tel);
    if (len > 0) {
        lcm_publish(node->lcm, TVO_CHANNEL_TELEMETRY, node->buffer, (unsigned)len);
    }
}

/* Runs the core with no measurement for the periods the plant skipped before `sequence`. */
static void step_missed_periods(node_t *node, int64_t sequence, int64_t apply_utime)
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
        tvo_command_t cmd;
        const tvo_status_t st = tvo_controller_step(&s->controller, NULL, (uint32_t)missed_apply_utime, &cmd);
        publish_step(node, &cmd, st, missed_apply_utime, sequence - k);
    }
}

static void on_measurement(const lcm_recv_buf_t *rbuf, const char *channel, const tvo_lcm_measurement_t *msg,
                           void *user)
{
    (void)rbuf;
    (void)channel;
    node_t *node = (node_t *)user;
    tvo_edge_session_t *s = &node->session;
    if (!s->active) {
        return;
    }
    /* The node's schedule: sampled at t_{n+1} - tau, applied at t_{n+1}. */
    const int64_t apply_utime = msg->utime + s->delay_us;
    step_missed_periods(node, msg->sequence, apply_utime);

    tvo_measurement_t meas;
    tvo_command_t cmd;
    const tvo_status_t conv = tvo_edge_measurement_from_lcm(msg, s->robot_count, &meas);
    if (conv == TVO_OK && !s->problem.slack_chosen) {
        const tvo_status_t slack = tvo_edge_choose_slack(s, &meas);
        if (slack != TVO_OK && slack != TVO_ERR_NOT_FINITE) {
            fprintf(stderr, "tvo_firmware_node: choosing the barrier slack failed: %s\n", tvo_status_str(slack));
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

static void on_target(const lcm_recv_buf_t *rbuf, const char *channel, const tvo_lcm_target_t *msg, void *user)
{
    (void)rbuf;
    (void)channel;
    node_t *node = (node_t *)user;
    if (!node->session.active) {
        return;
    }
    const tvo_status_t st = tvo_edge_target_update(&node->session, msg);
    if (st != TVO_OK && node->target_errors++ < NODE_MAX_TARGET_WARNINGS) {
        fprintf(stderr, "tvo_firmware_node: streamed target sample %lld rejected: %s\n", (long long)msg->sequence,
                tvo_status_str(st));
    }
}

static void on_start(node_t *node, const tvo_lcm_session_t *msg)
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
    if (st == TVO_OK) {
        const tvo_objective_t *obj = &s->problem.objective;
        fprintf(stderr,
                "tvo_firmware_node: session %lld started (%d robot(s), h = %lld us, tau = %lld us, %d term(s), "
                "%d multiplier(s))\n",
                (long long)msg->session_id, (int)s->robot_count, (long long)s->period_us, (long long)s->delay_us,
                (int)obj->term_count, (int)obj->dual_dim);
    } else if (bad_part != TVO_LCM_SESSION_ACK_T_PART_NONE) {
        fprintf(stderr, "tvo_firmware_node: session %lld rejected: %s (parameter %s, part: %s)\n",
                (long long)msg->session_id, tvo_status_str(st), tvo_param_str(bad), tvo_edge_part_str(bad_part));
    } else {
        fprintf(stderr, "tvo_firmware_node: session %lld rejected: %s (parameter %s)\n", (long long)msg->session_id,
                tvo_status_str(st), tvo_param_str(bad));
    }
    publish_ack(node, msg, st, bad, bad_part);
}

static void on_session(const lcm_recv_buf_t *rbuf, const char *channel, const tvo_lcm_session_t *msg, void *user)
{
    (void)rbuf;
    (void)channel;
    node_t *node = (node_t *)user;
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

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: tvo_firmware_node [--lcm-url URL]\n"
            "Runs the TV-O unicycle controller behind LCM until a session STOP, SIGINT or SIGTERM.\n"
            "  --lcm-url URL  LCM provider URL (default: $LCM_DEFAULT_URL, else LCM's default udpm)\n"
            "  -h, --help     show this help\n");
}

/* Returns 0 and sets *url (NULL: LCM's default), or 2 after printing why the arguments are bad. */
static int parse_args(int argc, char **argv, const char **url)
{
    *url = NULL;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            print_usage(stdout);
            exit(0);
        } else if (strcmp(arg, "--lcm-url") == 0 && i + 1 < argc) {
            *url = argv[++i];
        } else if (strncmp(arg, "--lcm-url=", 10) == 0) {
            *url = arg + 10;
        } else {
            fprintf(stderr, "tvo_firmware_node: error: unexpected argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    return 0;
}

static int install_signal_handlers(void)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    return (sigaction(SIGINT, &sa, NULL) == 0 && sigaction(SIGTERM, &sa, NULL) == 0) ? 0 : -1;
}

/* The published messages are fixed-size: their encoded sizes are constants, checked once here. */
static int buffer_fits_messages(void)
{
    tvo_lcm_command_t command;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_session_ack_t ack;
    memset(&command, 0, sizeof(command));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&ack, 0, sizeof(ack));
    return tvo_lcm_command_t_encoded_size(&command) <= NODE_BUFFER_BYTES &&
           tvo_lcm_telemetry_t_encoded_size(&telemetry) <= NODE_BUFFER_BYTES &&
           tvo_lcm_session_ack_t_encoded_size(&ack) <= NODE_BUFFER_BYTES;
}

int main(int argc, char **argv)
{
    const char *url = NULL;
    const int arg_status = parse_args(argc, argv, &url);
    if (arg_status != 0) {
        return arg_status;
    }
    if (!buffer_fits_messages()) {
        fprintf(stderr, "tvo_firmware_node: error: NODE_BUFFER_BYTES (%d) is smaller than an encoded message\n",
                NODE_BUFFER_BYTES);
        return 1;
    }
    if (install_signal_handlers() != 0) {
        perror("tvo_firmware_node: sigaction");
        return 1;
    }
    node_t node;
    memset(&node, 0, sizeof(node));
    node.lcm = lcm_create(url);
    if (node.lcm == NULL) {
        fprintf(stderr,
                "tvo_firmware_node: error: cannot create LCM on '%s'.\n"
                "  UDP multicast on loopback may be disabled. Fix (as root):\n"
                "    ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo\n"
                "  or choose another provider with --lcm-url URL or LCM_DEFAULT_URL.\n",
                url != NULL ? url : "LCM default");
        return 1;
    }
    tvo_lcm_session_t_subscribe(node.lcm, TVO_CHANNEL_SESSION, on_session, &node);
    tvo_lcm_measurement_t_subscribe(node.lcm, TVO_CHANNEL_MEASUREMENT, on_measurement, &node);
    tvo_lcm_target_t_subscribe(node.lcm, TVO_CHANNEL_TARGET, on_target, &node);

    int exit_code = 0;
    while (!g_stop_signal && !node.stop_requested) {
        /* A signal interrupts the wait with -1: that is a request to stop, not a failure. */
        if (lcm_handle_timeout(node.lcm, NODE_POLL_MS) < 0 && !g_stop_signal) {
            fprintf(stderr, "tvo_firmware_node: error: LCM receive failed\n");
            exit_code = 1;
            break;
        }
    }
    lcm_destroy(node.lcm);
    return exit_code;
}
