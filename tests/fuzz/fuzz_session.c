/*
 * Session decoding and tvo_problem_init through the node: a reference session runs, then a session
 * message of a new id whose encoded bytes are the variant's START XOR-ed with the input. One that
 * names another boot of the node (node_boot_id, robot_count) must be dropped unanswered, counted, and
 * leave everything as it was; one that names this boot is acknowledged exactly once. A refused START
 * must leave the running session byte for byte as it was (and still answering); an accepted one must
 * steer resting robots with commands within the new session's own limits.
 */
#include "fuzz_support.h"

#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

static tvo_node_t node;
static tvo_lcm_session_t reference;
static tvo_lcm_session_t fuzzed;
static tvo_lcm_session_ack_t ack;
static tvo_lcm_command_header_t header;
static const tvo_lcm_session_t *limits;
static int acks;
static int commands;
static uint8_t buffer[16384];
static uint8_t start[16384];

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (channel == TVO_NODE_CH_SESSION_ACK) {
        if (tvo_lcm_session_ack_t_decode(data, 0, (int)length, &ack) != (int)length) {
            fuzz_fail("ack does not decode");
        }
        acks++;
    } else if (fuzz_check_published_command(channel, data, length, limits, &header)) {
        commands++;
    }
}

/* Every robot of session `s` at rest at its start, for period `n` (a chain's on its own channel). */
static void measure(const tvo_lcm_session_t *s, int64_t n, int64_t now)
{
    const int64_t utime = s->epoch_utime + (n + 1) * s->period_us - s->delay_us;
    const int32_t robots = s->robot_count < 1 ? 1 : (s->robot_count > TVO_MAX_ROBOTS ? TVO_MAX_ROBOTS : s->robot_count);
    for (int32_t r = 0; r < robots; ++r) {
        int length = 0;
        int channel = TVO_NODE_CH_SAMPLE;
        if (s->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN) {
            tvo_lcm_chain_sample_t m;
            memset(&m, 0, sizeof(m));
            m.header.session_id = s->session_id;
            m.header.sequence = (int32_t)n;
            m.header.utime = utime;
            m.header.robot = (int8_t)r;
            m.position_m[0] = -1.0 + 3.0 * r;
            m.position_m[1] = -2.0;
            m.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
            length = tvo_lcm_chain_sample_t_encode(buffer, 0, sizeof(buffer), &m);
            channel = TVO_NODE_CH_CHAIN_SAMPLE;
        } else {
            tvo_lcm_unicycle_sample_t m;
            memset(&m, 0, sizeof(m));
            m.header.session_id = s->session_id;
            m.header.sequence = (int32_t)n;
            m.header.utime = utime;
            m.header.robot = (int8_t)r;
            m.position_m[0] = -1.0 + 3.0 * r;
            m.position_m[1] = -2.0;
            m.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
            length = tvo_lcm_unicycle_sample_t_encode(buffer, 0, sizeof(buffer), &m);
        }
        tvo_node_handle(&node, channel, buffer, (uint32_t)length, now);
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    if (tvo_node_init(&node, -1, FUZZ_BOOT, publish, NULL) != 0) {
        fuzz_fail("node init");
    }
    fuzz_session(&reference, 0);
    limits = &reference;
    int length = tvo_lcm_session_t_encode(buffer, 0, sizeof(buffer), &reference);
    tvo_node_handle(&node, TVO_NODE_CH_SESSION, buffer, (uint32_t)length, FUZZ_EPOCH_US);
    measure(&reference, 0, FUZZ_EPOCH_US);

    fuzz_session(&fuzzed, data[0]);
    fuzzed.session_id = FUZZ_SESSION_ID + 1;
    length = tvo_lcm_session_t_encode(start, 0, sizeof(start), &fuzzed);
    for (size_t i = 1; i < size && (int)(8 + i - 1) < length; ++i) {
        start[8 + i - 1] ^= data[i]; /* keep the fingerprint: the fields take the fuzz */
    }
    if (tvo_lcm_session_t_decode(start, 0, length, &fuzzed) < 0) {
        return 0;
    }
    static tvo_node_session_t before;
    memcpy(&before, tvo_node_session(&node), sizeof(before));
    const tvo_lcm_node_counters_t counters_before = node.counters;
    const int acks_before = acks;
    const int commands_before = commands;
    tvo_node_handle(&node, TVO_NODE_CH_SESSION, start, (uint32_t)length, FUZZ_EPOCH_US + 20000);
    const tvo_node_session_t *running = tvo_node_session(&node);
    if (node.last_event == TVO_NODE_EVENT_WRONG_BOOT) {
        /* It names no boot of this node (a boot id or the robot count fuzzed): dropped unanswered. */
        if (acks != acks_before || commands != commands_before || running == NULL ||
            memcmp(&before, running, sizeof(before)) != 0 || node.counters.wrong_boot != counters_before.wrong_boot + 1) {
            fuzz_fail("a session message naming another boot was answered, changed the session or was not counted");
        }
        return 0;
    }
    if (acks != acks_before + 1) {
        fuzz_fail("a session message naming this boot was not acknowledged exactly once");
    }
    if (ack.boot_id != FUZZ_BOOT || ack.own_robot != -1) {
        fuzz_fail("an ack that does not name the node");
    }
    if (ack.status != 0) {
        if (running == NULL || memcmp(&before, running, sizeof(before)) != 0) {
            fuzz_fail("a refused START changed the running session");
        }
        if (ack.running_session_id != FUZZ_SESSION_ID) {
            fuzz_fail("a refused START's ack does not name the session still running");
        }
        const int commands_now = commands;
        measure(&reference, 1, FUZZ_EPOCH_US + 20000);
        if (commands == commands_now || header.status != 0) {
            fuzz_fail("the running session stopped answering after a refused START");
        }
        return 0;
    }
    if (fuzzed.action == TVO_LCM_SESSION_T_ACTION_START && fuzzed.session_id != FUZZ_SESSION_ID) {
        if (running == NULL || running->session_id != fuzzed.session_id) {
            fuzz_fail("an accepted START is not the running session");
        }
        limits = &fuzzed;
        for (int64_t n = 0; n < 30; ++n) {
            const int64_t now = FUZZ_EPOCH_US + 20000 + n * 1000;
            measure(&fuzzed, n, now);
            (void)tvo_node_poll(&node, now);
        }
    }
    return 0;
}
