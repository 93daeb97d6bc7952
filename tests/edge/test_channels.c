/*
 * The protocol's one table (firmware/edge/channels.c): channel names and numbers, which a node takes,
 * each channel's fixed message size against the generated code's encoded size, the joint digest
 * against a value computed apart, and the names of every wire code.
 */
#include "edge_fixture.h"

#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static void test_names_and_numbers_are_one_table(void)
{
    static const struct {
        int channel;
        const char *name;
        int input;
    } expected[] = {
        {1, "TVO_SESSION", 1},  {2, "TVO_SESSION_ACK", 0}, {3, "TVO_SAMPLE", 1},
        {4, "TVO_TARGET", 1},   {5, "TVO_COMMAND", 0},     {6, "TVO_TELEMETRY", 0},
        {7, "TVO_NODE", 0},     {8, "TVO_CHAIN_SAMPLE", 1}, {9, "TVO_CHAIN_COMMAND", 0},
    };
    TEST_ASSERT_EQUAL_INT(TVO_NODE_CH_LAST - TVO_NODE_CH_FIRST + 1, (int)(sizeof(expected) / sizeof(expected[0])));
    for (size_t i = 0; i < sizeof(expected) / sizeof(expected[0]); ++i) {
        TEST_ASSERT_EQUAL_STRING(expected[i].name, tvo_node_channel_name(expected[i].channel));
        TEST_ASSERT_EQUAL_INT(expected[i].channel, tvo_node_channel_of(expected[i].name));
        TEST_ASSERT_EQUAL_INT(expected[i].input, tvo_node_channel_is_input(expected[i].channel));
    }
    const int outside[] = {INT32_MIN, -1, 0, TVO_NODE_CH_LAST + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(outside) / sizeof(outside[0]); ++i) {
        TEST_ASSERT_NULL(tvo_node_channel_name(outside[i]));
        TEST_ASSERT_EQUAL_INT(0, tvo_node_channel_is_input(outside[i]));
        TEST_ASSERT_EQUAL_UINT32(0u, tvo_node_channel_message_bytes(outside[i]));
    }
    TEST_ASSERT_EQUAL_INT(0, tvo_node_channel_of(NULL));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_channel_of(""));
    TEST_ASSERT_EQUAL_INT(0, tvo_node_channel_of("TVO_MEASUREMENT")); /* v2's: gone */
    TEST_ASSERT_EQUAL_INT(0, tvo_node_channel_of("TVO_SAMPLE_R0"));
}

static tvo_lcm_session_t session; /* 11 kB: not on the stack */

/* Every channel's size is the generated code's encoded size of its type (fixed arrays only, so any
 * value of the type has it). */
static void test_each_channels_message_size_is_its_types_encoded_size(void)
{
    tvo_lcm_session_ack_t ack;
    tvo_lcm_unicycle_sample_t sample;
    tvo_lcm_target_t target;
    tvo_lcm_unicycle_command_t command;
    tvo_lcm_telemetry_t telemetry;
    tvo_lcm_node_status_t status;
    tvo_lcm_chain_sample_t chain_sample;
    tvo_lcm_chain_command_t chain_command;
    memset(&session, 0, sizeof(session));
    memset(&ack, 0, sizeof(ack));
    memset(&sample, 0, sizeof(sample));
    memset(&target, 0, sizeof(target));
    memset(&command, 0, sizeof(command));
    memset(&telemetry, 0, sizeof(telemetry));
    memset(&status, 0, sizeof(status));
    memset(&chain_sample, 0, sizeof(chain_sample));
    memset(&chain_command, 0, sizeof(chain_command));
    const int sizes[TVO_NODE_CH_LAST + 1] = {
        [TVO_NODE_CH_SESSION] = tvo_lcm_session_t_encoded_size(&session),
        [TVO_NODE_CH_SESSION_ACK] = tvo_lcm_session_ack_t_encoded_size(&ack),
        [TVO_NODE_CH_SAMPLE] = tvo_lcm_unicycle_sample_t_encoded_size(&sample),
        [TVO_NODE_CH_TARGET] = tvo_lcm_target_t_encoded_size(&target),
        [TVO_NODE_CH_COMMAND] = tvo_lcm_unicycle_command_t_encoded_size(&command),
        [TVO_NODE_CH_TELEMETRY] = tvo_lcm_telemetry_t_encoded_size(&telemetry),
        [TVO_NODE_CH_NODE] = tvo_lcm_node_status_t_encoded_size(&status),
        [TVO_NODE_CH_CHAIN_SAMPLE] = tvo_lcm_chain_sample_t_encoded_size(&chain_sample),
        [TVO_NODE_CH_CHAIN_COMMAND] = tvo_lcm_chain_command_t_encoded_size(&chain_command),
    };
    uint32_t largest = 0u;
    for (int channel = TVO_NODE_CH_FIRST; channel <= TVO_NODE_CH_LAST; ++channel) {
        TEST_ASSERT_TRUE(sizes[channel] > 8);
        TEST_ASSERT_EQUAL_UINT32_MESSAGE((uint32_t)sizes[channel], tvo_node_channel_message_bytes(channel),
                                         tvo_node_channel_name(channel));
        largest = (uint32_t)sizes[channel] > largest ? (uint32_t)sizes[channel] : largest;
        /* Only the node's outputs go through its encode buffer. */
        if (!tvo_node_channel_is_input(channel)) {
            TEST_ASSERT_TRUE(sizes[channel] <= TVO_NODE_BUFFER_BYTES);
        }
    }
    TEST_ASSERT_EQUAL_UINT32(TVO_NODE_LARGEST_MESSAGE_BYTES, largest);
    TEST_ASSERT_EQUAL_INT(0, tvo_node_check_buffer());
}

static void test_the_joint_digest_is_fnv1a_of_the_rows_bits(void)
{
    /* FNV-1a 64 over the 16 bytes of (1.0, -0.5), least significant byte first (computed apart). */
    const double speed[2] = {1.0, 7.0};
    double turn[2] = {-0.5, 3.0};
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, 1) == 0x2c18cbea19d5b735ull);
    turn[0] = nextafter(-0.5, 0.0);
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, 1) != 0x2c18cbea19d5b735ull);
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, 0) == 0xcbf29ce484222325ull); /* the offset basis */
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, 2) != tvo_joint_digest(speed, turn, 1));
    TEST_ASSERT_TRUE(tvo_joint_digest(NULL, turn, 1) == 0u);
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, NULL, 1) == 0u);
    TEST_ASSERT_TRUE(tvo_joint_digest(speed, turn, -1) == 0u);
}

/* Every code the wire defines has a name, and none is the unknown one. */
static void test_every_wire_code_has_a_name(void)
{
    const char *unknown = tvo_protocol_status_str(-1);
    for (int32_t status = TVO_LCM_COMMAND_HEADER_T_STATUS_OK;
         status <= TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT; ++status) {
        TEST_ASSERT_TRUE(strcmp(unknown, tvo_protocol_status_str(status)) != 0);
    }
    TEST_ASSERT_EQUAL_STRING(unknown, tvo_protocol_status_str(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT + 1));
    const char *unknown_param = tvo_protocol_param_str(-1);
    for (int32_t param = TVO_LCM_SESSION_ACK_T_PARAM_NONE; param <= TVO_LCM_SESSION_ACK_T_PARAM_TELEMETRY_EVERY; ++param) {
        TEST_ASSERT_TRUE(strcmp(unknown_param, tvo_protocol_param_str(param)) != 0);
    }
    TEST_ASSERT_EQUAL_STRING(unknown_param, tvo_protocol_param_str(TVO_LCM_SESSION_ACK_T_PARAM_TELEMETRY_EVERY + 1));
    const char *unknown_part = tvo_protocol_part_str(-1);
    for (int32_t part = TVO_LCM_SESSION_ACK_T_PART_NONE; part <= TVO_LCM_SESSION_ACK_T_PART_OFFSETS; ++part) {
        TEST_ASSERT_TRUE(strcmp(unknown_part, tvo_protocol_part_str(part)) != 0);
    }
    /* The node's statuses are read as the wire codes step_codec.c's table sends them as. */
    for (int status = TVO_NODE_OK; status < TVO_NODE_STATUS_COUNT; ++status) {
        const tvo_step_why_t why = {(tvo_node_status_t)status, TVO_OK, TVO_REASON_NONE};
        TEST_ASSERT_TRUE(strcmp(unknown, tvo_protocol_status_str(tvo_step_wire_status(&why))) != 0);
    }
}

/* A wire code that is the core's error or reason reads as the core's own text (one phrase, one place). */
static void test_the_cores_codes_read_as_the_cores_texts(void)
{
    const tvo_status_t errors[] = {TVO_OK, TVO_ERR_NULL, TVO_ERR_NOT_FINITE, TVO_ERR_DIMENSION, TVO_ERR_PARAM,
                                   TVO_ERR_CAPACITY, TVO_ERR_NOT_INITIALIZED, TVO_ERR_NOT_POSITIVE_DEFINITE,
                                   TVO_ERR_NUMERIC};
    for (size_t i = 0; i < sizeof(errors) / sizeof(errors[0]); ++i) {
        const tvo_step_why_t why = {TVO_NODE_OK, errors[i], TVO_REASON_NONE};
        TEST_ASSERT_EQUAL_STRING(tvo_status_str(errors[i]), tvo_protocol_status_str(tvo_step_wire_status(&why)));
    }
    const tvo_reason_t reasons[] = {TVO_REASON_STALE, TVO_REASON_FUTURE_STAMP, TVO_REASON_MISSING_FIELD,
                                    TVO_REASON_TARGET_NOT_READY, TVO_REASON_WATCHDOG,
                                    TVO_REASON_IMPLAUSIBLE_MEASUREMENT};
    for (size_t i = 0; i < sizeof(reasons) / sizeof(reasons[0]); ++i) {
        const tvo_step_why_t why = {TVO_NODE_OK, TVO_OK, reasons[i]};
        TEST_ASSERT_EQUAL_STRING(tvo_reason_str(reasons[i]), tvo_protocol_status_str(tvo_step_wire_status(&why)));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_names_and_numbers_are_one_table);
    RUN_TEST(test_each_channels_message_size_is_its_types_encoded_size);
    RUN_TEST(test_the_joint_digest_is_fnv1a_of_the_rows_bits);
    RUN_TEST(test_every_wire_code_has_a_name);
    RUN_TEST(test_the_cores_codes_read_as_the_cores_texts);
    return UNITY_END();
}
