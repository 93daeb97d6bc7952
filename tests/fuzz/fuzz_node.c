/*
 * The node's raw-bytes entry: a valid session (variant from the first input byte), then a stream of
 * fuzzed messages on every channel with the node's clock advancing by fuzzed steps. Invariants after
 * every message and timer call: each command finite and within its limits, a safe stop all zero,
 * status 0 only on a computed command, and a measurement refused before the step changes nothing in
 * the session's controller and problem.
 * Record format after the variant byte: channel (1 byte), length (2 bytes LE), clock step
 * (1 byte, x 500 us), then `length` bytes of message.
 */
#include "fuzz_support.h"

static tvo_node_t node;
static tvo_lcm_session_t session;
static tvo_lcm_command_t last_command;
static int commands;
static uint8_t buffer[8192];

static void publish(void *context, int channel, const uint8_t *data, uint32_t length)
{
    (void)context;
    if (channel == TVO_NODE_CH_COMMAND) {
        if (tvo_lcm_command_t_decode(data, 0, (int)length, &last_command) < 0) {
            fuzz_fail("the node published a command that does not decode");
        }
        fuzz_check_command(&last_command, &session);
        commands++;
    }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1) {
        return 0;
    }
    tvo_node_init(&node, publish, NULL);
    fuzz_session(&session, data[0]);
    int64_t now = 5000000;
    const int n = tvo_lcm_session_t_encode(buffer, 0, sizeof(buffer), &session);
    tvo_node_handle(&node, TVO_NODE_CH_SESSION, buffer, (uint32_t)n, now);
    if (tvo_node_session(&node) == NULL) {
        fuzz_fail("the reference session was refused");
    }
    size_t i = 1;
    while (i + 4 <= size) {
        const int channel = 1 + data[i] % 6;
        size_t length = (size_t)data[i + 1] | ((size_t)data[i + 2] << 8);
        now += 500 * (int64_t)data[i + 3];
        i += 4;
        if (length > size - i) {
            length = size - i;
        }
        const tvo_node_session_t *s = tvo_node_session(&node);
        static tvo_edge_controller_t controller_before;
        static tvo_problem_t problem_before;
        const int had_session = s != NULL;
        if (had_session) {
            controller_before = s->controller;
            tvo_edge_controller_clear_scratch(&controller_before);
            problem_before = s->problem;
        }
        const int commands_before = commands;
        tvo_node_handle(&node, channel, data + i, (uint32_t)length, now);
        s = tvo_node_session(&node);
        static tvo_edge_controller_t controller_after; /* its scratch cleared, as before's */
        if (s != NULL) {
            controller_after = s->controller;
            tvo_edge_controller_clear_scratch(&controller_after);
        }
        if (channel == TVO_NODE_CH_MEASUREMENT && had_session && s != NULL && commands == commands_before + 1 &&
            fuzz_refused_before_step(last_command.status) &&
            (memcmp(&controller_before, &controller_after, sizeof(controller_before)) != 0 ||
             memcmp(&problem_before, &s->problem, sizeof(problem_before)) != 0)) {
            fuzz_fail("a refused measurement changed the session");
        }
        (void)tvo_node_poll(&node, now);
        i += length;
    }
    return 0;
}
