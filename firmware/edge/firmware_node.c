/*
 * tvo_firmware_node: the control core behind LCM, as a host process (hardware-in-the-loop edge).
 *
 * Subscribes TVO_SESSION, TVO_SAMPLE, TVO_CHAIN_SAMPLE and TVO_TARGET and publishes TVO_NODE,
 * TVO_SESSION_ACK, TVO_COMMAND (TVO_CHAIN_COMMAND) and TVO_TELEMETRY. The logic (sessions, schedule, watchdog timer, codecs) is node.c's,
 * shared with the processor-in-the-loop program; this file is the LCM transport, the node's clock
 * (CLOCK_MONOTONIC), the command line and the logs. SIGINT or SIGTERM ends the process with exit
 * code 0; so does a session STOP, unless --keep-running.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/select.h>
#include <time.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "auth_key_file.h"
#include "auth_link.h"
#include "node.h"

/* The only global: set by SIGINT/SIGTERM, polled by the main loop. */
static volatile sig_atomic_t g_stop_signal = 0;

/* Longest wait for a message before the stop flag, the parent and the node's timer are checked. */
#define NODE_POLL_US 100000
/* Each kind of log line is written at most once per this interval, with a count of the rest. */
#define NODE_LOG_INTERVAL_US 1000000
/* Log keys: one per refusal status, then the other kinds of event. */
enum {
    LOG_UNDECODABLE = TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS,
    LOG_OTHER_SESSION,
    LOG_SAFE_STOP,
    LOG_TARGET,
    LOG_SPEED_MISMATCH,
    LOG_UNAUTHENTICATED,
    LOG_REPLAYED,
    LOG_START_DONE,
    LOG_START_REFUSED,
    LOG_STOP,
    LOG_OTHER_ACK,
    LOG_KEYS
};

typedef struct {
    int64_t last_us;     /* when this kind was last written; -1: never */
    uint32_t unwritten;  /* events since then */
    char text[200];      /* the latest event's line, for the count written at exit */
} log_limit_t;

typedef struct {
    lcm_t *lcm;
    tvo_node_t node;     /* the transport-independent logic (node.h) */
    tvo_auth_link_t link; /* with --key-file: frames opened before the node, its messages signed */
    int keyed;
    log_limit_t limits[LOG_KEYS];
} lcm_node_t;

static void on_signal(int signo)
{
    (void)signo;
    g_stop_signal = 1;
}

/* The node's clock: CLOCK_MONOTONIC in microseconds (never steps with the wall clock). */
static int64_t monotonic_us(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (int64_t)ts.tv_sec * 1000000 + (int64_t)(ts.tv_nsec / 1000);
}

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    lcm_node_t *self = (lcm_node_t *)context;
    lcm_publish(self->lcm, tvo_node_channel_name(channel), data, length);
}

/* Whether a line of this kind may be written now; *suppressed gets how many were not. */
static int log_allowed(lcm_node_t *self, int key, uint32_t events, uint32_t *suppressed)
{
    log_limit_t *limit = &self->limits[key];
    const int64_t now = monotonic_us();
    limit->unwritten += events;
    if (limit->last_us >= 0 && now - limit->last_us < NODE_LOG_INTERVAL_US) {
        return 0;
    }
    *suppressed = limit->unwritten - 1u;
    limit->unwritten = 0;
    limit->last_us = now;
    return 1;
}

static void log_event(lcm_node_t *self, int key, uint32_t events, const char *what)
{
    uint32_t suppressed = 0;
    if (events > 0u) {
        snprintf(self->limits[key].text, sizeof(self->limits[key].text), "%s", what);
    }
    if (events > 0u && log_allowed(self, key, events, &suppressed)) {
        if (suppressed > 0u) {
            fprintf(stderr, "tvo_firmware_node: %s (and %u more like it in the last second)\n", what, suppressed);
        } else {
            fprintf(stderr, "tvo_firmware_node: %s\n", what);
        }
    }
}

/* At exit: the events a rate limit held back since their kind's last line, so none goes unsaid. */
static void log_flush(lcm_node_t *self)
{
    for (int k = 0; k < LOG_KEYS; ++k) {
        if (self->limits[k].unwritten > 0u) {
            fprintf(stderr, "tvo_firmware_node: %s (%u more like it since the last line of its kind)\n", self->limits[k].text,
                    self->limits[k].unwritten);
            self->limits[k].unwritten = 0;
        }
    }
}

static void log_ack(lcm_node_t *self)
{
    const tvo_lcm_session_ack_t *ack = &self->node.last_ack;
    char line[200];
    const char *action = ack->action == TVO_LCM_SESSION_T_ACTION_START  ? "START"
                         : ack->action == TVO_LCM_SESSION_T_ACTION_STOP ? "STOP"
                                                                        : "session message";
    if (ack->status == TVO_OK) {
        snprintf(line, sizeof(line), "%s of session %lld done (running: %lld)", action, (long long)ack->session_id,
                 (long long)ack->running_session_id);
    } else {
        snprintf(line, sizeof(line), "%s of session %lld refused: %s (parameter %s, part %s, entry %d; running: %lld)",
                 action, (long long)ack->session_id, tvo_protocol_status_str(ack->status),
                 tvo_protocol_param_str(ack->bad_param), tvo_protocol_part_str(ack->bad_part), (int)ack->bad_index,
                 (long long)ack->running_session_id);
    }
    const int key = ack->action == TVO_LCM_SESSION_T_ACTION_START ? (ack->status == TVO_OK ? LOG_START_DONE : LOG_START_REFUSED)
                    : ack->action == TVO_LCM_SESSION_T_ACTION_STOP ? LOG_STOP
                                                                   : LOG_OTHER_ACK;
    log_event(self, key, 1u, line);
}

/* What changed in the counters during one message or timer call, as rate-limited log lines. */
static void log_changes(lcm_node_t *self, const tvo_lcm_node_counters_t *before, uint32_t acks_before)
{
    const tvo_lcm_node_counters_t *after = &self->node.counters;
    char line[160];
    if (self->node.acks != acks_before) {
        log_ack(self);
    }
    for (int s = 0; s < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++s) {
        if (after->refused[s] > before->refused[s]) {
            snprintf(line, sizeof(line), "sample refused: %s", tvo_protocol_status_str(s));
            log_event(self, s, (uint32_t)(after->refused[s] - before->refused[s]), line);
        }
    }
    log_event(self, LOG_UNDECODABLE, (uint32_t)(after->malformed - before->malformed),
              self->keyed ? "a message did not decode (ignored)"
                          : "a message did not decode (ignored; if the plant signs its messages, start the node "
                            "with the same --key-file)");
    log_event(self, LOG_OTHER_SESSION, (uint32_t)(after->other_session - before->other_session),
              "a message for another session id (ignored)");
    log_event(self, LOG_SAFE_STOP, (uint32_t)(after->safe_stops - before->safe_stops), "safe stop published");
    log_event(self, LOG_TARGET, (uint32_t)(after->targets_refused - before->targets_refused),
              "streamed target sample refused");
    log_event(self, LOG_UNAUTHENTICATED, (uint32_t)(after->unauthenticated - before->unauthenticated),
              "a frame without a valid tag was dropped (forged, altered, or another key)");
    log_event(self, LOG_REPLAYED, (uint32_t)(after->replayed - before->replayed),
              "a frame with a used counter was dropped (a replay)");
    log_event(self, LOG_SPEED_MISMATCH, (uint32_t)(after->speed_mismatch - before->speed_mismatch),
              "measured speed contradicts the commanded speed (stalled wheels?)");
}

/* Every subscribed channel arrives here encoded; node.c decodes it (the same path as on the MCU). */
static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    lcm_node_t *self = (lcm_node_t *)user;
    const tvo_lcm_node_counters_t before = self->node.counters;
    const uint32_t acks_before = self->node.acks;
    if (self->keyed) {
        (void)tvo_auth_link_receive(&self->link, &self->node, tvo_node_channel_of(channel),
                                    (const uint8_t *)rbuf->data, rbuf->data_size, monotonic_us());
    } else {
        (void)tvo_node_handle(&self->node, tvo_node_channel_of(channel), (const uint8_t *)rbuf->data,
                              rbuf->data_size, monotonic_us());
    }
    log_changes(self, &before, acks_before);
}

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: tvo_firmware_node [--key-file FILE [--sender-id N]] [--own-robot I] [--lcm-url URL]\n"
            "                         [--keep-running] [--exit-with-parent]\n"
            "Runs the TV-O controller behind LCM: sessions on TVO_SESSION, measurements in, commands out.\n"
            "  --key-file FILE     authenticate every message both ways with this 32-byte key (tools/keygen;\n"
            "                      mode 0600); without it the bus is unauthenticated (lab use)\n"
            "  --sender-id N       this node's sender id on a keyed bus (default 1, a fleet node's 256 + I;\n"
            "                      unique per key holder)\n"
            "  --own-robot I       a fleet node: drive robot I only (it hears every robot's samples and evaluates\n"
            "                      the joint law); default: every robot of the session. Sessions of up to %d robots\n"
            "  --lcm-url URL       LCM provider URL (default: $LCM_DEFAULT_URL, else LCM's default udpm)\n"
            "  --keep-running      serve session after session (default: exit after a session's STOP)\n"
            "  --exit-with-parent  exit when the process that started this one dies (no orphans)\n"
            "  -h, --help          show this help\n",
            (int)TVO_NODE_MAX_ROBOTS);
}

typedef struct {
    const char *key_file; /* NULL: unauthenticated */
    uint32_t sender_id;
    const char *url;      /* NULL: LCM's default */
    int keep_running;
    int exit_with_parent;
    int32_t own_robot;    /* -1: the whole joint command (no fleet) */
} node_options_t;

/* Returns 0 and fills *opt, 1 after --help, or 2 after printing why the arguments are bad. */
static int parse_args(int argc, char **argv, node_options_t *opt)
{
    memset(opt, 0, sizeof(*opt));
    opt->sender_id = TVO_AUTH_SENDER_NODE;
    opt->own_robot = -1;
    int sender_id_given = 0;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = NULL;
        if ((strcmp(arg, "--key-file") == 0 || strcmp(arg, "--sender-id") == 0) && i + 1 < argc) {
            value = argv[++i];
        } else if (strncmp(arg, "--key-file=", 11) == 0 || strncmp(arg, "--sender-id=", 12) == 0) {
            value = strchr(arg, '=') + 1;
        }
        if (value != NULL && strncmp(arg, "--key-file", 10) == 0) {
            opt->key_file = value;
            continue;
        }
        if (value != NULL) {
            char *end = NULL;
            errno = 0;
            const unsigned long id = strtoul(value, &end, 10);
            if (errno != 0 || end == value || *end != '\0' || value[0] == '-' || id > UINT32_MAX) {
                fprintf(stderr, "tvo_firmware_node: error: --sender-id takes a whole number 0 .. 4294967295, not '%s'\n",
                        value);
                return 2;
            }
            opt->sender_id = (uint32_t)id;
            sender_id_given = 1;
            continue;
        }
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            print_usage(stdout);
            return 1;
        } else if (strcmp(arg, "--lcm-url") == 0 && i + 1 < argc) {
            opt->url = argv[++i];
        } else if (strncmp(arg, "--lcm-url=", 10) == 0) {
            opt->url = arg + 10;
        } else if ((strcmp(arg, "--own-robot") == 0 && i + 1 < argc) || strncmp(arg, "--own-robot=", 12) == 0) {
            const char *robot = arg[11] == '=' ? arg + 12 : argv[++i];
            char *end = NULL;
            const long r = strtol(robot, &end, 10);
            if (end == robot || *end != '\0' || r < 0 || r >= TVO_NODE_MAX_ROBOTS) {
                fprintf(stderr, "tvo_firmware_node: error: --own-robot takes a robot 0 .. %d, not '%s'\n",
                        (int)TVO_NODE_MAX_ROBOTS - 1, robot);
                return 2;
            }
            opt->own_robot = (int32_t)r;
        } else if (strcmp(arg, "--keep-running") == 0) {
            opt->keep_running = 1;
        } else if (strcmp(arg, "--exit-with-parent") == 0) {
            opt->exit_with_parent = 1;
        } else {
            fprintf(stderr, "tvo_firmware_node: error: unexpected argument '%s' (see --help)\n", arg);
            return 2;
        }
    }
    if (opt->own_robot >= 0 && !sender_id_given) {
        opt->sender_id = TVO_AUTH_SENDER_FLEET_NODE + (uint32_t)opt->own_robot; /* each fleet node its own stream */
    }
    if (sender_id_given && opt->key_file == NULL) {
        fprintf(stderr, "tvo_firmware_node: error: --sender-id needs --key-file (it names this node on a keyed bus)\n");
        return 2;
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

/* Waits for LCM traffic until deadline_us (node clock) at most; -1 on a receive error. */
static int wait_and_handle(lcm_t *lcm, int64_t deadline_us)
{
    int64_t wait_us = deadline_us - monotonic_us();
    wait_us = wait_us < 0 ? 0 : (wait_us > NODE_POLL_US ? NODE_POLL_US : wait_us);
    const int fd = lcm_get_fileno(lcm);
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(fd, &readable);
    struct timeval tv;
    tv.tv_sec = (time_t)(wait_us / 1000000);
    tv.tv_usec = (suseconds_t)(wait_us % 1000000);
    const int ready = select(fd + 1, &readable, NULL, NULL, &tv);
    if (ready < 0) {
        return g_stop_signal ? 0 : -1; /* a signal interrupts the wait: a request to stop */
    }
    return (ready > 0) ? lcm_handle(lcm) : 0;
}

int main(int argc, char **argv)
{
    node_options_t opt;
    const int arg_status = parse_args(argc, argv, &opt);
    if (arg_status != 0) {
        return arg_status == 1 ? 0 : arg_status;
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
    const pid_t parent = getppid();
    /* Static: the node holds two session slots, the decoded message and the encode buffer (kilobytes). */
    static lcm_node_t self;
    /* Interim boot id until --boot-file (the LCM process's own work): the wall clock's seconds at start,
     * which a restart more than a second later never repeats. */
    const int64_t boot_id = (int64_t)time(NULL);
    if (opt.key_file != NULL) {
        uint8_t key[TVO_AUTH_KEY_BYTES];
        char why[300];
        if (tvo_auth_key_file_read(opt.key_file, key, why, sizeof(why)) != 0) {
            fprintf(stderr, "tvo_firmware_node: error: %s\n", why);
            return 2;
        }
        const tvo_auth_status_t keyed = tvo_auth_link_init(&self.link, key, opt.sender_id, 1u, publish, &self);
        memset(key, 0, sizeof(key));
        if (keyed != TVO_AUTH_OK ||
            tvo_auth_follow_clock(&self.link.auth, tvo_auth_wall_clock_counter, TVO_AUTH_NEW_SENDER_WINDOW_US) != TVO_AUTH_OK) {
            fprintf(stderr, "tvo_firmware_node: error: authentication set-up failed\n");
            return 1;
        }
        self.keyed = 1;
    } else {
        fprintf(stderr, "tvo_firmware_node: the bus is unauthenticated (no --key-file): anyone on the network can "
                        "drive, stop or replace this session\n");
    }
    if (tvo_node_init(&self.node, (int8_t)opt.own_robot, boot_id, self.keyed ? tvo_auth_link_publish : publish,
                      self.keyed ? (void *)&self.link : (void *)&self) != 0) {
        fprintf(stderr, "tvo_firmware_node: error: node set-up failed (boot id %lld)\n", (long long)boot_id);
        return 1;
    }
    if (opt.own_robot >= 0) {
        fprintf(stderr, "tvo_firmware_node: node of robot %d (%s; sessions of up to %d robots)\n", (int)opt.own_robot,
                self.keyed ? "keyed bus" : "unauthenticated bus", (int)TVO_NODE_MAX_ROBOTS);
    }
    for (int k = 0; k < LOG_KEYS; ++k) {
        self.limits[k].last_us = -1;
    }
    self.lcm = lcm_create(opt.url);
    if (self.lcm == NULL) {
        fprintf(stderr,
                "tvo_firmware_node: error: cannot create LCM on '%s'.\n"
                "  UDP multicast on loopback may be disabled. Fix (as root):\n"
                "    ip link set lo multicast on && ip route add 224.0.0.0/4 dev lo\n"
                "  or choose another provider with --lcm-url URL or LCM_DEFAULT_URL.\n",
                opt.url != NULL ? opt.url : "LCM default");
        return 1;
    }
    lcm_subscribe(self.lcm, TVO_CHANNEL_SESSION, on_message, &self);
    lcm_subscribe(self.lcm, TVO_CHANNEL_SAMPLE, on_message, &self);
    lcm_subscribe(self.lcm, TVO_CHANNEL_CHAIN_SAMPLE, on_message, &self);
    lcm_subscribe(self.lcm, TVO_CHANNEL_TARGET, on_message, &self);

    int exit_code = 0;
    while (!g_stop_signal && (opt.keep_running || !self.node.stop_requested)) {
        if (opt.exit_with_parent && getppid() != parent) {
            fprintf(stderr, "tvo_firmware_node: the parent process is gone; exiting\n");
            break;
        }
        const tvo_lcm_node_counters_t before = self.node.counters;
        const uint32_t acks_before = self.node.acks;
        const int64_t deadline = tvo_node_poll(&self.node, monotonic_us());
        log_changes(&self, &before, acks_before);
        if (wait_and_handle(self.lcm, deadline) < 0) {
            fprintf(stderr, "tvo_firmware_node: error: LCM receive failed\n");
            exit_code = 1;
            break;
        }
    }
    log_flush(&self);
    tvo_auth_clear(&self.link.auth);
    lcm_destroy(self.lcm);
    return exit_code;
}
