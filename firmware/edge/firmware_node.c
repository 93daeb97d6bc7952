/*
 * tvo_firmware_node: the control core behind LCM, as a host process (hardware-in-the-loop edge).
 *
 * Subscribes the node's input channels (channels.h: TVO_SESSION, TVO_SAMPLE, TVO_CHAIN_SAMPLE,
 * TVO_TARGET) and publishes its acks, commands, telemetry and announcements (TVO_NODE). The logic
 * (sessions, periods, the watchdog timer, codecs, announcements) is node.c's, shared with the
 * processor-in-the-loop program; this file is the LCM transport, the node's identity (its boot id,
 * from a counter file: boot_file.h), the node's clock (CLOCK_MONOTONIC), the command line and the
 * logs. SIGINT or SIGTERM ends the process with exit code 0; so does a session STOP, unless
 * --keep-running.
 *
 * Floods: each wake-up handles every message LCM has queued (up to a bound, and never past the node's
 * next deadline), so a burst of forged frames costs time, not genuine samples. LCM's receive thread
 * queues whatever arrives (its ring buffer grows rather than drop), but LCM 1.3.1 keeps at most 30
 * messages per subscription and silently drops any more: the node's subscriptions are unbounded, so
 * the only place a frame can be lost is the kernel socket buffer behind LCM, which is sized
 * (udpm_socket.h) and whose drops are counted. Every drop the node can see is counted: the node's
 * counters (node_counters_t, announced on TVO_NODE) and the socket's, both in the logs and at exit.
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
#include "boot_file.h"
#include "node.h"
#include "udpm_socket.h"

/* The only global: set by SIGINT/SIGTERM, polled by the main loop. */
static volatile sig_atomic_t g_stop_signal = 0;

/* Longest wait for a message before the stop flag, the parent and the node's timer are checked. */
#define NODE_POLL_US 100000
/* Messages handled per wake-up at most (a flood is drained in turns with the node's timer). */
#define NODE_DRAIN_MAX 4096
/* The kernel receive buffer asked for: 1 s of a 10,000 frames/s flood of ~80-byte datagrams at the
 * kernel's ~1.5 KiB accounting each, should LCM's receive thread not run for that long. */
#define NODE_RECV_BUFFER_BYTES (16u * 1024u * 1024u)
/* Each kind of log line is written at most once per this interval, with a count of the rest. */
#define NODE_LOG_INTERVAL_US 1000000

/* Log keys: one per refusal status, then the other kinds of event. */
enum {
    LOG_MALFORMED = TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS,
    LOG_UNAUTHENTICATED,
    LOG_REPLAYED,
    LOG_WRONG_BOOT,
    LOG_IDLE,
    LOG_OTHER_SESSION,
    LOG_PREDICTED,
    LOG_SAFE_STOP,
    LOG_TARGET,
    LOG_SPEED_MISMATCH,
    LOG_SOCKET_DROPS,
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
    tvo_node_t node;      /* the transport-independent logic (node.h) */
    tvo_auth_link_t link; /* with --key-file: frames checked and opened before the node, its messages signed */
    int keyed;
    tvo_udpm_socket_t socket; /* LCM's receive socket (udpm), for its buffer and its drops */
    uint32_t socket_drops;    /* the kernel's drops on it, as last read */
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
    if (events == 0u) {
        return;
    }
    snprintf(self->limits[key].text, sizeof(self->limits[key].text), "%s", what);
    if (log_allowed(self, key, events, &suppressed)) {
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
            fprintf(stderr, "tvo_firmware_node: %s (%u more like it since the last line of its kind)\n",
                    self->limits[k].text, self->limits[k].unwritten);
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
    if (ack->status == TVO_LCM_COMMAND_HEADER_T_STATUS_OK) {
        snprintf(line, sizeof(line), "%s of session %lld done (running: %lld)", action, (long long)ack->session_id,
                 (long long)ack->running_session_id);
    } else {
        snprintf(line, sizeof(line), "%s of session %lld refused: %s (parameter %s, part %s, entry %d; running: %lld)",
                 action, (long long)ack->session_id, tvo_protocol_status_str(ack->status),
                 tvo_protocol_param_str(ack->bad_param), tvo_protocol_part_str(ack->bad_part), (int)ack->bad_index,
                 (long long)ack->running_session_id);
    }
    const int key = ack->action == TVO_LCM_SESSION_T_ACTION_START
                        ? (ack->status == TVO_LCM_COMMAND_HEADER_T_STATUS_OK ? LOG_START_DONE : LOG_START_REFUSED)
                    : ack->action == TVO_LCM_SESSION_T_ACTION_STOP ? LOG_STOP
                                                                   : LOG_OTHER_ACK;
    log_event(self, key, 1u, line);
}

static uint32_t grew(int32_t after, int32_t before)
{
    return after > before ? (uint32_t)(after - before) : 0u;
}

/* What changed in the counters (since boot) during one message or timer call, as rate-limited lines. */
static void log_changes(lcm_node_t *self, const tvo_lcm_node_counters_t *before, uint32_t acks_before)
{
    const tvo_lcm_node_counters_t *after = tvo_node_counters(&self->node);
    char line[160];
    if (self->node.acks != acks_before) {
        log_ack(self);
    }
    for (int s = 0; s < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++s) {
        if (after->refused[s] > before->refused[s]) {
            snprintf(line, sizeof(line), "sample refused: %s", tvo_protocol_status_str(s));
            log_event(self, s, grew(after->refused[s], before->refused[s]), line);
        }
    }
    log_event(self, LOG_MALFORMED, grew(after->malformed, before->malformed),
              self->keyed ? "a frame that is no message of its channel was dropped (length or fingerprint)"
                          : "a frame that is no message of its channel was dropped (if the plant signs its messages, "
                            "start the node with the same --key-file)");
    log_event(self, LOG_UNAUTHENTICATED, grew(after->unauthenticated, before->unauthenticated),
              "a frame without a valid tag was dropped (forged, altered, or another key)");
    log_event(self, LOG_REPLAYED, grew(after->replayed, before->replayed),
              "a frame with a used counter was dropped (a replay)");
    log_event(self, LOG_WRONG_BOOT, grew(after->wrong_boot, before->wrong_boot),
              "a START or STOP naming another boot of this node was dropped (a recording, or another node's)");
    log_event(self, LOG_IDLE, grew(after->idle, before->idle), "a sample or target arrived while no session ran (dropped)");
    log_event(self, LOG_OTHER_SESSION, grew(after->other_session, before->other_session),
              "a sample or target of another session id was ignored");
    log_event(self, LOG_PREDICTED, grew(after->predicted, before->predicted), "a robot's missing sample was predicted");
    log_event(self, LOG_SAFE_STOP, grew(after->safe_stops, before->safe_stops), "safe stop published");
    log_event(self, LOG_TARGET, grew(after->targets_refused, before->targets_refused), "streamed target sample refused");
    log_event(self, LOG_SPEED_MISMATCH, grew(after->speed_mismatch, before->speed_mismatch),
              "measured speed contradicts the commanded speed (stalled wheels?)");
}

/* The kernel's drops on LCM's socket since the last look, as a log line. */
static void log_socket_drops(lcm_node_t *self)
{
    const uint32_t drops = tvo_udpm_socket_drops(&self->socket);
    if (drops != self->socket_drops) {
        char line[200];
        snprintf(line, sizeof(line),
                 "the kernel dropped datagrams on the node's socket (its receive buffer of %u B was full: "
                 "%u since start)", self->socket.buffer_bytes, drops);
        log_event(self, LOG_SOCKET_DROPS, drops - self->socket_drops, line);
        self->socket_drops = drops;
    }
}

/* Every subscribed channel arrives here encoded; node.c decodes it (the same path as on the MCU). */
static void on_message(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    lcm_node_t *self = (lcm_node_t *)user;
    const tvo_lcm_node_counters_t before = *tvo_node_counters(&self->node);
    const uint32_t acks_before = self->node.acks;
    const int number = tvo_node_channel_of(channel);
    if (self->keyed) {
        (void)tvo_auth_link_receive(&self->link, &self->node, number, (const uint8_t *)rbuf->data, rbuf->data_size,
                                    monotonic_us());
    } else if (!tvo_node_channel_is_input(number)) {
        tvo_node_count_drop(&self->node, TVO_NODE_DROP_MALFORMED); /* not subscribed: cannot happen; counted if it does */
    } else {
        (void)tvo_node_handle(&self->node, number, (const uint8_t *)rbuf->data, rbuf->data_size, monotonic_us());
    }
    log_changes(self, &before, acks_before);
}

static void print_usage(FILE *out)
{
    fprintf(out,
            "Usage: tvo_firmware_node [--key-file FILE [--sender-id N]] [--own-robot I] [--boot-file PATH]\n"
            "                         [--lcm-url URL] [--keep-running] [--exit-with-parent]\n"
            "Runs the TV-O controller behind LCM: sessions on TVO_SESSION, samples in, commands out; announces\n"
            "itself on TVO_NODE (its boot id, which a START must name).\n"
            "  --key-file FILE     authenticate every message both ways with this 32-byte key (tools/keygen;\n"
            "                      mode 0600); without it the bus is unauthenticated (lab use)\n"
            "  --sender-id N       this node's sender id on a keyed bus (default 1, robot I's node 256 + I;\n"
            "                      unique per key holder)\n"
            "  --own-robot I       drive robot I only (a fleet's node: it hears every robot's samples and\n"
            "                      evaluates the joint law); default: every robot of the session. Sessions of\n"
            "                      up to %d robots\n"
            "  --boot-file PATH    the boot counter, incremented at every start so a boot id never repeats\n"
            "                      (default $XDG_STATE_HOME/%s, else ~/.local/state/%s)\n"
            "  --lcm-url URL       LCM provider URL (default: $LCM_DEFAULT_URL, else LCM's default udpm)\n"
            "  --keep-running      serve session after session (default: exit after a session's STOP)\n"
            "  --exit-with-parent  exit when the process that started this one dies (no orphans)\n"
            "  -h, --help          show this help\n",
            (int)TVO_NODE_MAX_ROBOTS, TVO_BOOT_FILE_RELATIVE_PATH, TVO_BOOT_FILE_RELATIVE_PATH);
}

typedef struct {
    const char *key_file;  /* NULL: unauthenticated */
    uint32_t sender_id;
    const char *boot_file; /* NULL: the default path */
    const char *url;       /* NULL: LCM's default */
    int keep_running;
    int exit_with_parent;
    int32_t own_robot;     /* -1: every robot of the session */
} node_options_t;

/* The value of option `name` at argv[*i] ("--name VALUE" or "--name=VALUE"), advancing *i; else NULL. */
static const char *option_value(int argc, char **argv, int *i, const char *name)
{
    const size_t n = strlen(name);
    if (strncmp(argv[*i], name, n) != 0) {
        return NULL;
    }
    if (argv[*i][n] == '=') {
        return argv[*i] + n + 1;
    }
    if (argv[*i][n] == '\0' && *i + 1 < argc) {
        return argv[++*i];
    }
    return NULL;
}

/* Returns 0 and fills *opt, 1 after --help, or 2 after printing why the arguments are bad. */
static int parse_args(int argc, char **argv, node_options_t *opt)
{
    memset(opt, 0, sizeof(*opt));
    opt->own_robot = -1;
    int sender_id_given = 0;
    for (int i = 1; i < argc; ++i) {
        const char *value = NULL;
        if ((value = option_value(argc, argv, &i, "--key-file")) != NULL) {
            opt->key_file = value;
        } else if ((value = option_value(argc, argv, &i, "--boot-file")) != NULL) {
            opt->boot_file = value;
        } else if ((value = option_value(argc, argv, &i, "--lcm-url")) != NULL) {
            opt->url = value;
        } else if ((value = option_value(argc, argv, &i, "--sender-id")) != NULL) {
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
        } else if ((value = option_value(argc, argv, &i, "--own-robot")) != NULL) {
            char *end = NULL;
            const long r = strtol(value, &end, 10);
            if (end == value || *end != '\0' || r < 0 || r >= TVO_NODE_MAX_ROBOTS) {
                fprintf(stderr, "tvo_firmware_node: error: --own-robot takes a robot 0 .. %d, not '%s'\n",
                        (int)TVO_NODE_MAX_ROBOTS - 1, value);
                return 2;
            }
            opt->own_robot = (int32_t)r;
        } else if (strcmp(argv[i], "-h") == 0 || strcmp(argv[i], "--help") == 0) {
            print_usage(stdout);
            return 1;
        } else if (strcmp(argv[i], "--keep-running") == 0) {
            opt->keep_running = 1;
        } else if (strcmp(argv[i], "--exit-with-parent") == 0) {
            opt->exit_with_parent = 1;
        } else {
            fprintf(stderr, "tvo_firmware_node: error: unexpected argument '%s' (see --help)\n", argv[i]);
            return 2;
        }
    }
    if (sender_id_given && opt->key_file == NULL) {
        fprintf(stderr, "tvo_firmware_node: error: --sender-id needs --key-file (it names this node on a keyed bus)\n");
        return 2;
    }
    if (!sender_id_given) { /* each node its own counter stream */
        opt->sender_id = opt->own_robot >= 0 ? TVO_AUTH_SENDER_FLEET_NODE + (uint32_t)opt->own_robot : TVO_AUTH_SENDER_NODE;
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

/* 1 if LCM has a message queued (its notify pipe is readable) within wait_us, 0 if not, -1 on error. */
static int lcm_ready(lcm_t *lcm, int64_t wait_us)
{
    const int fd = lcm_get_fileno(lcm);
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(fd, &readable);
    struct timeval tv;
    tv.tv_sec = (time_t)(wait_us / 1000000);
    tv.tv_usec = (suseconds_t)(wait_us % 1000000);
    const int ready = select(fd + 1, &readable, NULL, NULL, &tv);
    if (ready < 0) {
        return (errno == EINTR) ? 0 : -1; /* a signal interrupts the wait: the loop looks at it */
    }
    return ready > 0;
}

/* Waits for LCM traffic until deadline_us (node clock) at most, then handles every queued message, up
 * to NODE_DRAIN_MAX and not past the deadline (the node's timer comes first). -1 on a receive error. */
static int wait_and_drain(lcm_t *lcm, int64_t deadline_us)
{
    int64_t wait_us = deadline_us - monotonic_us();
    wait_us = wait_us < 0 ? 0 : (wait_us > NODE_POLL_US ? NODE_POLL_US : wait_us);
    int ready = lcm_ready(lcm, wait_us);
    for (int handled = 0; ready > 0 && handled < NODE_DRAIN_MAX && !g_stop_signal; ++handled) {
        if (lcm_handle(lcm) != 0) {
            return -1;
        }
        if (monotonic_us() >= deadline_us) {
            break;
        }
        ready = lcm_ready(lcm, 0);
    }
    return ready < 0 ? -1 : 0;
}

/* The node's boot id from its counter file; exit code 2 after saying why not. */
static int take_boot_id(const node_options_t *opt, int64_t *boot_id)
{
    char default_path[4096];
    char why[600];
    const char *path = opt->boot_file;
    if (path == NULL) {
        if (tvo_boot_file_default_path(default_path, sizeof(default_path), why, sizeof(why)) != 0) {
            fprintf(stderr, "tvo_firmware_node: error: %s (--boot-file PATH)\n", why);
            return 2;
        }
        path = default_path;
    }
    if (tvo_boot_file_next(path, boot_id, why, sizeof(why)) != 0) {
        fprintf(stderr, "tvo_firmware_node: error: %s (%s)\n", why,
                opt->boot_file != NULL ? "--boot-file" : "the default boot file; choose another with --boot-file PATH");
        return 2;
    }
    return 0;
}

/* The counts at exit, one line of key=value (the node's counters since boot, the socket's drops). */
static void print_summary(const lcm_node_t *self)
{
    const tvo_lcm_node_counters_t *c = tvo_node_counters(&self->node);
    fprintf(stderr,
            "tvo_firmware_node: counts boot_id=%lld accepted=%d malformed=%d unauthenticated=%d replayed=%d "
            "wrong_boot=%d idle=%d other_session=%d predicted=%d safe_stops=%d targets_refused=%d "
            "speed_mismatch=%d sessions=%d socket_drops=%u unsigned_drops=%u",
            (long long)self->node.boot_id, c->accepted, c->malformed, c->unauthenticated, c->replayed, c->wrong_boot,
            c->idle, c->other_session, c->predicted, c->safe_stops, c->targets_refused, c->speed_mismatch, c->sessions,
            tvo_udpm_socket_drops(&self->socket), self->link.unsigned_drops);
    for (int s = 0; s < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS; ++s) {
        if (c->refused[s] != 0) {
            fprintf(stderr, " refused_%d=%d", s, c->refused[s]);
        }
    }
    fprintf(stderr, "\n");
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
    uint8_t key[TVO_AUTH_KEY_BYTES];
    if (opt.key_file != NULL) { /* read before the boot id is spent: a bad key file changes nothing */
        char why[300];
        if (tvo_auth_key_file_read(opt.key_file, key, why, sizeof(why)) != 0) {
            fprintf(stderr, "tvo_firmware_node: error: %s\n", why);
            return 2;
        }
    }
    int64_t boot_id = 0;
    const int boot_status = take_boot_id(&opt, &boot_id);
    if (boot_status != 0) {
        memset(key, 0, sizeof(key));
        return boot_status;
    }
    if (opt.key_file != NULL) {
        const tvo_auth_status_t keyed = tvo_auth_link_init(&self.link, key, opt.sender_id, boot_id, publish, &self);
        memset(key, 0, sizeof(key));
        if (keyed != TVO_AUTH_OK) {
            fprintf(stderr, "tvo_firmware_node: error: authentication set-up failed: %s\n", tvo_auth_status_str(keyed));
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
    for (int k = 0; k < LOG_KEYS; ++k) {
        self.limits[k].last_us = -1;
    }
    /* Sockets on LCM's port this process inherited (a plant that started it): not the node's own. */
    int url_sized = 0;
    const int port = tvo_udpm_url_port(opt.url, &url_sized);
    tvo_udpm_socket_census_t inherited;
    tvo_udpm_socket_census(&inherited, port);
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
    for (int channel = TVO_NODE_CH_FIRST; channel <= TVO_NODE_CH_LAST; ++channel) {
        if (tvo_node_channel_is_input(channel)) {
            lcm_subscription_t *subscription = lcm_subscribe(self.lcm, tvo_node_channel_name(channel), on_message, &self);
            /* LCM 1.3.1 queues at most 30 messages per subscription and drops the rest without a count:
             * unbounded here, so a burst is dropped, if at all, by the kernel, which counts it. */
            if (subscription == NULL || lcm_subscription_set_queue_capacity(subscription, 0) != 0) {
                fprintf(stderr, "tvo_firmware_node: error: cannot subscribe to %s\n", tvo_node_channel_name(channel));
                lcm_destroy(self.lcm);
                return 1;
            }
        }
    }
    /* LCM's receive socket exists once something is subscribed: size its buffer, unless the URL did. */
    const int socket_found =
        port > 0 && tvo_udpm_socket_open(&self.socket, port, url_sized ? 0u : NODE_RECV_BUFFER_BYTES, &inherited) == 0;
    char robots[64];
    if (opt.own_robot >= 0) {
        snprintf(robots, sizeof(robots), "robot %d's node", (int)opt.own_robot);
    } else {
        snprintf(robots, sizeof(robots), "every robot's node");
    }
    fprintf(stderr, "tvo_firmware_node: boot %lld, %s, %s, sessions of up to %d robots", (long long)boot_id, robots,
            self.keyed ? "keyed" : "unauthenticated", (int)TVO_NODE_MAX_ROBOTS);
    if (socket_found) {
        fprintf(stderr, ", receive buffer %u B%s", self.socket.buffer_bytes,
                self.socket.forced || url_sized || self.socket.buffer_bytes >= NODE_RECV_BUFFER_BYTES
                    ? ""
                    : " (capped by net.core.rmem_max; root may raise it: sysctl -w net.core.rmem_max=16777216)");
    }
    fprintf(stderr, "\n");

    int exit_code = 0;
    while (!g_stop_signal && (opt.keep_running || !tvo_node_stop_requested(&self.node))) {
        if (opt.exit_with_parent && getppid() != parent) {
            fprintf(stderr, "tvo_firmware_node: the parent process is gone; exiting\n");
            break;
        }
        const tvo_lcm_node_counters_t before = *tvo_node_counters(&self.node);
        const uint32_t acks_before = self.node.acks;
        const int64_t deadline = tvo_node_poll(&self.node, monotonic_us());
        log_changes(&self, &before, acks_before);
        log_socket_drops(&self);
        if (wait_and_drain(self.lcm, deadline) < 0) {
            fprintf(stderr, "tvo_firmware_node: error: LCM receive failed\n");
            exit_code = 1;
            break;
        }
    }
    log_socket_drops(&self);
    log_flush(&self);
    print_summary(&self);
    tvo_auth_clear(&self.link.auth);
    lcm_destroy(self.lcm);
    return exit_code;
}
