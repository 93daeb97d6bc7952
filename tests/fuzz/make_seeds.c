/*
 * Writes the seed corpus of each harness into the folder given (tests/fuzz/corpus): genuine
 * traffic of the reference sessions, so the fuzzer starts from messages that decode and steps
 * that run. Run by hand after a change of the wire format: fuzz_make_seeds tests/fuzz/corpus
 */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "fuzz_support.h"
#include "serial_frame.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

static uint8_t out[262144];
static size_t out_length;

static void put(const void *data, size_t length)
{
    if (out_length + length <= sizeof(out)) {
        memcpy(out + out_length, data, length);
        out_length += length;
    }
}

static int save(const char *dir, const char *harness, const char *name)
{
    char path[512];
    snprintf(path, sizeof(path), "%s/%s/%s", dir, harness, name);
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        fprintf(stderr, "fuzz_make_seeds: cannot write %s (create the folder first)\n", path);
        return 1;
    }
    fwrite(out, 1, out_length, f);
    fclose(f);
    out_length = 0;
    return 0;
}

/* A node record: channel selector, length, clock step (x 500 us), message. */
static void node_record(int channel, const uint8_t *message, int length, uint8_t clock_step)
{
    const uint8_t header[4] = {(uint8_t)(channel - 1), (uint8_t)length, (uint8_t)(length >> 8), clock_step};
    put(header, sizeof(header));
    put(message, (size_t)length);
}

/* The reference session's genuine sample n of robot r: on schedule, numbered by period, every field
 * measured (a chain's on its own message). Returns the encoded length in `message`, *channel its channel. */
static int genuine_sample(const tvo_lcm_session_t *s, int n, int r, uint8_t *message, size_t size, int *channel)
{
    const int64_t utime = s->epoch_utime + (n + 1) * s->period_us - s->delay_us;
    if (s->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN) {
        tvo_lcm_chain_sample_t m;
        memset(&m, 0, sizeof(m));
        m.header.session_id = s->session_id;
        m.header.sequence = n;
        m.header.utime = utime;
        m.header.robot = (int8_t)r;
        m.position_m[0] = -1.0 + 3.0 * r + 0.01 * n;
        m.position_m[1] = -2.0;
        m.output_rate_mps[0] = 0.01f;
        m.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
        *channel = TVO_NODE_CH_CHAIN_SAMPLE;
        return tvo_lcm_chain_sample_t_encode(message, 0, (int)size, &m);
    }
    tvo_lcm_unicycle_sample_t m;
    memset(&m, 0, sizeof(m));
    m.header.session_id = s->session_id;
    m.header.sequence = n;
    m.header.utime = utime;
    m.header.robot = (int8_t)r;
    m.position_m[0] = -1.0 + 3.0 * r + 0.01 * n;
    m.position_m[1] = -2.0;
    m.speed_mps = 0.01f * (float)n;
    m.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    *channel = TVO_NODE_CH_SAMPLE;
    return tvo_lcm_unicycle_sample_t_encode(message, 0, (int)size, &m);
}

static int node_seed(const char *dir, uint8_t variant, const char *name)
{
    static uint8_t message[16384];
    tvo_lcm_session_t s;
    fuzz_session(&s, variant);
    put(&variant, 1);
    for (int n = 0; n < 40; ++n) {
        for (int r = 0; r < s.robot_count; ++r) { /* in robot order: the last one steps the period */
            int channel = 0;
            const int length = genuine_sample(&s, n, r, message, sizeof(message), &channel);
            node_record(channel, message, length, r == 0 ? 20 : 0);
        }
        if (n == 20) {
            tvo_lcm_session_t stop = s;
            stop.action = TVO_LCM_SESSION_T_ACTION_STOP;
            stop.session_id = 7; /* another session's STOP: acked NO_SESSION */
            const int stop_length = tvo_lcm_session_t_encode(message, 0, sizeof(message), &stop);
            node_record(TVO_NODE_CH_SESSION, message, stop_length, 0);
            stop.session_id = s.session_id;
            stop.node_boot_id[0] = FUZZ_BOOT + 1; /* the running id's STOP naming another boot: dropped */
            const int other_boot = tvo_lcm_session_t_encode(message, 0, sizeof(message), &stop);
            node_record(TVO_NODE_CH_SESSION, message, other_boot, 0);
        }
    }
    return save(dir, "node", name);
}

/* fuzz_auth's seed: the node seed's samples as records the harness signs (mode 1), with one raw,
 * one altered and one replayed frame among them. */
static int auth_seed(const char *dir, uint8_t variant, const char *name)
{
    static uint8_t message[16384];
    tvo_lcm_session_t s;
    fuzz_session(&s, variant);
    put(&variant, 1);
    for (int n = 0; n < 30; ++n) {
        int channel = 0;
        const int length = genuine_sample(&s, n, 0, message, sizeof(message), &channel);
        const uint8_t mode = (n == 10) ? 0u : (n == 15) ? 2u : (n == 20) ? 3u : 1u;
        const uint8_t header[5] = {mode, (uint8_t)(channel - 1), (uint8_t)length, (uint8_t)(length >> 8), 20};
        put(header, sizeof(header));
        if (mode == 2u) {
            const uint8_t flip = 77;
            put(&flip, 1);
        }
        put(message, (size_t)length);
    }
    return save(dir, "auth", name);
}

/* fuzz_fleet's seed: for each period, every robot's sample in robot order (the last steps the period),
 * as kind-0 records. */
static int fleet_seed(const char *dir, uint8_t variant, const char *name)
{
    const int robots = 2 + variant % 7; /* as fuzz_fleet.c reads the variant byte (the fleet build: 8) */
    put(&variant, 1);
    for (int n = 0; n < 30; ++n) {
        for (int r = 0; r < robots; ++r) {
            const int16_t x = (int16_t)(3000 * r + 3000 - 10 * n), y = (int16_t)(20 * n), heading = 1571, speed = 0;
            const uint8_t payload[11] = {(uint8_t)r, (uint8_t)(r == 0 && n > 0 ? 1 : 0),
                                         (uint8_t)x, (uint8_t)(x >> 8), (uint8_t)y, (uint8_t)(y >> 8),
                                         (uint8_t)heading, (uint8_t)(heading >> 8), (uint8_t)speed, (uint8_t)(speed >> 8), 3};
            const uint8_t header[4] = {0, sizeof(payload), 0, (uint8_t)(r == 0 ? 20 : 0)};
            put(header, sizeof(header));
            put(payload, sizeof(payload));
        }
    }
    return save(dir, "fleet", name);
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: fuzz_make_seeds CORPUS_DIR (with subfolders node, session, frame, controller, auth, fleet)\n");
        return 2;
    }
    const char *dir = argv[1];
    int failed = 0;
    failed |= node_seed(dir, 0, "plant_clock_unicycle");
    failed |= node_seed(dir, 1, "node_clock_unicycle");
    failed |= node_seed(dir, 2, "plant_clock_chain");
    failed |= node_seed(dir, 4 | 8 | 16, "position_only_two_robots_distance");
    failed |= node_seed(dir, 32, "obstacle");
    failed |= auth_seed(dir, 0, "signed_plant_clock");
    failed |= auth_seed(dir, 1, "signed_node_clock");
    /* The variant byte as fuzz_fleet.c reads it: robots 2 + v % 7, own robot (v >> 3) % (robots + 1) - 1. */
    failed |= fleet_seed(dir, 20, "eight_robots_ring_position_only_node_of_robot_1");
    failed |= fleet_seed(dir, 48, "eight_robots_ring_obstacle_node_of_robot_5");
    failed |= fleet_seed(dir, 13, "eight_robots_node_clock_node_of_robot_0");
    failed |= fleet_seed(dir, 2, "four_robots_node_of_every_robot");
    failed |= fleet_seed(dir, 146, "eight_robots_ring_node_of_every_robot");

    for (uint8_t variant = 0; variant < 64; variant = (uint8_t)(variant + 9)) {
        char name[32];
        snprintf(name, sizeof(name), "variant_%u", (unsigned)variant);
        put(&variant, 1); /* the rest empty: the variant's START unchanged, accepted */
        failed |= save(dir, "session", name);
    }

    static uint8_t frame[TVO_FRAME_MAX_ENCODED];
    size_t frame_length = 0;
    const uint8_t body[] = {1, 2, 3, 0, 0, 255, 254, 0, 9};
    if (tvo_frame_encode(TVO_NODE_CH_SAMPLE, body, sizeof(body), frame, sizeof(frame), &frame_length) == TVO_FRAME_OK) {
        put(frame, frame_length);
        put(frame, frame_length);
        failed |= save(dir, "frame", "two_frames");
    }
    /* A frame with the zero-run stage: mostly zeros, as a session_t is (fixed arrays for 32 robots). */
    static uint8_t sparse[600];
    for (size_t i = 0; i < sizeof(sparse); i += 97u) {
        sparse[i] = (uint8_t)(i | 1u);
    }
    if (tvo_frame_encode(TVO_NODE_CH_SESSION, sparse, sizeof(sparse), frame, sizeof(frame), &frame_length) == TVO_FRAME_OK &&
        (frame[1] & TVO_FRAME_ZERO_RUNS) != 0u) {
        put(frame, frame_length);
        failed |= save(dir, "frame", "zero_runs");
    } else {
        failed = 1; /* the seed must exercise the zero-run stage */
    }

    const uint8_t mode = 0;
    put(&mode, 1);
    for (int n = 0; n < 40; ++n) {
        const uint8_t timing[5] = {0x10, 0x27, 0x88, 0x13, 3}; /* +10000 ticks, apply +5000, pose + speed */
        const float pose[4] = {-1.0f + 0.01f * (float)n, -2.0f, 0.0f, 0.01f * (float)n};
        put(timing, sizeof(timing));
        put(pose, sizeof(pose));
    }
    failed |= save(dir, "controller", "steady");
    return failed;
}
