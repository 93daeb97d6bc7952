/*
 * Status and parameter names: every code has its own description, and parameter names are the
 * tvo_controller_config_t field names (so a log line points at the field to fix).
 */
#include "test_support.h"

void setUp(void) {}
void tearDown(void) {}

static void test_every_status_has_a_distinct_description(void)
{
    const char *seen[TVO_ERR_WATCHDOG + 1];
    const char *unknown = tvo_status_str((tvo_status_t)999);
    TEST_ASSERT_NOT_NULL(unknown);
    for (int s = TVO_OK; s <= TVO_ERR_WATCHDOG; ++s) {
        const char *str = tvo_status_str((tvo_status_t)s);
        TEST_ASSERT_NOT_NULL(str);
        TEST_ASSERT_TRUE(strlen(str) > 0u);
        TEST_ASSERT_TRUE_MESSAGE(strcmp(str, unknown) != 0, "a defined status prints as unknown");
        for (int p = TVO_OK; p < s; ++p) {
            TEST_ASSERT_TRUE_MESSAGE(strcmp(seen[p], str) != 0, "two statuses share a description");
        }
        seen[s] = str;
    }
}

static void test_status_values_are_the_wire_values(void)
{
    /* command_t.status carries these numbers: they must never be renumbered. */
    TEST_ASSERT_EQUAL_INT(0, TVO_OK);
    TEST_ASSERT_EQUAL_INT(1, TVO_ERR_NULL);
    TEST_ASSERT_EQUAL_INT(2, TVO_ERR_NOT_FINITE);
    TEST_ASSERT_EQUAL_INT(3, TVO_ERR_DIMENSION);
    TEST_ASSERT_EQUAL_INT(4, TVO_ERR_PARAM);
    TEST_ASSERT_EQUAL_INT(5, TVO_ERR_CAPACITY);
    TEST_ASSERT_EQUAL_INT(6, TVO_ERR_NOT_INITIALIZED);
    TEST_ASSERT_EQUAL_INT(7, TVO_ERR_NOT_POSITIVE_DEFINITE);
    TEST_ASSERT_EQUAL_INT(8, TVO_ERR_NUMERIC);
    TEST_ASSERT_EQUAL_INT(9, TVO_ERR_STALE);
    TEST_ASSERT_EQUAL_INT(10, TVO_ERR_OUT_OF_ORDER);
    TEST_ASSERT_EQUAL_INT(11, TVO_ERR_FUTURE_STAMP);
    TEST_ASSERT_EQUAL_INT(12, TVO_ERR_NO_MEASUREMENT);
    TEST_ASSERT_EQUAL_INT(13, TVO_ERR_MISSING_FIELD);
    TEST_ASSERT_EQUAL_INT(14, TVO_ERR_TARGET_NOT_READY);
    TEST_ASSERT_EQUAL_INT(15, TVO_ERR_WATCHDOG);
}

static void test_flags_are_distinct_bits(void)
{
    const uint32_t flags[] = {TVO_FLAG_OMEGA_SATURATED, TVO_FLAG_ACCEL_SATURATED, TVO_FLAG_SPEED_SATURATED,
                              TVO_FLAG_LOW_SPEED,       TVO_FLAG_HOLDING,         TVO_FLAG_SAFE_STOP,
                              TVO_FLAG_PREDICTED};
    uint32_t all = 0;
    for (size_t i = 0; i < sizeof(flags) / sizeof(flags[0]); ++i) {
        TEST_ASSERT_EQUAL_UINT32(0u, flags[i] & (flags[i] - 1u)); /* one bit */
        TEST_ASSERT_EQUAL_UINT32(0u, all & flags[i]);
        all |= flags[i];
    }
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
    TEST_ASSERT_NOT_NULL(tvo_param_str(TVO_PARAM_OBJECTIVE));
    TEST_ASSERT_NOT_NULL(tvo_param_str(TVO_PARAM_EPOCH));
    TEST_ASSERT_NOT_NULL(tvo_param_str((tvo_param_t)999));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_every_status_has_a_distinct_description);
    RUN_TEST(test_status_values_are_the_wire_values);
    RUN_TEST(test_flags_are_distinct_bits);
    RUN_TEST(test_parameter_names_are_config_field_names);
    return UNITY_END();
}
