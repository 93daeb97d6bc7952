/*
 * Session decoding and tvo_problem_init through the node: a reference session runs, then a START of
 * a new id whose encoded bytes are the variant's START XOR-ed with the input. A refused START must
 * leave the running session byte for byte as it was (and still answering); an accepted one must
 * steer a resting robot with commands within the new session's own limits.
 */
#include "fuzz_support.h"

static tvo_node_t node;
static tvo_lcm_session_t reference;
static tvo_lcm_session_t fuzzed;
static tvo_lcm_session_ack_t ack;
static tvo_lcm_command_t command;
static const tvo_lcm_session_t *limits;
static int acks;
static uint8_t buffer[8192];
static uint8_t start[8192];

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (channel == TVO_NODE_CH_SESSION_ACK) {
        if (tvo_lcm_session_ack_t_decode(data, 0, (int)length, &ack) < 0) {
            fuzz_fail("ack does not decode");
        }
        acks++;
    } else if (channel == TVO_NODE_CH_COMMAND) {
        if (tvo_lcm_command_t_decode(data, 0, (int)length, &command) < 0) {
            fuzz_fail("command does not decode");
        }
        fuzz_check_command(&command, limits);
    }
}

/* One measurement of robots at rest at their start, for period `n` of session `s`. */
static void measure(const tvo_lcm_session_t *s, int64_t n, int64_t now)
{
    tvo_lcm_measurement_t m;
    memset(&m, 0, sizeof(m));
    m.session_id = s->session_id;
    m.sequence = n;
    m.utime = s->epoch_utime + (n + 1) * s->period_us - s->delay_us;
    m.robot_count = s->robot_count;
    for (int r = 0; r < 4; ++r) {
        m.position_m[r][0] = -1.0 + 3.0 * r;
        m.position_m[r][1] = -2.0;
    }
    m.heading_valid = 1;
    m.speed_valid = 1;
    m.derivatives_valid = 1;
    const int length = tvo_lcm_measurement_t_encode(buffer, 0, sizeof(buffer), &m);
    tvo_node_handle(&node, TVO_NODE_CH_MEASUREMENT, buffer, (uint32_t)length, now);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    tvo_node_init(&node, publish, NULL);
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
    before = *tvo_node_session(&node);
    const int acks_before = acks;
    tvo_node_handle(&node, TVO_NODE_CH_SESSION, start, (uint32_t)length, FUZZ_EPOCH_US + 20000);
    if (acks != acks_before + 1) {
        fuzz_fail("a START was not acknowledged exactly once");
    }
    const tvo_node_session_t *running = tvo_node_session(&node);
    if (ack.status != 0) {
        if (running == NULL || memcmp(&before, running, sizeof(before)) != 0) {
            fuzz_fail("a refused START changed the running session");
        }
        if (ack.running_session_id != FUZZ_SESSION_ID) {
            fuzz_fail("a refused START's ack does not name the session still running");
        }
        measure(&reference, 1, FUZZ_EPOCH_US + 20000);
        if (command.status != 0) {
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
