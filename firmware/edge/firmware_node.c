/*
 * tvo_firmware_node: the control core behind LCM, as a host process (hardware-in-the-loop edge).
 *
 * Subscribes TVO_SESSION, TVO_MEASUREMENT and TVO_TARGET; answers every measurement with a
 * command on TVO_COMMAND (applied at stamp + delay) and telemetry on TVO_TELEMETRY. A session
 * STOP, SIGINT or SIGTERM ends the process with exit code 0.
 *
 * The logic (sessions, missed periods, the slack rule, streamed targets) is node.c's, shared with the
 * processor-in-the-loop program; this file is the LCM transport, the command line and the logs.
 */
#define _POSIX_C_SOURCE 200809L

#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <lcm/lcm.h>

#include "node.h"

/* The only global: set by SIGINT/SIGTERM, polled by the main loop. */
static volatile sig_atomic_t g_stop_signal = 0;

/* How long one lcm_handle_timeout call may block before the stop flag is checked again. */
#define NODE_POLL_MS 100
/* Streamed-target errors reported at most this many times (the rest are only counted). */
#define NODE_MAX_TARGET_WARNINGS 5

typedef struct {
    lcm_t *lcm;
    tvo_node_t node;   /* the transport-independent logic (node.h) */
} lcm_node_t;

static void on_signal(int signo)
{
    (void)signo;
    g_stop_signal = 1;
}

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    lcm_node_t *self = (lcm_node_t *)context;
    lcm_publish(self->lcm, tvo_node_channel_name(channel), data, length);
}

static void report_start(const tvo_node_t *node)
{
    const tvo_edge_session_t *s = &node->session;
    if (s->start_status == TVO_OK) {
        const tvo_objective_t *obj = &s->problem.objective;
        fprintf(stderr,
                "tvo_firmware_node: session %lld started (%d robot(s), h = %lld us, tau = %lld us, %d term(s), "
                "%d multiplier(s))\n",
                (long long)s->session_id, (int)s->robot_count, (long long)s->period_us, (long long)s->delay_us,
                (int)obj->term_count, (int)obj->dual_dim);
    } else if (s->start_bad_part != TVO_LCM_SESSION_ACK_T_PART_NONE) {
        fprintf(stderr, "tvo_firmware_node: session %lld rejected: %s (parameter %s, part: %s)\n",
                (long long)s->session_id, tvo_status_str(s->start_status), tvo_param_str(s->start_bad_param),
                tvo_edge_part_str(s->start_bad_part));
    } else {
        fprintf(stderr, "tvo_firmware_node: session %lld rejected: %s (parameter %s)\n", (long long)s->session_id,
                tvo_status_str(s->start_status), tvo_param_str(s->start_bad_param));
    }
}

/* Every subscribed channel arrives here encoded; node.c decodes it (the same path as on the MCU). */
static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    lcm_node_t *self = (lcm_node_t *)user;
    tvo_node_t *node = &self->node;
    const int64_t previous_id = node->session.session_id;
    const uint8_t had_start = node->has_start;
    const uint32_t target_errors = node->target_errors;
    const uint32_t slack_errors = node->slack_errors;
    const int handled = tvo_node_handle(node, tvo_node_channel_of(channel), (const uint8_t *)rbuf->data,
                                        rbuf->data_size);
    if (handled == 0) {
        fprintf(stderr, "tvo_firmware_node: a message on %s did not decode (ignored)\n", channel);
    } else if (handled == TVO_NODE_CH_SESSION && node->rx.session.action == TVO_LCM_SESSION_T_ACTION_START &&
               (!had_start || node->session.session_id != previous_id)) {
        report_start(node);
    } else if (node->target_errors > target_errors && node->target_errors <= NODE_MAX_TARGET_WARNINGS) {
        fprintf(stderr, "tvo_firmware_node: streamed target sample %lld rejected: %s\n",
                (long long)node->rx.target.sequence, tvo_status_str(node->last_target_status));
    }
    if (node->slack_errors > slack_errors) {
        fprintf(stderr, "tvo_firmware_node: choosing the barrier slack from the first measurement failed\n");
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

int main(int argc, char **argv)
{
    const char *url = NULL;
    const int arg_status = parse_args(argc, argv, &url);
    if (arg_status != 0) {
        return arg_status;
    }
    if (tvo_node_check_buffer() != 0) {
        fprintf(stderr, "tvo_firmware_node: error: TVO_NODE_BUFFER_BYTES (%d) is smaller than an encoded message\n",
                TVO_NODE_BUFFER_BYTES);
        return 1;
    }
    if (install_signal_handlers() != 0) {
        perror("tvo_firmware_node: sigaction");
        return 1;
    }
    /* Static: the node holds the session, the decoded message and the encode buffer (kilobytes). */
    static lcm_node_t self;
    tvo_node_init(&self.node, publish, &self);
    self.lcm = lcm_create(url);
    if (self.lcm == NULL) {
        fprintf(stderr,
                "tvo_firmware_node: error: cannot create LCM on '%s'.\n"
                "  UDP multicast on loopback may be disabled. Fix (as root):\n"
                "    ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo\n"
                "  or choose another provider with --lcm-url URL or LCM_DEFAULT_URL.\n",
                url != NULL ? url : "LCM default");
        return 1;
    }
    lcm_subscribe(self.lcm, TVO_CHANNEL_SESSION, on_message, &self);
    lcm_subscribe(self.lcm, TVO_CHANNEL_MEASUREMENT, on_message, &self);
    lcm_subscribe(self.lcm, TVO_CHANNEL_TARGET, on_message, &self);

    int exit_code = 0;
    while (!g_stop_signal && !self.node.stop_requested) {
        /* A signal interrupts the wait with -1: that is a request to stop, not a failure. */
        if (lcm_handle_timeout(self.lcm, NODE_POLL_MS) < 0 && !g_stop_signal) {
            fprintf(stderr, "tvo_firmware_node: error: LCM receive failed\n");
            exit_code = 1;
            break;
        }
    }
    lcm_destroy(self.lcm);
    return exit_code;
}
