/*
 * Names of statuses, outcomes, reasons and parameters: every code has its own description, and
 * parameter names are the configurations' field names (so a log line points at the field to fix).
 */
#include "test_support.h"

void setUp(void) {}
void tearDown(void) {}

typedef const char *(*describe_fn)(int code);

static const char *status_text(int code) { return tvo_status_str((tvo_status_t)code); }
static const char *outcome_text(int code) { return tvo_outcome_str((tvo_outcome_t)code); }
static const char *reason_text(int code) { return tvo_reason_str((tvo_reason_t)code); }
static const char *param_text(int code) { return tvo_param_str((tvo_param_t)code); }
static const char *chain_param_text(int code) { return tvo_chain_param_str((tvo_chain_param_t)code); }

/* Codes 0 .. count-1 each have a text of their own, none the unknown code's; count itself is unknown. */
static void assert_distinct_descriptions(describe_fn describe, int count)
{
    const char *seen[32];
    TEST_ASSERT_TRUE(count <= 32);
    const char *unknown = describe(999);
    TEST_ASSERT_NOT_NULL(unknown);
    TEST_ASSERT_EQUAL_STRING(unknown, describe(count)); /* the count covers every code */
    for (int s = 0; s < count; ++s) {
        const char *str = describe(s);
        TEST_ASSERT_NOT_NULL(str);
        TEST_ASSERT_TRUE(strlen(str) > 0u);
        TEST_ASSERT_TRUE_MESSAGE(strcmp(str, unknown) != 0, "a defined code prints as unknown");
        for (int p = 0; p < s; ++p) {
            TEST_ASSERT_TRUE_MESSAGE(strcmp(seen[p], str) != 0, "two codes share a description");
        }
        seen[s] = str;
    }
}

static void test_every_status_outcome_reason_and_parameter_has_a_distinct_description(void)
{
    assert_distinct_descriptions(status_text, TVO_STATUS_COUNT);
    assert_distinct_descriptions(outcome_text, TVO_OUTCOME_COUNT);
    assert_distinct_descriptions(reason_text, TVO_REASON_COUNT);
    assert_distinct_descriptions(param_text, TVO_PARAM_COUNT);
    assert_distinct_descriptions(chain_param_text, TVO_CHAIN_PARAM_COUNT);
}

static void test_zero_is_success_applied_and_no_reason(void)
{
    /* Zeroed storage reads as the good case: a returned 0 is TVO_OK, a zeroed command is applied. */
    TEST_ASSERT_EQUAL_INT(0, TVO_OK);
    TEST_ASSERT_EQUAL_INT(0, TVO_OUTCOME_APPLIED);
    TEST_ASSERT_EQUAL_INT(0, TVO_REASON_NONE);
    TEST_ASSERT_EQUAL_INT(0, TVO_PARAM_NONE);
    TEST_ASSERT_EQUAL_INT(0, TVO_CHAIN_PARAM_NONE);
    TEST_ASSERT_EQUAL_INT(TVO_STATUS_COUNT - 1, TVO_ERR_NUMERIC);
    TEST_ASSERT_EQUAL_INT(TVO_REASON_COUNT - 1, TVO_REASON_REFUSED);
}

static void test_flags_are_distinct_bits_apart_from_the_wires_outcome_bits(void)
{
    const uint32_t flags[] = {TVO_FLAG_OMEGA_SATURATED, TVO_FLAG_ACCEL_SATURATED, TVO_FLAG_SPEED_SATURATED,
                              TVO_FLAG_LOW_SPEED,       TVO_FLAG_PREDICTED,       TVO_FLAG_REGULARIZED,
                              TVO_FLAG_SPEED_MISMATCH};
    const uint32_t wire_outcome_bits = (1u << 4) | (1u << 5); /* command_t.FLAG_HOLDING, FLAG_SAFE_STOP */
    uint32_t all = 0;
    for (size_t i = 0; i < sizeof(flags) / sizeof(flags[0]); ++i) {
        TEST_ASSERT_EQUAL_UINT32(0u, flags[i] & (flags[i] - 1u)); /* one bit */
        TEST_ASSERT_EQUAL_UINT32(0u, all & flags[i]);
        all |= flags[i];
    }
    TEST_ASSERT_EQUAL_UINT32(0u, all & wire_outcome_bits);
}

static void test_parameter_names_are_config_field_names(void)
{
    TEST_ASSERT_EQUAL_STRING("tick_hz", tvo_param_str(TVO_PARAM_TICK_HZ));
    TEST_ASSERT_EQUAL_STRING("period_ticks", tvo_param_str(TVO_PARAM_PERIOD));
    TEST_ASSERT_EQUAL_STRING("delay_ticks", tvo_param_str(TVO_PARAM_DELAY));
    TEST_ASSERT_EQUAL_STRING("filter_tf_s", tvo_param_str(TVO_PARAM_FILTER_TF));
    TEST_ASSERT_NOT_NULL(strstr(tvo_param_str(TVO_PARAM_GAINS), "gain_kp"));
    TEST_ASSERT_NOT_NULL(strstr(tvo_param_str(TVO_PARAM_GAINS), "gain_kd"));
    TEST_ASSERT_EQUAL_STRING("omega_max_radps", tvo_param_str(TVO_PARAM_OMEGA_MAX));
    TEST_ASSERT_EQUAL_STRING("accel_max_mps2", tvo_param_str(TVO_PARAM_ACCEL_MAX));
    TEST_ASSERT_EQUAL_STRING("speed_max_mps", tvo_param_str(TVO_PARAM_SPEED_MAX));
    TEST_ASSERT_EQUAL_STRING("min_speed_mps", tvo_param_str(TVO_PARAM_MIN_SPEED));
    TEST_ASSERT_EQUAL_STRING("watchdog_periods", tvo_param_str(TVO_PARAM_WATCHDOG));
    TEST_ASSERT_EQUAL_STRING("robot_count", tvo_param_str(TVO_PARAM_ROBOT_COUNT));
    TEST_ASSERT_EQUAL_STRING("velocity_source", tvo_param_str(TVO_PARAM_VELOCITY_SOURCE));
    TEST_ASSERT_EQUAL_STRING("initial_speed_mps", tvo_param_str(TVO_PARAM_INITIAL_SPEED));
    TEST_ASSERT_EQUAL_STRING("objective", tvo_param_str(TVO_PARAM_OBJECTIVE));
    /* The chain's configuration names its own fields. */
    TEST_ASSERT_EQUAL_STRING("tick_hz", tvo_chain_param_str(TVO_CHAIN_PARAM_TICK_HZ));
    TEST_ASSERT_EQUAL_STRING("period_ticks", tvo_chain_param_str(TVO_CHAIN_PARAM_PERIOD));
    TEST_ASSERT_EQUAL_STRING("delay_ticks", tvo_chain_param_str(TVO_CHAIN_PARAM_DELAY));
    TEST_ASSERT_EQUAL_STRING("relative_degree", tvo_chain_param_str(TVO_CHAIN_PARAM_RELATIVE_DEGREE));
    TEST_ASSERT_EQUAL_STRING("gain", tvo_chain_param_str(TVO_CHAIN_PARAM_GAIN));
    TEST_ASSERT_EQUAL_STRING("filter_tf_s", tvo_chain_param_str(TVO_CHAIN_PARAM_FILTER_TF));
    TEST_ASSERT_EQUAL_STRING("input_max", tvo_chain_param_str(TVO_CHAIN_PARAM_INPUT_MAX));
    TEST_ASSERT_EQUAL_STRING("watchdog_periods", tvo_chain_param_str(TVO_CHAIN_PARAM_WATCHDOG));
    TEST_ASSERT_EQUAL_STRING("objective", tvo_chain_param_str(TVO_CHAIN_PARAM_OBJECTIVE));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_status_outcome_reason_and_parameter_has_a_distinct_description);
    RUN_TEST(test_zero_is_success_applied_and_no_reason);
    RUN_TEST(test_flags_are_distinct_bits_apart_from_the_wires_outcome_bits);
    RUN_TEST(test_parameter_names_are_config_field_names);
    return UNITY_END();
}
