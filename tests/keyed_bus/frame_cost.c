/*
 * keyed_bus_frame_cost: what a forged frame costs a keyed node on this host (tools/bench part 8), each
 * kind straight into the node's link (tvo_auth_link_receive; no LCM, no socket): a sample with a forged
 * tag (a verify), from an unknown sender id (the sender table searched, then a verify), cut short (a
 * length check), with another type's fingerprint (a comparison), a replay of a genuine sample (a
 * counter comparison, no tag). The node runs a session, as under a flood. Each kind: BATCHES batches of
 * FRAMES frames on CLOCK_MONOTONIC, the fastest batch's mean (the least disturbed by other work on a
 * shared machine; informational, machine and load dependent). Every frame must be dropped and counted
 * as its kind, or the program fails. Prints "FRAME_COST <kind> ns <ns per frame>", then "FRAME_COST_DONE".
 */
#define _POSIX_C_SOURCE 200809L

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "auth_link.h"

#define FRAMES 20000u
#define BATCHES 5u
#define BOOT_ID 9

static tvo_node_t node;
static tvo_auth_link_t link;
static tvo_auth_t plant;
static uint8_t frame[TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES];
static uint8_t genuine[TVO_NODE_LARGEST_MESSAGE_BYTES + TVO_AUTH_TRAILER_BYTES];
static uint8_t frames[FRAMES][128];
static uint32_t lengths[FRAMES];
static const uint8_t key[TVO_AUTH_KEY_BYTES] = {3, 1, 4, 1, 5, 9, 2, 6, 5, 3, 5, 8, 9, 7, 9, 3,
                                                2, 3, 8, 4, 6, 2, 6, 4, 3, 3, 8, 3, 2, 7, 9, 5};

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    (void)channel;
    (void)data;
    (void)length;
}

static void fail(const char *what)
{
    fprintf(stderr, "keyed_bus_frame_cost: %s\n", what);
    exit(1);
}

static double now_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return 1e9 * (double)ts.tv_sec + (double)ts.tv_nsec;
}

static uint32_t signed_frame(uint8_t *out, int channel, int length)
{
    size_t signed_length = 0u;
    if (length <= 0 || tvo_auth_sign(&plant, tvo_node_channel_name(channel), out, (size_t)length,
                                     sizeof(frame), &signed_length) != TVO_AUTH_OK) {
        fail("signing failed");
    }
    return (uint32_t)signed_length;
}

typedef enum { KIND_FORGED_TAG, KIND_UNKNOWN_SENDER, KIND_SHORT, KIND_FINGERPRINT, KIND_REPLAY, KIND_COUNT } kind_t;
static const char *const kind_names[KIND_COUNT] = {"forged_tag", "unknown_sender", "cut_short", "other_fingerprint",
                                                   "replay"};

/* The frame of kind k, number i, in `frame`; its length. */
static uint32_t make(kind_t k, uint32_t i, uint32_t genuine_length)
{
    memcpy(frame, genuine, genuine_length);
    uint8_t *trailer = frame + genuine_length - TVO_AUTH_TRAILER_BYTES;
    switch (k) {
    case KIND_FORGED_TAG:
    case KIND_UNKNOWN_SENDER: {
        const uint64_t counter = (UINT64_C(1) << 62) + i;
        const uint32_t sender = (k == KIND_UNKNOWN_SENDER) ? 0x10000u + i : TVO_AUTH_SENDER_PLANT;
        for (unsigned b = 0u; b < 4u; ++b) {
            trailer[b] = (uint8_t)(sender >> (24u - 8u * b));
        }
        for (unsigned b = 0u; b < 8u; ++b) {
            trailer[4u + b] = (uint8_t)(counter >> (56u - 8u * b));
        }
        trailer[12] ^= (uint8_t)(1u + i);
        return genuine_length;
    }
    case KIND_SHORT: return genuine_length - 1u;
    case KIND_FINGERPRINT: frame[0] ^= 0x5au; return genuine_length;
    case KIND_REPLAY:
    case KIND_COUNT:
    default: return genuine_length;
    }
}

int main(void)
{
    if (tvo_auth_init(&plant, key, TVO_AUTH_SENDER_PLANT, 1000u) != TVO_AUTH_OK ||
        tvo_auth_link_init(&link, key, TVO_AUTH_SENDER_NODE, BOOT_ID, publish, NULL) != TVO_AUTH_OK ||
        tvo_node_init(&node, -1, BOOT_ID, tvo_auth_link_publish, &link) != 0) {
        fail("set-up");
    }
    static tvo_lcm_session_t start;
    (void)tvo_protocol_default_start(&start, 1);
    start.utime = 1000000;
    start.session_id = 5;
    start.node_boot_id[0] = BOOT_ID;
    start.epoch_utime = 1100000;
    start.omega_max_radps = 6.0;
    start.speed_max_mps = 2.0;
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_CIRCLE;
    start.robot[0].target.semi_axis_m[0] = 1.0;
    start.robot[0].target.omega_radps = 0.5;
    uint32_t length = signed_frame(frame, TVO_NODE_CH_SESSION, tvo_lcm_session_t_encode(frame, 0, (int)sizeof(frame), &start));
    (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SESSION, frame, length, 1000000);
    if (tvo_node_session(&node) == NULL) {
        fail("the START was refused");
    }
    tvo_lcm_unicycle_sample_t sample;
    memset(&sample, 0, sizeof(sample));
    sample.header.utime = 1105000;
    sample.header.session_id = 5;
    sample.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING;
    sample.position_m[0] = 1.2;
    const uint32_t genuine_length = signed_frame(
        genuine, TVO_NODE_CH_SAMPLE, tvo_lcm_unicycle_sample_t_encode(genuine, 0, (int)sizeof(genuine), &sample));
    memcpy(frame, genuine, genuine_length);
    (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SAMPLE, frame, genuine_length, 1105000);
    if (tvo_node_counters(&node)->accepted != 1) {
        fail("the genuine sample was not accepted");
    }
    for (int k = 0; k < KIND_COUNT; ++k) {
        double best = 1e300;
        for (uint32_t batch = 0u; batch < BATCHES; ++batch) {
            for (uint32_t i = 0u; i < FRAMES; ++i) { /* built first: the clock times the node alone */
                lengths[i] = make((kind_t)k, batch * FRAMES + i, genuine_length);
                memcpy(frames[i], frame, lengths[i]);
            }
            const uint32_t drops_before = link.drops;
            const double t0 = now_ns();
            for (uint32_t i = 0u; i < FRAMES; ++i) {
                (void)tvo_auth_link_receive(&link, &node, TVO_NODE_CH_SAMPLE, frames[i], lengths[i], 1105000);
            }
            const double spent = now_ns() - t0;
            if (link.drops - drops_before != FRAMES) {
                fail("a forged frame was not dropped");
            }
            best = spent / FRAMES < best ? spent / FRAMES : best;
        }
        printf("FRAME_COST %s ns %.0f\n", kind_names[k], best);
    }
    const tvo_lcm_node_counters_t *c = tvo_node_counters(&node);
    const int32_t per_kind = (int32_t)(FRAMES * BATCHES);
    if (c->unauthenticated != 2 * per_kind || c->malformed != 2 * per_kind || c->replayed != per_kind ||
        c->accepted != 1) {
        fail("the drops were not counted as their kinds");
    }
    printf("FRAME_COST_DONE\n");
    return 0;
}
