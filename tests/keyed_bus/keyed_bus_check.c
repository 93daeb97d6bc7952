/*
 * Acceptance checks of an authenticated bus against tvo_firmware_node over LCM (wire v3, issue 36):
 *
 *   keyed_bus_check replay --node NODE --lcm-url URL --work DIR
 *     A recording of a whole session (every START repeat, every sample, the STOP) made before the node
 *     restarts is replayed after the restart, at once and twice: the moment the new boot announces
 *     itself (racing the genuine plant's START) and again amid the genuine plant's samples, from a
 *     socket of its own. Nothing of it may be accepted: no ack for the old session, every replayed
 *     frame counted by the node as wrong_boot, idle, other_session or replayed, and the genuine plant,
 *     which follows the plant's rules (hear TVO_NODE, START naming the boot), is served: every one of
 *     its samples answered with a computed command.
 *   keyed_bus_check flood --node NODE --lcm-url URL --work DIR
 *     20,000 forged frames sent at 10,000 a second from a socket of their own (samples with forged
 *     tags from the plant's sender id and from unknown ones, cut-short frames, frames of another
 *     fingerprint, replays of the plant's own samples, forged STARTs) while the genuine plant runs its
 *     session in lockstep: no genuine sample lost (every one answered with a computed command, the
 *     node's accepted count equal to the samples sent), every forged frame counted in the node's
 *     counters as what it is, and no datagram dropped by the kernel on the node's socket.
 *
 * Counts are asserted, not times: the genuine plant is in lockstep (it waits for each answer, up to
 * ANSWER_TIMEOUT_S, which only bounds a failing run), and the flood's rate is a pace it keeps if the
 * machine allows (the achieved rate is printed). The node's counters are its own announcement after
 * the STOP (node_status_t on TVO_NODE, signed) and its exit summary (socket drops). Exit 0: passed;
 * 1: a check failed (the line says which); 2: bad arguments or set-up.
 */
#define _GNU_SOURCE

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/select.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "auth.h"
#include "auth_key_file.h"
#include "channels.h"
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"
#include "udpm_socket.h"

#define PERIOD_US 10000
#define DELAY_US 5000
#define WATCHDOG_PERIODS 10
#define ANSWER_TIMEOUT_S 10.0      /* bounds a failing run; a passing one never waits this long */
#define NODE_TIMEOUT_S 20.0        /* for the node to announce itself, or to ack */
#define RECORDED_PERIODS 50
#define REPLAY_SERVED_PERIODS 100
#define REPLAY_AGAIN_AT 30
#define FLOOD_FRAMES 20000u
#define FLOOD_RATE_HZ 10000.0
#define FLOOD_AFTER_PERIODS 20     /* genuine periods after the flood ended, before the STOP */
#define MAX_RECORDED 512
#define FRAME_CAPACITY (TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES)

static const char *g_node_path;
static const char *g_url;
static char g_key_path[1024];
static char g_boot_path[1024];
static char g_log_path[1024];
static uint8_t g_key[TVO_AUTH_KEY_BYTES];

/* ---- Results ---------------------------------------------------------------------------------- */

static int g_failures;

static void check(int ok, const char *format, ...) __attribute__((format(printf, 2, 3)));
static void check(int ok, const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fprintf(stdout, "%s: ", ok ? "ok" : "FAILED");
    vfprintf(stdout, format, args);
    fprintf(stdout, "\n");
    fflush(stdout);
    va_end(args);
    g_failures += ok ? 0 : 1;
}

static void die(const char *format, ...) __attribute__((format(printf, 1, 2), noreturn));
static void die(const char *format, ...)
{
    va_list args;
    va_start(args, format);
    fprintf(stdout, "keyed_bus_check: error: ");
    vfprintf(stdout, format, args);
    fprintf(stdout, "\n");
    va_end(args);
    exit(2);
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- The node's process ------------------------------------------------------------------------ */

static pid_t g_node_pid = -1;

static void start_node(void)
{
    g_node_pid = fork();
    if (g_node_pid < 0) {
        die("fork: %s", strerror(errno));
    }
    if (g_node_pid == 0) {
        const int log = open(g_log_path, O_WRONLY | O_CREAT | O_APPEND, 0600);
        if (log >= 0) {
            dup2(log, STDERR_FILENO);
            dup2(log, STDOUT_FILENO);
        }
        for (int fd = 3; fd < 1024; ++fd) { /* the plant's sockets are not the node's */
            close(fd);
        }
        execl(g_node_path, g_node_path, "--key-file", g_key_path, "--boot-file", g_boot_path, "--lcm-url", g_url,
              "--keep-running", "--exit-with-parent", (char *)NULL);
        _exit(127);
    }
}

/* SIGTERM, then the exit status (0 expected: the node ends cleanly on SIGTERM). */
static int stop_node(void)
{
    if (g_node_pid <= 0) {
        return -1;
    }
    kill(g_node_pid, SIGTERM);
    int status = 0;
    while (waitpid(g_node_pid, &status, 0) < 0 && errno == EINTR) {
    }
    g_node_pid = -1;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/* The value of `key=` on the node log's last "counts" line, or -1. */
static long last_count(const char *key)
{
    FILE *f = fopen(g_log_path, "r");
    char line[4096];
    long value = -1;
    char pattern[64];
    snprintf(pattern, sizeof(pattern), " %s=", key);
    while (f != NULL && fgets(line, sizeof(line), f) != NULL) {
        const char *found = strstr(line, "tvo_firmware_node: counts ") == line ? strstr(line, pattern) : NULL;
        if (found != NULL) {
            value = strtol(found + strlen(pattern), NULL, 10);
        }
    }
    if (f != NULL) {
        fclose(f);
    }
    return value;
}

/* ---- The genuine plant (lcm_types/README.md, "Writing your own plant") ---------------------------- */

typedef struct {
    int channel;
    uint32_t length;
    uint8_t bytes[FRAME_CAPACITY];
} recorded_t;

typedef struct {
    lcm_t *lcm;
    tvo_auth_t auth;                  /* signs the plant's frames, opens the node's */
    tvo_lcm_node_status_t status;     /* the newest announcement heard */
    int status_heard;
    int64_t boot_heard;               /* the newest boot announced */
    int acked;                        /* the awaited ack came */
    int32_t awaited_session;
    int8_t awaited_action;
    int64_t awaited_boot;
    int8_t ack_status;
    uint32_t foreign_acks;            /* acks of foreign_session from foreign_boot */
    int32_t foreign_session;          /* a session the node of foreign_boot must never ack */
    int64_t foreign_boot;
    int32_t awaited_sequence;         /* the sample whose command is awaited */
    int answered;
    int8_t answer_status;
    double x_m, y_m, heading_rad;     /* the robot, moved by the commands it applies */
    double speed_mps, turn_rate_radps;
    uint32_t dropped;                 /* node frames that did not open (there must be none) */
    uint32_t recorded;                /* frames published, kept for a replay */
    recorded_t *recording;
} plant_t;

static uint8_t g_frame[FRAME_CAPACITY];

static void on_node_frame(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    plant_t *p = (plant_t *)user;
    size_t length = 0u;
    if (tvo_auth_open(&p->auth, channel, (const uint8_t *)rbuf->data, rbuf->data_size, &length) != TVO_AUTH_OK) {
        p->dropped++;
        return;
    }
    const int number = tvo_node_channel_of(channel);
    if (number == TVO_NODE_CH_NODE) {
        if (tvo_lcm_node_status_t_decode(rbuf->data, 0, (int)length, &p->status) == (int)length) {
            p->status_heard = 1;
            p->boot_heard = p->status.boot_id > p->boot_heard ? p->status.boot_id : p->boot_heard;
        }
    } else if (number == TVO_NODE_CH_SESSION_ACK) {
        tvo_lcm_session_ack_t ack;
        if (tvo_lcm_session_ack_t_decode(rbuf->data, 0, (int)length, &ack) != (int)length) {
            return;
        }
        if (ack.session_id == p->foreign_session && ack.boot_id == p->foreign_boot) {
            p->foreign_acks++;
        }
        if (ack.session_id == p->awaited_session && ack.action == p->awaited_action && ack.boot_id == p->awaited_boot) {
            p->acked = 1;
            p->ack_status = ack.status;
        }
    } else if (number == TVO_NODE_CH_COMMAND) {
        tvo_lcm_unicycle_command_t command;
        if (tvo_lcm_unicycle_command_t_decode(rbuf->data, 0, (int)length, &command) == (int)length &&
            command.header.measurement_sequence == p->awaited_sequence) {
            p->answered = 1;
            p->answer_status = command.header.status;
            if (command.header.status == 0 || (command.header.flags & TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0) {
                p->speed_mps = (double)command.speed_mps;
                p->turn_rate_radps = (double)command.turn_rate_radps;
            }
        }
    }
}

/* Handles the plant's LCM traffic for up to wait_s; 0, or -1 on a receive error. */
static int plant_handle(plant_t *p, double wait_s)
{
    const int fd = lcm_get_fileno(p->lcm);
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(fd, &readable);
    struct timeval tv = {(time_t)wait_s, (suseconds_t)((wait_s - (double)(time_t)wait_s) * 1e6)};
    const int ready = select(fd + 1, &readable, NULL, NULL, &tv);
    if (ready < 0) {
        return errno == EINTR ? 0 : -1;
    }
    return ready > 0 ? lcm_handle(p->lcm) : 0;
}

static void plant_init(plant_t *p, recorded_t *recording)
{
    memset(p, 0, sizeof(*p));
    p->lcm = lcm_create(g_url);
    if (p->lcm == NULL) {
        die("cannot create LCM on %s", g_url);
    }
    if (tvo_auth_init(&p->auth, g_key, TVO_AUTH_SENDER_PLANT, 1u) != TVO_AUTH_OK ||
        tvo_auth_follow_clock(&p->auth, tvo_auth_wall_clock_counter) != TVO_AUTH_OK) {
        die("the plant's authentication");
    }
    p->foreign_session = -1;
    p->awaited_sequence = -1;
    p->x_m = 1.3; /* 0.3 m outside the target's circle, at rest */
    p->heading_rad = 1.5;
    p->recording = recording;
    const char *outputs[] = {TVO_CHANNEL_NODE, TVO_CHANNEL_SESSION_ACK, TVO_CHANNEL_COMMAND, TVO_CHANNEL_TELEMETRY};
    for (unsigned i = 0u; i < sizeof(outputs) / sizeof(outputs[0]); ++i) {
        /* Unbounded queues: LCM 1.3.1 drops, uncounted, past 30 queued messages per subscription. */
        lcm_subscription_set_queue_capacity(lcm_subscribe(p->lcm, outputs[i], on_node_frame, p), 0);
    }
}

/* Signs and publishes the encoded message in g_frame[0 .. length) on channel; keeps a copy if recording. */
static void plant_publish(plant_t *p, int channel, int length)
{
    size_t signed_length = 0u;
    if (length <= 0 || tvo_auth_sign(&p->auth, tvo_node_channel_name(channel), g_frame, (size_t)length,
                                     sizeof(g_frame), &signed_length) != TVO_AUTH_OK) {
        die("the plant cannot sign a message");
    }
    lcm_publish(p->lcm, tvo_node_channel_name(channel), g_frame, (unsigned)signed_length);
    if (p->recording != NULL && p->recorded < MAX_RECORDED) {
        recorded_t *r = &p->recording[p->recorded++];
        r->channel = channel;
        r->length = (uint32_t)signed_length;
        memcpy(r->bytes, g_frame, signed_length);
    }
}

/* Rule 1: the node's announcement of a boot newer than `after`; its boot id. */
static int64_t plant_hear_node(plant_t *p, int64_t after)
{
    const double deadline = now_s() + NODE_TIMEOUT_S;
    while (p->boot_heard <= after && now_s() < deadline) {
        if (plant_handle(p, 0.05) < 0) {
            die("LCM receive failed");
        }
    }
    if (p->boot_heard <= after) {
        die("no announcement of a new boot from the node within %.0f s (see %s)", NODE_TIMEOUT_S, g_log_path);
    }
    return p->boot_heard;
}

static tvo_lcm_session_t g_session;

/* One unicycle on a circle, CLOCK_PLANT lockstep, naming boot `boot`. */
static void make_session(int32_t session_id, int8_t action, int64_t boot, int64_t utime)
{
    (void)tvo_protocol_default_start(&g_session, 1);
    g_session.utime = utime;
    g_session.session_id = session_id;
    g_session.action = action;
    g_session.node_boot_id[0] = boot;
    g_session.epoch_utime = utime + 100000;
    g_session.period_us = PERIOD_US;
    g_session.delay_us = DELAY_US;
    g_session.watchdog_periods = WATCHDOG_PERIODS;
    g_session.omega_max_radps = 6.0;
    g_session.speed_max_mps = 2.0;
    g_session.robot[0].target.kind = TVO_LCM_PATH_T_KIND_CIRCLE;
    g_session.robot[0].target.semi_axis_m[0] = 1.0;
    g_session.robot[0].target.omega_radps = 0.5;
}

/* Rule 2 (and 6): a session message naming `boot`, repeated with back-off until its ack; the ack's status. */
static int8_t plant_session(plant_t *p, int32_t session_id, int8_t action, int64_t boot, int64_t utime)
{
    p->acked = 0;
    p->awaited_session = session_id;
    p->awaited_action = action;
    p->awaited_boot = boot;
    const double deadline = now_s() + NODE_TIMEOUT_S;
    double backoff = 0.1;
    while (!p->acked && now_s() < deadline) {
        make_session(session_id, action, boot, utime);
        plant_publish(p, TVO_NODE_CH_SESSION, tvo_lcm_session_t_encode(g_frame, 0, (int)sizeof(g_frame), &g_session));
        const double until = now_s() + backoff;
        while (!p->acked && now_s() < until) {
            if (plant_handle(p, 0.01) < 0) {
                die("LCM receive failed");
            }
        }
        backoff = backoff < 0.8 ? 2.0 * backoff : 0.8;
    }
    if (!p->acked) {
        die("no ack of session %d (action %d) from boot %lld within %.0f s (see %s)", session_id, action,
            (long long)boot, NODE_TIMEOUT_S, g_log_path);
    }
    return p->ack_status;
}

/* Rules 3-4: period n's sample, then its command (lockstep); the command's status, or -1 if none came. */
static int plant_period(plant_t *p, int32_t session_id, int32_t n, int64_t utime)
{
    tvo_lcm_unicycle_sample_t sample;
    memset(&sample, 0, sizeof(sample));
    sample.header.utime = utime + 100000 + (int64_t)n * PERIOD_US + PERIOD_US - DELAY_US;
    sample.header.session_id = session_id;
    sample.header.sequence = n;
    sample.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    sample.position_m[0] = p->x_m;
    sample.position_m[1] = p->y_m;
    sample.heading_rad = (float)atan2(sin(p->heading_rad), cos(p->heading_rad));
    sample.speed_mps = (float)p->speed_mps;
    p->answered = 0;
    p->awaited_sequence = n;
    plant_publish(p, TVO_NODE_CH_SAMPLE, tvo_lcm_unicycle_sample_t_encode(g_frame, 0, (int)sizeof(g_frame), &sample));
    const double deadline = now_s() + ANSWER_TIMEOUT_S;
    while (!p->answered && now_s() < deadline) {
        if (plant_handle(p, 0.01) < 0) {
            die("LCM receive failed");
        }
    }
    /* The robot moves one period under the command it holds (an exact arc). */
    const double h = 1e-6 * PERIOD_US, v = p->speed_mps, w = p->turn_rate_radps, th = p->heading_rad;
    if (fabs(w) < 1e-9) {
        p->x_m += v * h * cos(th);
        p->y_m += v * h * sin(th);
    } else {
        p->x_m += v / w * (sin(th + w * h) - sin(th));
        p->y_m -= v / w * (cos(th + w * h) - cos(th));
    }
    p->heading_rad = th + w * h;
    return p->answered ? p->answer_status : -1;
}

/* The node's announcement after its session ended (STOP): idle, no session; its counters are final. */
static const tvo_lcm_node_counters_t *plant_final_counters(plant_t *p, int64_t boot)
{
    p->status_heard = 0;
    const double deadline = now_s() + NODE_TIMEOUT_S;
    while (now_s() < deadline) {
        if (plant_handle(p, 0.05) < 0) {
            die("LCM receive failed");
        }
        if (p->status_heard && p->status.boot_id == boot && p->status.state == TVO_LCM_NODE_STATUS_T_STATE_IDLE &&
            p->status.session_id == -1) {
            return &p->status.counters;
        }
        p->status_heard = 0;
    }
    die("no idle announcement of boot %lld after the STOP", (long long)boot);
    return NULL;
}

static int64_t wall_utime(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_REALTIME, &ts);
    return (int64_t)ts.tv_sec * 1000000 + ts.tv_nsec / 1000;
}

/* ---- replay: a recording from before the restart ------------------------------------------------ */

static recorded_t g_recording[MAX_RECORDED];

/* Publishes every recorded frame at once from the attacker's own socket. */
static void replay_all(lcm_t *attacker, uint32_t count)
{
    for (uint32_t i = 0u; i < count; ++i) {
        lcm_publish(attacker, tvo_node_channel_name(g_recording[i].channel), g_recording[i].bytes, g_recording[i].length);
    }
}

static int check_replay(void)
{
    static plant_t plant;
    plant_init(&plant, g_recording);
    lcm_t *attacker = lcm_create(g_url);
    if (attacker == NULL) {
        die("cannot create the attacker's LCM");
    }
    start_node();
    const int64_t boot1 = plant_hear_node(&plant, 0);
    const int32_t recorded_session = 100;
    const int64_t utime = wall_utime();
    check(plant_session(&plant, recorded_session, TVO_LCM_SESSION_T_ACTION_START, boot1, utime) == 0,
          "the recorded session %d started on boot %lld", recorded_session, (long long)boot1);
    int served = 0;
    for (int32_t n = 0; n < RECORDED_PERIODS; ++n) {
        served += plant_period(&plant, recorded_session, n, utime) == 0;
    }
    check(served == RECORDED_PERIODS, "the recorded session was served: %d of %d samples", served, RECORDED_PERIODS);
    check(plant_session(&plant, recorded_session, TVO_LCM_SESSION_T_ACTION_STOP, boot1, utime) == 0,
          "the recorded session stopped");
    const uint32_t recorded = plant.recorded;
    uint32_t recorded_sessions = 0u;
    for (uint32_t i = 0u; i < recorded; ++i) {
        recorded_sessions += g_recording[i].channel == TVO_NODE_CH_SESSION;
    }
    plant.recording = NULL; /* the rest is the genuine plant's new session */
    check(stop_node() == 0, "the node of boot %lld ended on SIGTERM", (long long)boot1);

    /* The restart: the recording is replayed the moment the new boot announces itself, racing the
     * genuine plant's START, and again amid its samples. */
    start_node();
    const int64_t boot2 = plant_hear_node(&plant, boot1);
    plant.foreign_session = recorded_session;
    plant.foreign_boot = boot2;
    replay_all(attacker, recorded);
    const int32_t session = 101;
    const int64_t utime2 = wall_utime();
    check(plant_session(&plant, session, TVO_LCM_SESSION_T_ACTION_START, boot2, utime2) == 0,
          "the genuine plant's session %d started on the new boot %lld", session, (long long)boot2);
    int computed = 0;
    int first_computed = -1;
    for (int32_t n = 0; n < REPLAY_SERVED_PERIODS; ++n) {
        if (n == REPLAY_AGAIN_AT) {
            replay_all(attacker, recorded);
        }
        const int status = plant_period(&plant, session, n, utime2);
        computed += status == 0;
        if (status == 0 && first_computed < 0) {
            first_computed = n;
        }
    }
    check(plant_session(&plant, session, TVO_LCM_SESSION_T_ACTION_STOP, boot2, utime2) == 0, "the genuine session stopped");
    const tvo_lcm_node_counters_t *c = plant_final_counters(&plant, boot2);
    const int32_t replayed_frames = 2 * (int32_t)recorded;
    const int32_t counted = c->wrong_boot + c->idle + c->other_session + c->replayed;
    printf("recording: %u frames (%u session messages, %u samples), replayed twice; the node counted wrong_boot %d, "
           "idle %d, other_session %d, replayed %d, unauthenticated %d, malformed %d; accepted %d, sessions %d\n",
           recorded, recorded_sessions, recorded - recorded_sessions, c->wrong_boot, c->idle, c->other_session,
           c->replayed, c->unauthenticated, c->malformed, c->accepted, c->sessions);
    check(plant.foreign_acks == 0u, "the new boot acked nothing of the recorded session (%u acks)", plant.foreign_acks);
    check(c->sessions == 1, "the new boot ran one session, the genuine one (%d)", c->sessions);
    check(counted == replayed_frames, "every replayed frame was dropped and counted: %d of %d", counted, replayed_frames);
    check(c->unauthenticated == 0 && c->malformed == 0, "the genuine frames all opened");
    check(c->accepted == REPLAY_SERVED_PERIODS && computed == REPLAY_SERVED_PERIODS,
          "the genuine plant was served: %d of %d samples accepted, %d computed commands", c->accepted,
          REPLAY_SERVED_PERIODS, computed);
    check(first_computed == 0, "served from its first sample after the restart, well within the watchdog (%d periods)",
          WATCHDOG_PERIODS);
    check(plant.dropped == 0u, "the plant opened every frame of the node (%u did not)", plant.dropped);
    check(stop_node() == 0, "the node of boot %lld ended on SIGTERM", (long long)boot2);
    lcm_destroy(attacker);
    lcm_destroy(plant.lcm);
    return g_failures;
}

/* ---- flood: forged frames at 10,000 a second -------------------------------------------------- */

typedef enum {
    FORGED_TAG_PLANT_ID, /* the plant's sender id, a counter above its, a forged tag: a verify each */
    FORGED_TAG_NEW_ID,   /* a sender id never heard, a forged tag */
    FORGED_SHORT,        /* cut short by one byte */
    FORGED_FINGERPRINT,  /* the right length, another type's fingerprint */
    FORGED_REPLAY,       /* one of the plant's own samples again */
    FORGED_START,        /* a whole START (11 kB, in fragments) with a forged tag */
    FORGED_KINDS
} forged_kind_t;

/* The kind of forged frame i: mostly what costs the node a verify. */
static forged_kind_t forged_kind(uint32_t i)
{
    if (i % 200u == 199u) {
        return FORGED_START;
    }
    switch (i % 10u) {
    case 6: return FORGED_TAG_NEW_ID;
    case 7: return FORGED_SHORT;
    case 8: return FORGED_FINGERPRINT;
    case 9: return FORGED_REPLAY;
    default: return FORGED_TAG_PLANT_ID;
    }
}

typedef struct {
    lcm_t *lcm;
    int32_t session_id;
    uint32_t sent[FORGED_KINDS];
    uint32_t unsent;                   /* publishes that failed (not counted as sent) */
    double seconds;
    pthread_mutex_t lock;              /* guards the plant's last sample frame, copied for replays */
    uint8_t genuine[FRAME_CAPACITY];
    uint32_t genuine_length;
    volatile int done;
} flood_t;

static flood_t g_flood;

static void put_be(uint8_t *p, uint64_t v, unsigned bytes)
{
    for (unsigned i = 0u; i < bytes; ++i) {
        p[i] = (uint8_t)(v >> (8u * (bytes - 1u - i)));
    }
}

static void *flood_thread(void *unused)
{
    (void)unused;
    static uint8_t frame[FRAME_CAPACITY];
    static tvo_lcm_session_t start;
    uint64_t random = 0x9e3779b97f4a7c15ull;
    const double begin = now_s();
    struct timespec next;
    clock_gettime(CLOCK_MONOTONIC, &next);
    for (uint32_t i = 0u; i < FLOOD_FRAMES; ++i) {
        /* Pace: frame i leaves at begin + i / rate, or at once if behind. */
        const long step_ns = (long)(1e9 / FLOOD_RATE_HZ);
        next.tv_nsec += step_ns;
        while (next.tv_nsec >= 1000000000L) {
            next.tv_nsec -= 1000000000L;
            next.tv_sec += 1;
        }
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &next, NULL);
        const forged_kind_t kind = forged_kind(i);
        random ^= random << 13;
        random ^= random >> 7;
        random ^= random << 17;
        int channel = TVO_NODE_CH_SAMPLE;
        uint32_t length = 0u;
        if (kind == FORGED_REPLAY) {
            pthread_mutex_lock(&g_flood.lock);
            length = g_flood.genuine_length;
            memcpy(frame, g_flood.genuine, length);
            pthread_mutex_unlock(&g_flood.lock);
        } else if (kind == FORGED_START) {
            make_session(g_flood.session_id, TVO_LCM_SESSION_T_ACTION_STOP, 1, 0);
            start = g_session;
            length = (uint32_t)tvo_lcm_session_t_encode(frame, 0, (int)sizeof(frame), &start) + TVO_AUTH_TRAILER_BYTES;
            channel = TVO_NODE_CH_SESSION;
        } else {
            tvo_lcm_unicycle_sample_t sample;
            memset(&sample, 0, sizeof(sample));
            sample.header.session_id = g_flood.session_id;
            sample.header.sequence = (int32_t)(i & 0xffffu);
            sample.header.utime = (int64_t)(random & 0xffffffu);
            sample.position_m[0] = 100.0;
            length = (uint32_t)tvo_lcm_unicycle_sample_t_encode(frame, 0, (int)sizeof(frame), &sample) + TVO_AUTH_TRAILER_BYTES;
            if (kind == FORGED_FINGERPRINT) {
                frame[0] ^= 0x5au;
            }
        }
        if (kind != FORGED_REPLAY) { /* a trailer with a forged tag */
            uint8_t *trailer = frame + length - TVO_AUTH_TRAILER_BYTES;
            put_be(trailer, kind == FORGED_TAG_NEW_ID ? 0x10000u + i : TVO_AUTH_SENDER_PLANT, 4u);
            put_be(trailer + 4u, (UINT64_C(1) << 62) + i, 8u);
            for (unsigned b = 0u; b < TVO_AUTH_TAG_BYTES; ++b) {
                trailer[12u + b] = (uint8_t)(random >> (8u * (b % 8u)));
            }
        }
        if (kind == FORGED_SHORT) {
            length -= 1u;
        }
        if (length > 0u) {
            if (lcm_publish(g_flood.lcm, tvo_node_channel_name(channel), frame, length) == 0) {
                g_flood.sent[kind]++;
            } else {
                g_flood.unsent++;
            }
        }
    }
    g_flood.seconds = now_s() - begin;
    g_flood.done = 1;
    return NULL;
}

static int check_flood(void)
{
    static plant_t plant;
    plant_init(&plant, NULL);
    memset(&g_flood, 0, sizeof(g_flood));
    pthread_mutex_init(&g_flood.lock, NULL);
    g_flood.lcm = lcm_create(g_url);
    if (g_flood.lcm == NULL) {
        die("cannot create the flood's LCM");
    }
    start_node();
    const int64_t boot = plant_hear_node(&plant, 0);
    /* The plant hears the flood too (LCM reads every datagram of the group): its buffer sized like the node's. */
    tvo_udpm_socket_t plant_socket;
    (void)tvo_udpm_socket_open(&plant_socket, tvo_udpm_url_port(g_url, NULL), 16u * 1024u * 1024u, NULL);
    const int32_t session = 200;
    g_flood.session_id = session;
    const int64_t utime = wall_utime();
    check(plant_session(&plant, session, TVO_LCM_SESSION_T_ACTION_START, boot, utime) == 0, "session %d started", session);
    /* A first genuine sample, so a replay has something to copy. */
    int32_t sent = 0;
    int computed = plant_period(&plant, session, sent++, utime) == 0;
    pthread_mutex_lock(&g_flood.lock);
    memcpy(g_flood.genuine, g_frame, sizeof(g_flood.genuine));
    g_flood.genuine_length = (uint32_t)(tvo_node_channel_message_bytes(TVO_NODE_CH_SAMPLE) + TVO_AUTH_TRAILER_BYTES);
    pthread_mutex_unlock(&g_flood.lock);
    struct rusage before_usage;
    getrusage(RUSAGE_CHILDREN, &before_usage);
    pthread_t thread;
    if (pthread_create(&thread, NULL, flood_thread, NULL) != 0) {
        die("pthread_create");
    }
    int after_flood = 0;
    while (after_flood < FLOOD_AFTER_PERIODS) {
        const int status = plant_period(&plant, session, sent++, utime);
        computed += status == 0;
        pthread_mutex_lock(&g_flood.lock);
        memcpy(g_flood.genuine, g_frame, g_flood.genuine_length);
        pthread_mutex_unlock(&g_flood.lock);
        after_flood += g_flood.done ? 1 : 0;
        if (status != 0 && status != -1) {
            break; /* refused: a forged frame moved the node; the checks below say so */
        }
    }
    pthread_join(thread, NULL);
    check(plant_session(&plant, session, TVO_LCM_SESSION_T_ACTION_STOP, boot, utime) == 0, "session %d stopped", session);
    const tvo_lcm_node_counters_t *c = plant_final_counters(&plant, boot);
    uint32_t forged = 0u;
    for (int k = 0; k < FORGED_KINDS; ++k) {
        forged += g_flood.sent[k];
    }
    const uint32_t expect_unauthenticated =
        g_flood.sent[FORGED_TAG_PLANT_ID] + g_flood.sent[FORGED_TAG_NEW_ID] + g_flood.sent[FORGED_START];
    const uint32_t expect_malformed = g_flood.sent[FORGED_SHORT] + g_flood.sent[FORGED_FINGERPRINT];
    const uint32_t expect_replayed = g_flood.sent[FORGED_REPLAY];
    printf("flood: %u publishes failed; the plant's socket: %u B, %u datagrams dropped by the kernel\n", g_flood.unsent,
           plant_socket.buffer_bytes, tvo_udpm_socket_drops(&plant_socket));
    printf("flood: %u forged frames in %.2f s (%.0f a second; paced at %.0f), during %d genuine periods; the node "
           "counted unauthenticated %d (sent %u), malformed %d (sent %u), replayed %d (sent %u); accepted %d\n",
           forged, g_flood.seconds, (double)forged / g_flood.seconds, FLOOD_RATE_HZ, sent, c->unauthenticated,
           expect_unauthenticated, c->malformed, expect_malformed, c->replayed, expect_replayed, c->accepted);
    check(c->accepted == sent && computed == sent,
          "no genuine sample lost: %d sent, %d accepted, %d computed commands received", sent, c->accepted, computed);
    check(c->unauthenticated == (int32_t)expect_unauthenticated && c->malformed == (int32_t)expect_malformed &&
              c->replayed == (int32_t)expect_replayed,
          "every forged frame counted as what it is (%u forged)", forged);
    check(c->other_session == 0 && c->idle == 0 && c->wrong_boot == 0,
          "no forged frame reached the node's session logic");
    check(plant.dropped == 0u, "the plant opened every frame of the node (%u did not)", plant.dropped);
    check(stop_node() == 0, "the node ended on SIGTERM");
    struct rusage after_usage;
    getrusage(RUSAGE_CHILDREN, &after_usage);
    const double node_cpu_s = (double)(after_usage.ru_utime.tv_sec - before_usage.ru_utime.tv_sec) +
                              1e-6 * (double)(after_usage.ru_utime.tv_usec - before_usage.ru_utime.tv_usec) +
                              (double)(after_usage.ru_stime.tv_sec - before_usage.ru_stime.tv_sec) +
                              1e-6 * (double)(after_usage.ru_stime.tv_usec - before_usage.ru_stime.tv_usec);
    const long socket_drops = last_count("socket_drops");
    check(socket_drops == 0, "the kernel dropped no datagram on the node's socket (%ld)", socket_drops);
    printf("the node's CPU time during the flood and the rest of the session: %.3f s, %.1f us per frame it handled "
           "(LCM's receive thread and its queue included; informational)\n",
           node_cpu_s, 1e6 * node_cpu_s / (double)(forged + (uint32_t)sent));
    lcm_destroy(g_flood.lcm);
    lcm_destroy(plant.lcm);
    return g_failures;
}

/* ---- main ------------------------------------------------------------------------------------- */

static void write_key(void)
{
    FILE *random = fopen("/dev/urandom", "rb");
    if (random == NULL || fread(g_key, 1, sizeof(g_key), random) != sizeof(g_key)) {
        die("cannot read /dev/urandom");
    }
    fclose(random);
    unlink(g_key_path);
    const int fd = open(g_key_path, O_WRONLY | O_CREAT | O_EXCL, 0600);
    if (fd < 0) {
        die("cannot write the key file %s: %s", g_key_path, strerror(errno));
    }
    char hex[2u * TVO_AUTH_KEY_BYTES + 2u];
    for (unsigned i = 0u; i < TVO_AUTH_KEY_BYTES; ++i) {
        snprintf(hex + 2u * i, 3u, "%02x", g_key[i]);
    }
    hex[2u * TVO_AUTH_KEY_BYTES] = '\n';
    if (write(fd, hex, sizeof(hex) - 1u) != (ssize_t)(sizeof(hex) - 1u)) {
        die("cannot write the key file");
    }
    close(fd);
}

int main(int argc, char **argv)
{
    const char *mode = argc > 1 ? argv[1] : "";
    const char *work = NULL;
    for (int i = 2; i + 1 < argc; i += 2) {
        if (strcmp(argv[i], "--node") == 0) {
            g_node_path = argv[i + 1];
        } else if (strcmp(argv[i], "--lcm-url") == 0) {
            g_url = argv[i + 1];
        } else if (strcmp(argv[i], "--work") == 0) {
            work = argv[i + 1];
        } else {
            die("unexpected argument '%s'", argv[i]);
        }
    }
    if ((strcmp(mode, "replay") != 0 && strcmp(mode, "flood") != 0) || g_node_path == NULL || g_url == NULL ||
        work == NULL) {
        die("usage: keyed_bus_check replay|flood --node NODE --lcm-url URL --work DIR");
    }
    if (mkdir(work, 0700) != 0 && errno != EEXIST) {
        die("cannot make %s: %s", work, strerror(errno));
    }
    snprintf(g_key_path, sizeof(g_key_path), "%s/bus.key", work);
    snprintf(g_boot_path, sizeof(g_boot_path), "%s/node-boot-id", work);
    snprintf(g_log_path, sizeof(g_log_path), "%s/node.log", work);
    unlink(g_log_path);
    write_key();
    signal(SIGPIPE, SIG_IGN);
    const int failures = strcmp(mode, "replay") == 0 ? check_replay() : check_flood();
    if (g_node_pid > 0) {
        stop_node();
    }
    printf("%s: %s (node log: %s)\n", mode, failures == 0 ? "passed" : "FAILED", g_log_path);
    return failures == 0 ? 0 : 1;
}
