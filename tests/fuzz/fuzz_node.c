/*
 * The node's raw-bytes entry: a valid session (variant from the first input byte: one robot or two,
 * either plant, either clock), then a stream of fuzzed messages on every channel with the node's clock
 * advancing by fuzzed steps. Invariants after every message and timer call: each command finite and
 * within its limits, a safe stop all zero, status 0 only on a computed command, every announcement
 * decodes and carries the node's counters, and a sample refused (by the node's checks or the core's)
 * changes nothing of the running session but the schedule's votes and refusal streak (byte for byte:
 * controller, problem, schedule, what it gathered of its robots).
 * Record format after the variant byte: channel (1 byte), length (2 bytes LE), clock step
 * (1 byte, x 500 us), then `length` bytes of message.
 */
#include "fuzz_support.h"

static tvo_node_t node;
static tvo_lcm_session_t session;
static tvo_lcm_command_header_t last_header;
static int commands;
static uint8_t buffer[16384];

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (fuzz_check_published_command(channel, data, length, &session, &last_header)) {
        commands++;
    } else if (channel == TVO_NODE_CH_NODE) {
        tvo_lcm_node_status_t status;
        if (tvo_lcm_node_status_t_decode(data, 0, (int)length, &status) != (int)length ||
            status.boot_id != FUZZ_BOOT || memcmp(&status.counters, &node.counters, sizeof(status.counters)) != 0) {
            fuzz_fail("an announcement that does not decode, or names another boot, or other counters");
        }
    }
}

/* The session without the controller's scratch and what a refusal may leave (votes, streak). */
static void comparable(const tvo_node_session_t *s, tvo_node_session_t *out)
{
    memcpy(out, s, sizeof(*out));
    tvo_edge_controller_clear_scratch(&out->controller);
    out->schedule.votes = 0u;
    out->schedule.vote_value = 0;
    if (out->schedule.ops->clock_source == TVO_LCM_SESSION_T_CLOCK_PLANT) {
        out->controller.ops->clock(&out->controller)->refusals_in_row = 0u; /* the core counts refusals */
        out->schedule.clock.plant.vote_period = 0; /* part of the vote */
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
    fuzz_session(&session, data[0]);
    int64_t now = 5000000;
    const int n = tvo_lcm_session_t_encode(buffer, 0, sizeof(buffer), &session);
    tvo_node_handle(&node, TVO_NODE_CH_SESSION, buffer, (uint32_t)n, now);
    if (tvo_node_session(&node) == NULL) {
        fuzz_fail("the reference session was refused");
    }
    size_t i = 1;
    while (i + 4 <= size) {
        const int channel = 1 + data[i] % TVO_NODE_CH_LAST;
        size_t length = (size_t)data[i + 1] | ((size_t)data[i + 2] << 8);
        now += 500 * (int64_t)data[i + 3];
        i += 4;
        if (length > size - i) {
            length = size - i;
        }
        const tvo_node_session_t *s = tvo_node_session(&node);
        static tvo_node_session_t before;
        static tvo_node_session_t after;
        const int had_session = s != NULL;
        const uint8_t running_before = node.running;
        if (had_session) {
            comparable(s, &before);
        }
        const int commands_before = commands;
        tvo_node_handle(&node, channel, data + i, (uint32_t)length, now);
        s = tvo_node_session(&node);
        const int sample = channel == TVO_NODE_CH_SAMPLE || channel == TVO_NODE_CH_CHAIN_SAMPLE;
        if (sample && had_session && s != NULL && node.running == running_before && commands > commands_before &&
            fuzz_refused_before_step(last_header.status)) {
            comparable(s, &after);
            if (memcmp(&before, &after, sizeof(before)) != 0) {
                fuzz_fail("a refused sample changed the session");
            }
        }
        (void)tvo_node_poll(&node, now);
        i += length;
    }
    return 0;
}
