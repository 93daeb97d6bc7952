/*
 * tvo_pil_bridge: joins LCM and the serial link of a processor-in-the-loop target (QEMU's -serial
 * socket). Messages on the node's input channels (tvo_node_channel_is_input in channels.h) go to the
 * target as frames (serial_frame.h: COBS, zero runs, CRC-32, tagged with channels.h's numbers); frames from the
 * target (its acks, commands, telemetry and announcements) are republished on LCM unchanged. The
 * bridge moves LCM's encoded bytes (trailers included on a keyed bus), so the target sees exactly
 * what tvo_firmware_node would, with one exception, the link's own queue policy: a session_t is
 * 11.4 kB, and QEMU's UART carries about 4 kB/s (before the framing's zero runs, a START took 3 s;
 * now it is a few hundred bytes on the link, but a slow link still holds it), while a plant repeats its
 * START every 100 .. 800 ms until the ack comes; queued behind each other, six repeats held the first
 * sample back 18 s. So a repeat of the session message in flight (same session id and action) is held
 * while that one is on its way (until the target acks it, or for its length at 2 kB/s): dropped if the
 * ack comes (the plant hears it), written if not. Other session messages go at once.
 * Samples do not queue behind a session message either: while one is on its way, each robot's newest
 * sample waits in the bridge (a newer one replaces it, counted samples_replaced: the target would have
 * refused it as stale) and goes when the session message is acked or its time is up. Measured on a
 * loaded machine, an 11 kB START took 1.5 to 3 s to clock in; samples written behind it reached the
 * board in a burst, seconds old. Every other frame goes at once. The bridge reads the session id and
 * action of session messages and acks, and the robot of samples, nothing else.
 *
 * Usage: tvo_pil_bridge --connect HOST:PORT [--lcm-url URL] [--corrupt-every N] [--connect-timeout-s S]
 *   --corrupt-every N   flip one bit in every N-th sample frame sent to the target and in every N-th
 *                       command frame coming from it (a test of the framing: each end must drop those
 *                       frames, which then look like lost messages). Counted per kind, so which
 *                       messages are hit does not depend on timing (how often the plant repeated its
 *                       START; samples are counted as the bridge takes them, so a held sample that a
 *                       newer one replaced may be the one hit); session frames are never hit (a lost
 *                       STOP would leave the target running).
 * Ends when the target closes the link (its program ended), on SIGINT/SIGTERM, or on an error;
 * prints the frame counts as key=value pairs (samples_to_target: every sample taken for the target, of
 * which samples_held waited behind a session message and samples_replaced were never written, a newer
 * one of their robot sent instead). Exit code 0, or 1 on errors, 2 on bad arguments.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <netdb.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <time.h>
#include <unistd.h>

#include <lcm/lcm.h>

#include "auth.h"
#include "channels.h"
#include "serial_frame.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

static volatile sig_atomic_t g_stop_signal = 0;

#define BRIDGE_READ_CHUNK 4096
#define BRIDGE_POLL_MS 100
/* LCM messages handled per wake-up at most before the serial side is served again. */
#define BRIDGE_DRAIN_MAX 256
/* The slowest link a held session repeat waits for: the one in flight gets its length at this rate. */
#define SESSION_LINK_FLOOR_BYTES_PER_S 2000.0
#define SESSION_IN_FLIGHT_MIN_S 0.5
/* A sample frame held while a session message is on its way (a sample is ~60 bytes, signed ~100). */
#define SAMPLE_FRAME_MAX_BYTES 256u
#define BRIDGE_MAX_ROBOTS TVO_LCM_SESSION_T_MAX_ROBOTS

/* Every frame the link carries fits a serial frame: the largest message, signed. */
_Static_assert(TVO_FRAME_MAX_PAYLOAD >= TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES,
               "a serial frame holds a signed session_t");

typedef struct {
    lcm_t *lcm;
    int socket_fd;
    unsigned long corrupt_every;
    unsigned long frames_to_target;
    unsigned long samples_to_target;
    unsigned long samples_corrupted;
    unsigned long frames_from_target;         /* passed the checks and republished */
    unsigned long commands_from_target;       /* intact as sent, before any corruption */
    unsigned long commands_corrupted;
    int failed;
    tvo_frame_decoder_t decoder;
    tvo_frame_decoder_t peek;                 /* reads a frame's channel before it may be corrupted */
    uint8_t frame[TVO_FRAME_MAX_ENCODED];
    uint8_t payload[TVO_FRAME_MAX_PAYLOAD];
    /* The frame from the target being collected, delimiter excluded; one byte more than any valid
     * frame, so an overlong one reaches the decoder cut short (it fails the COBS or CRC check there). */
    uint8_t raw[TVO_FRAME_MAX_ENCODED + 1u];
    size_t raw_length;
    /* The session message on its way to the target, and a repeat of it held meanwhile. */
    int session_in_flight;
    int32_t flight_session_id;
    int8_t flight_action;
    double flight_until_s;                    /* written then; given up on (not acked) at this time */
    int repeat_held;
    uint8_t held[TVO_FRAME_MAX_ENCODED];
    size_t held_length;
    unsigned long repeats_held;               /* repeats that waited for the link */
    unsigned long repeats_dropped;            /* repeats the target's ack made unneeded */
    /* Per robot, its newest sample while a session message is on its way (sent when that one is done). */
    int sample_held[BRIDGE_MAX_ROBOTS];
    uint8_t held_sample[BRIDGE_MAX_ROBOTS][SAMPLE_FRAME_MAX_BYTES];
    size_t held_sample_length[BRIDGE_MAX_ROBOTS];
    unsigned long samples_held;               /* samples that waited for a session message */
    unsigned long samples_replaced;           /* held samples a newer one of the same robot replaced (not sent) */
} bridge_t;

static double monotonic_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* The session id and action of a session message or an ack (LCM-encoded; a keyed frame's trailer after
 * it is not read); 0, or -1 if it does not decode. */
static int session_of(int channel, const uint8_t *data, uint32_t length, int32_t *session_id, int8_t *action)
{
    static tvo_lcm_session_t session;
    tvo_lcm_session_ack_t ack;
    if (channel == TVO_NODE_CH_SESSION && tvo_lcm_session_t_decode(data, 0, (int)length, &session) > 0) {
        *session_id = session.session_id;
        *action = session.action;
        return 0;
    }
    if (channel == TVO_NODE_CH_SESSION_ACK && tvo_lcm_session_ack_t_decode(data, 0, (int)length, &ack) > 0) {
        *session_id = ack.session_id;
        *action = ack.action;
        return 0;
    }
    return -1;
}

/* The robot of a sample (unicycle or chain; a keyed frame's trailer after it is not read), or -1 if it
 * does not decode or is out of range. */
static int robot_of(int channel, const uint8_t *data, uint32_t length)
{
    static tvo_lcm_unicycle_sample_t unicycle;
    static tvo_lcm_chain_sample_t chain;
    int robot = -1;
    if (channel == TVO_NODE_CH_SAMPLE && tvo_lcm_unicycle_sample_t_decode(data, 0, (int)length, &unicycle) > 0) {
        robot = unicycle.header.robot;
    } else if (channel == TVO_NODE_CH_CHAIN_SAMPLE && tvo_lcm_chain_sample_t_decode(data, 0, (int)length, &chain) > 0) {
        robot = chain.header.robot;
    }
    return (robot >= 0 && robot < BRIDGE_MAX_ROBOTS) ? robot : -1;
}

static void on_signal(int signo)
{
    (void)signo;
    g_stop_signal = 1;
}

static int write_all(int fd, const uint8_t *data, size_t length)
{
    while (length > 0u) {
        const ssize_t n = write(fd, data, length);
        if (n < 0 && errno == EINTR) {
            continue;
        }
        if (n <= 0) {
            return -1;
        }
        data += n;
        length -= (size_t)n;
    }
    return 0;
}

/* 1 if this is the N-th frame of its kind (count already advanced) and corruption is on. */
static int is_nth(const bridge_t *b, unsigned long count)
{
    return b->corrupt_every > 0u && count % b->corrupt_every == 0u;
}

/* Flips one bit in the middle of an encoded frame (never its delimiter); a byte that would become
 * 0x00 becomes 0x10 instead, since a zero would split the frame in two rather than corrupt it. */
static void corrupt(uint8_t *frame, size_t length)
{
    uint8_t *byte = &frame[length / 2u];
    *byte ^= 0x10u;
    if (*byte == 0u) {
        *byte = 0x10u;
    }
}

static void write_to_target(bridge_t *b, const uint8_t *frame, size_t length)
{
    ++b->frames_to_target;
    if (write_all(b->socket_fd, frame, length) != 0) {
        fprintf(stderr, "tvo_pil_bridge: error: writing to the target failed: %s\n", strerror(errno));
        b->failed = 1;
    }
}

/* A session message goes on its way: the link is busy with it until its ack, or its length at the floor rate. */
static void session_in_flight(bridge_t *b, int32_t session_id, int8_t action, size_t length)
{
    const double transfer_s = (double)length / SESSION_LINK_FLOOR_BYTES_PER_S;
    b->session_in_flight = 1;
    b->flight_session_id = session_id;
    b->flight_action = action;
    b->flight_until_s = monotonic_s() + (transfer_s > SESSION_IN_FLIGHT_MIN_S ? transfer_s : SESSION_IN_FLIGHT_MIN_S);
}

/* The session message on its way is done (acked, or its time is up): the samples held behind it go,
 * robot by robot, each the newest of its robot. */
static void release_samples(bridge_t *b)
{
    for (int robot = 0; robot < BRIDGE_MAX_ROBOTS; ++robot) {
        if (b->sample_held[robot]) {
            b->sample_held[robot] = 0;
            write_to_target(b, b->held_sample[robot], b->held_sample_length[robot]);
        }
    }
}

/* The session message in flight was not acked in its time: the held repeat, if any, goes now (and the
 * samples then wait for it); else the held samples go. */
static void session_timer(bridge_t *b)
{
    if (b->session_in_flight && monotonic_s() >= b->flight_until_s) {
        b->session_in_flight = 0;
        if (b->repeat_held) {
            b->repeat_held = 0;
            session_in_flight(b, b->flight_session_id, b->flight_action, b->held_length);
            write_to_target(b, b->held, b->held_length);
        } else {
            release_samples(b);
        }
    }
}

/* A sample passes the link's corruption test (--corrupt-every) as it is sent or held, so which samples
 * are hit does not depend on timing; then it is written, or copied to hold (its robot's slot). */
static void sample_to_target(bridge_t *b, uint8_t *frame, size_t length, uint8_t *hold)
{
    if (is_nth(b, ++b->samples_to_target) && length > 2u) {
        corrupt(frame, length - 1u); /* length - 1: the delimiter stays */
        ++b->samples_corrupted;
    }
    if (hold != NULL) {
        memcpy(hold, frame, length);
    } else {
        write_to_target(b, frame, length);
    }
}

static void to_target(const lcm_recv_buf_t *rbuf, const char *channel, void *user)
{
    bridge_t *b = (bridge_t *)user;
    const int number = tvo_node_channel_of(channel);
    size_t length = 0u;
    const tvo_frame_status_t st = tvo_frame_encode((uint8_t)number, (const uint8_t *)rbuf->data, rbuf->data_size,
                                                   b->frame, sizeof(b->frame), &length);
    if (st != TVO_FRAME_OK) {
        fprintf(stderr, "tvo_pil_bridge: a %u-byte message on %s does not fit a frame (dropped)\n",
                rbuf->data_size, channel);
        return;
    }
    int32_t session_id = 0;
    int8_t action = 0;
    if (number == TVO_NODE_CH_SESSION &&
        session_of(number, (const uint8_t *)rbuf->data, rbuf->data_size, &session_id, &action) == 0) {
        session_timer(b);
        if (b->session_in_flight && session_id == b->flight_session_id && action == b->flight_action) {
            memcpy(b->held, b->frame, length); /* the newest repeat waits for the link */
            b->held_length = length;
            b->repeats_held += b->repeat_held ? 0u : 1u;
            b->repeat_held = 1;
            return;
        }
        b->repeat_held = 0; /* another session message: a held repeat of the last one is stale */
        session_in_flight(b, session_id, action, length);
    }
    const int sample = number == TVO_NODE_CH_SAMPLE || number == TVO_NODE_CH_CHAIN_SAMPLE;
    if (sample) {
        session_timer(b);
    }
    const int robot = sample ? robot_of(number, (const uint8_t *)rbuf->data, rbuf->data_size) : -1;
    if (robot >= 0 && b->session_in_flight && length <= SAMPLE_FRAME_MAX_BYTES) {
        /* Behind the session message it would reach the target stale: the robot's newest waits. */
        b->samples_replaced += b->sample_held[robot] ? 1u : 0u;
        ++b->samples_held;
        b->sample_held[robot] = 1;
        b->held_sample_length[robot] = length;
        sample_to_target(b, b->frame, length, b->held_sample[robot]);
        return;
    }
    if (sample) {
        sample_to_target(b, b->frame, length, NULL);
        return;
    }
    write_to_target(b, b->frame, length);
}

static int connect_to(const char *host_port, double timeout_s)
{
    char host[256];
    const char *colon = strrchr(host_port, ':');
    if (colon == NULL || (size_t)(colon - host_port) >= sizeof(host)) {
        return -2;
    }
    memcpy(host, host_port, (size_t)(colon - host_port));
    host[colon - host_port] = '\0';
    struct addrinfo hints;
    memset(&hints, 0, sizeof(hints));
    hints.ai_family = AF_UNSPEC;
    hints.ai_socktype = SOCK_STREAM;
    struct addrinfo *addresses = NULL;
    if (getaddrinfo(host, colon + 1, &hints, &addresses) != 0) {
        return -2;
    }
    /* The target (QEMU) may still be starting: retry until the timeout. */
    const struct timespec pause = {0, 50000000L};
    int fd = -1;
    for (double waited = 0.0; fd < 0 && waited <= timeout_s && !g_stop_signal; waited += 0.05) {
        for (struct addrinfo *a = addresses; a != NULL && fd < 0; a = a->ai_next) {
            fd = socket(a->ai_family, a->ai_socktype, a->ai_protocol);
            if (fd >= 0 && connect(fd, a->ai_addr, a->ai_addrlen) != 0) {
                close(fd);
                fd = -1;
            }
            if (fd >= 0) {
                /* Frames are small and lockstep waits for each answer: no Nagle delay. */
                const int one = 1;
                (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
            }
        }
        if (fd < 0) {
            nanosleep(&pause, NULL);
        }
    }
    freeaddrinfo(addresses);
    return fd;
}

/* The channel of a collected frame from the target if it passes the checks, else 0. */
static int peek_channel(bridge_t *b)
{
    tvo_frame_decoder_init(&b->peek);
    uint8_t channel = 0u;
    size_t length = 0u;
    for (size_t i = 0; i < b->raw_length; ++i) {
        (void)tvo_frame_decoder_push(&b->peek, b->raw[i], &channel, b->payload, &length);
    }
    return tvo_frame_decoder_push(&b->peek, 0u, &channel, b->payload, &length) == TVO_FRAME_OK ? channel : 0;
}

/* A frame from the target is complete: maybe corrupt it, then decode it (a corrupted or broken frame
 * is dropped and counted by the decoder) and republish it. */
static void frame_from_target(bridge_t *b)
{
    const int peeked = peek_channel(b);
    const int command = peeked == TVO_NODE_CH_COMMAND || peeked == TVO_NODE_CH_CHAIN_COMMAND;
    if (command && is_nth(b, ++b->commands_from_target)) {
        corrupt(b->raw, b->raw_length);
        ++b->commands_corrupted;
    }
    uint8_t channel = 0u;
    size_t length = 0u;
    for (size_t i = 0; i < b->raw_length; ++i) {
        (void)tvo_frame_decoder_push(&b->decoder, b->raw[i], &channel, b->payload, &length);
    }
    b->raw_length = 0u;
    if (tvo_frame_decoder_push(&b->decoder, 0u, &channel, b->payload, &length) != TVO_FRAME_OK) {
        return;
    }
    const char *name = tvo_node_channel_name(channel);
    if (name == NULL) {
        fprintf(stderr, "tvo_pil_bridge: frame on unknown channel %u (dropped)\n", (unsigned)channel);
        return;
    }
    int32_t session_id = 0;
    int8_t action = 0;
    if (channel == TVO_NODE_CH_SESSION_ACK && b->session_in_flight &&
        session_of(channel, b->payload, (uint32_t)length, &session_id, &action) == 0 &&
        session_id == b->flight_session_id && action == b->flight_action) {
        b->session_in_flight = 0; /* it arrived: the plant hears the ack, a held repeat is not needed */
        b->repeats_dropped += b->repeat_held ? 1u : 0u;
        b->repeat_held = 0;
        release_samples(b);
    }
    ++b->frames_from_target;
    lcm_publish(b->lcm, name, b->payload, (unsigned)length);
}

static void from_target(bridge_t *b, const uint8_t *bytes, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        if (bytes[i] == 0u) {
            frame_from_target(b);
        } else if (b->raw_length < sizeof(b->raw)) {
            b->raw[b->raw_length++] = bytes[i];
        }
    }
}

static int usage(FILE *out, int code)
{
    fprintf(out, "Usage: tvo_pil_bridge --connect HOST:PORT [--lcm-url URL] [--corrupt-every N] "
                 "[--connect-timeout-s S]\n"
                 "Joins LCM and a processor-in-the-loop target's serial socket (see the source's header).\n");
    return code;
}

int main(int argc, char **argv)
{
    const char *connect_arg = NULL;
    const char *url = NULL;
    unsigned long corrupt_every = 0u;
    double timeout_s = 10.0;
    for (int i = 1; i < argc; ++i) {
        const char *arg = argv[i];
        const char *value = (i + 1 < argc) ? argv[i + 1] : NULL;
        char *end = NULL;
        if (strcmp(arg, "-h") == 0 || strcmp(arg, "--help") == 0) {
            return usage(stdout, 0);
        } else if (strcmp(arg, "--connect") == 0 && value != NULL) {
            connect_arg = value;
            ++i;
        } else if (strcmp(arg, "--lcm-url") == 0 && value != NULL) {
            url = value;
            ++i;
        } else if (strcmp(arg, "--corrupt-every") == 0 && value != NULL) {
            const long parsed = strtol(value, &end, 10);
            if (end == value || *end != '\0' || parsed < 0) {
                fprintf(stderr, "tvo_pil_bridge: error: --corrupt-every: expected N >= 0, got '%s'\n", value);
                return 2;
            }
            corrupt_every = (unsigned long)parsed;
            ++i;
        } else if (strcmp(arg, "--connect-timeout-s") == 0 && value != NULL) {
            timeout_s = strtod(value, &end);
            if (*end != '\0' || !(timeout_s >= 0.0)) {
                fprintf(stderr, "tvo_pil_bridge: error: --connect-timeout-s: expected S >= 0, got '%s'\n", value);
                return 2;
            }
            ++i;
        } else {
            fprintf(stderr, "tvo_pil_bridge: error: unexpected argument '%s'\n", arg);
            return usage(stderr, 2);
        }
    }
    if (connect_arg == NULL) {
        fprintf(stderr, "tvo_pil_bridge: error: --connect HOST:PORT is required\n");
        return usage(stderr, 2);
    }
    struct sigaction sa;
    memset(&sa, 0, sizeof(sa));
    sa.sa_handler = on_signal;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGPIPE, SIG_IGN); /* a closed link is reported by write(), not by a signal */

    static bridge_t b;
    memset(&b, 0, sizeof(b));
    b.corrupt_every = corrupt_every;
    tvo_frame_decoder_init(&b.decoder);
    b.socket_fd = connect_to(connect_arg, timeout_s);
    if (b.socket_fd < 0) {
        fprintf(stderr, "tvo_pil_bridge: error: cannot connect to %s (is the target's QEMU running with "
                        "-serial tcp:%s,server?)\n", connect_arg, connect_arg);
        return 1;
    }
    b.lcm = lcm_create(url);
    if (b.lcm == NULL) {
        fprintf(stderr, "tvo_pil_bridge: error: cannot create LCM on '%s' (see tvo_firmware_node --help "
                        "for the multicast fix)\n", url != NULL ? url : "LCM default");
        close(b.socket_fd);
        return 1;
    }
    for (int channel = TVO_NODE_CH_FIRST; channel <= TVO_NODE_CH_LAST; ++channel) {
        if (tvo_node_channel_is_input(channel)) {
            /* Unbounded: LCM drops past 30 queued messages per subscription, silently (32 robots' samples). */
            lcm_subscription_t *subscription = lcm_subscribe(b.lcm, tvo_node_channel_name(channel), to_target, &b);
            if (subscription == NULL || lcm_subscription_set_queue_capacity(subscription, 0) != 0) {
                fprintf(stderr, "tvo_pil_bridge: error: cannot subscribe to %s\n", tvo_node_channel_name(channel));
                close(b.socket_fd);
                return 1;
            }
        }
    }

    uint8_t chunk[BRIDGE_READ_CHUNK];
    int link_open = 1;
    while (!g_stop_signal && link_open && !b.failed) {
        struct pollfd fds[2] = {{lcm_get_fileno(b.lcm), POLLIN, 0}, {b.socket_fd, POLLIN, 0}};
        const int ready = poll(fds, 2, BRIDGE_POLL_MS);
        if (ready < 0) {
            if (errno == EINTR) {
                continue;
            }
            fprintf(stderr, "tvo_pil_bridge: error: poll: %s\n", strerror(errno));
            b.failed = 1;
            break;
        }
        if (fds[1].revents & (POLLIN | POLLHUP | POLLERR)) {
            const ssize_t n = read(b.socket_fd, chunk, sizeof(chunk));
            if (n > 0) {
                from_target(&b, chunk, (size_t)n);
            } else if (n == 0 || errno != EINTR) {
                link_open = 0; /* the target's program ended and QEMU closed the socket */
            }
        }
        session_timer(&b);
        /* Everything LCM has queued, up to a bound, before the serial side is looked at again. */
        for (int handled = 0; (fds[0].revents & POLLIN) && handled < BRIDGE_DRAIN_MAX; ++handled) {
            if (lcm_handle(b.lcm) != 0) {
                break;
            }
            struct pollfd more = {lcm_get_fileno(b.lcm), POLLIN, 0};
            if (poll(&more, 1, 0) <= 0) {
                break;
            }
        }
    }
    fprintf(stderr,
            "tvo_pil_bridge: frames to_target=%lu session_repeats_held=%lu session_repeats_dropped=%lu "
            "samples_to_target=%lu samples_held=%lu samples_replaced=%lu samples_corrupted=%lu "
            "from_target_ok=%lu from_target_dropped=%lu commands_from_target=%lu commands_corrupted=%lu\n",
            b.frames_to_target, b.repeats_held, b.repeats_dropped, b.samples_to_target, b.samples_held,
            b.samples_replaced, b.samples_corrupted,
            b.frames_from_target,
            (unsigned long)b.decoder.frames_dropped, b.commands_from_target, b.commands_corrupted);
    lcm_destroy(b.lcm);
    close(b.socket_fd);
    return b.failed ? 1 : 0;
}
