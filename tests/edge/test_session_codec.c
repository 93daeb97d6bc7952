/*
 * The session codec on its own (firmware/edge/session_codec.c): the START's timing ranges at the
 * int64/int32 extremes, every path kind, polynomial coefficients past the build's degree, counts
 * past capacity, robot indices past robot_count, the controller configurations, the ack's fields,
 * and the content hash that tells a repeated START from a new one.
 */
#include "edge_fixture.h"

#include "tvo/target.h"
#include "internal/objective.h"
#include "internal/target.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static tvo_lcm_session_t msg;
static tvo_problem_desc_t desc;

static const int64_t int64_extremes[] = {INT64_MIN, -1, EF_TWO_POW_60 + 1, INT64_MAX};
#define INT64_EXTREMES (sizeof(int64_extremes) / sizeof(int64_extremes[0]))

/* Evaluates a target's position at t_s. */
static void position_at(const tvo_target_t *target, double t_s, double out[2])
{
    tvo_time_jet_t t;
    EF_ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks((uint64_t)llround(t_s * (double)TVO_EDGE_TICK_HZ), TVO_EDGE_TICK_HZ,
                                                   TVO_R(1.0), &t));
    tvo_real_t d[TVO_JET_MAX_ORDER + 1][2];
    EF_ASSERT_STATUS(TVO_OK, tvo_target_derivatives(target, &t, 0, d));
    out[0] = (double)d[0][0];
    out[1] = (double)d[0][1];
}

/* Position tolerance of the core's scalar for values of order 1..10. */
#define POS_TOL (200.0 * (double)TVO_EPSILON)

static tvo_status_t decode_timing(tvo_session_timing_t *timing, tvo_session_reject_t *why)
{
    return tvo_session_decode_timing(&msg, timing, why);
}

/* A START whose timing is refused names `param` (status TVO_ERR_PARAM, no part). */
static void expect_timing_refused(tvo_session_param_t param, int line)
{
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    memset(&why, 0x5A, sizeof(why));
    const tvo_status_t st = decode_timing(&timing, &why);
    if (st != TVO_ERR_PARAM || why.status != TVO_ERR_PARAM || why.param != param ||
        why.part != TVO_LCM_SESSION_ACK_T_PART_NONE || why.index != -1) {
        static char text[200];
        (void)snprintf(text, sizeof(text), "expected PARAM/%s, got status %d why {%d, %s, part %d, index %d}",
                       tvo_protocol_param_str((int32_t)param), (int)st, (int)why.status,
                       tvo_protocol_param_str((int32_t)why.param), (int)why.part, (int)why.index);
        UNITY_TEST_FAIL(line, text);
    }
}
#define EXPECT_TIMING_REFUSED(param) expect_timing_refused((param), __LINE__)

/* The problem's decode refuses with status, part and index. */
static void expect_problem_refused(tvo_status_t status, int32_t part, int32_t index, int line)
{
    tvo_session_reject_t why;
    memset(&why, 0x5A, sizeof(why));
    const tvo_status_t st = tvo_session_decode_problem(&msg, &desc, &why);
    if (st != status || why.status != status || why.param != TVO_SESSION_PARAM_OBJECTIVE || why.part != part ||
        why.index != index) {
        static char text[200];
        (void)snprintf(text, sizeof(text),
                       "expected %s part %d index %d, got status %d why {%d, param %d, part %d, index %d}",
                       tvo_status_str(status), (int)part, (int)index, (int)st, (int)why.status, (int)why.param,
                       (int)why.part, (int)why.index);
        UNITY_TEST_FAIL(line, text);
    }
}
#define EXPECT_PROBLEM_REFUSED(status, part, index) expect_problem_refused((status), (part), (index), __LINE__)

static void expect_problem_ok(int line)
{
    tvo_session_reject_t why;
    const tvo_status_t st = tvo_session_decode_problem(&msg, &desc, &why);
    if (st != TVO_OK || why.status != TVO_OK) {
        static char text[160];
        (void)snprintf(text, sizeof(text), "expected OK, got %d (%s) part %d index %d", (int)st, tvo_status_str(st),
                       (int)why.part, (int)why.index);
        UNITY_TEST_FAIL(line, text);
    }
}
#define EXPECT_PROBLEM_OK() expect_problem_ok(__LINE__)

/* ------------------------------------------------------------------------------------------------
 * Timing
 * --------------------------------------------------------------------------------------------- */

static void test_valid_start_decodes_its_timing(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_NODE, 3);
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    EF_ASSERT_STATUS(TVO_OK, why.status);
    EF_ASSERT_PARAM(TVO_SESSION_PARAM_NONE, why.param);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_T_CLOCK_NODE, timing.clock_source);
    TEST_ASSERT_EQUAL_INT64(EF_EPOCH, timing.epoch_utime);
    TEST_ASSERT_EQUAL_INT64(EF_PERIOD_US, timing.period_us);
    TEST_ASSERT_EQUAL_INT64(EF_DELAY_US, timing.delay_us);
    TEST_ASSERT_EQUAL_UINT32(EF_WATCHDOG, timing.watchdog_periods);
    TEST_ASSERT_EQUAL_UINT8(3u, timing.robot_count);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_T_PLANT_UNICYCLE, timing.plant_kind);
    TEST_ASSERT_EQUAL_UINT32(1u, timing.telemetry_every); /* the fixture asks for every answer's */
}

static void test_protocol_version_other_than_this_wires_is_refused_first(void)
{
    const int32_t bad[] = {INT32_MIN, -1, 0, 1, 2, TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.protocol_version = bad[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_PROTOCOL_VERSION);
        msg.period_us = 0; /* its other fields may mean something else: the version is named first */
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_PROTOCOL_VERSION);
    }
}

static void test_telemetry_every_zero_is_the_default_rate_and_its_range_is_checked(void)
{
    /* 0: the fewest periods spanning 100 ms, for every period from 1 us to the longest. */
    const int64_t periods[] = {1, 3, 9999, 10000, 10001, 33333, 100000, 100001, (int64_t)TVO_MAX_TICK_SPAN};
    for (size_t i = 0; i < sizeof(periods) / sizeof(periods[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.period_us = periods[i];
        msg.delay_us = 0;
        msg.watchdog_periods = 1;
        msg.telemetry_every = 0;
        tvo_session_timing_t timing;
        tvo_session_reject_t why;
        EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
        const uint32_t every = timing.telemetry_every;
        TEST_ASSERT_TRUE(every >= 1u);
        TEST_ASSERT_TRUE((int64_t)every * periods[i] >= TVO_SESSION_TELEMETRY_DEFAULT_US || every == 1u);
        TEST_ASSERT_TRUE(every == 1u || (int64_t)(every - 1u) * periods[i] < TVO_SESSION_TELEMETRY_DEFAULT_US);
    }
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.telemetry_every = 0;
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    TEST_ASSERT_EQUAL_UINT32(10u, timing.telemetry_every); /* h = 10 ms: 10 Hz */
    msg.telemetry_every = TVO_SESSION_TELEMETRY_EVERY_MAX;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)TVO_SESSION_TELEMETRY_EVERY_MAX, timing.telemetry_every);
    const int32_t bad[] = {INT32_MIN, -1, TVO_SESSION_TELEMETRY_EVERY_MAX + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        msg.telemetry_every = bad[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_TELEMETRY_EVERY);
    }
}

static void test_a_chain_session_has_one_robot(void)
{
    for (int32_t robots = 2; robots <= TVO_MAX_ROBOTS; ++robots) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, robots);
        msg.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_ROBOT_COUNT);
    }
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
}

static void test_utime_and_epoch_outside_the_wire_range_name_the_epoch(void)
{
    for (size_t i = 0; i < INT64_EXTREMES; ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.utime = int64_extremes[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_EPOCH);
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.epoch_utime = int64_extremes[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_EPOCH);
        /* Both at the same extreme: their difference is 0, the range check must still refuse. */
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.utime = int64_extremes[i];
        msg.epoch_utime = int64_extremes[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_EPOCH);
    }
}

static void test_times_at_the_ends_of_the_wire_range_are_accepted(void)
{
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.utime = 0;
    msg.epoch_utime = 0;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    msg.utime = EF_TWO_POW_60;
    msg.epoch_utime = EF_TWO_POW_60;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    TEST_ASSERT_EQUAL_INT64(EF_TWO_POW_60, timing.epoch_utime);
}

static void test_epoch_lead_is_limited_to_the_controllers_tick_span(void)
{
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    /* Half the controller's clock span: the other half is left for the first sample after START. */
    const int64_t span = TVO_SESSION_EPOCH_SPAN_US;
    const int64_t base = (int64_t)1 << 40;
    const int64_t leads_ok[] = {-span, -1, 0, 1, span};
    for (size_t i = 0; i < sizeof(leads_ok) / sizeof(leads_ok[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.utime = base;
        msg.epoch_utime = base + leads_ok[i];
        EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    }
    const int64_t leads_bad[] = {-span - 1, span + 1, -((int64_t)1 << 39), (int64_t)1 << 39};
    for (size_t i = 0; i < sizeof(leads_bad) / sizeof(leads_bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.utime = base;
        msg.epoch_utime = base + leads_bad[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_EPOCH);
    }
}

static void test_period_outside_one_to_two_pow_thirty_is_refused(void)
{
    const int64_t bad[] = {INT64_MIN, -1, 0, (int64_t)TVO_MAX_TICK_SPAN + 1, EF_TWO_POW_60 + 1, INT64_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.period_us = bad[i];
        msg.delay_us = 0;
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_PERIOD);
    }
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.period_us = 1;
    msg.delay_us = 1;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    msg.period_us = (int64_t)TVO_MAX_TICK_SPAN;
    msg.watchdog_periods = 1;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
}

static void test_delay_outside_zero_to_period_is_refused(void)
{
    const int64_t bad[] = {INT64_MIN, -1, EF_PERIOD_US + 1, EF_TWO_POW_60 + 1, INT64_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.delay_us = bad[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_DELAY);
    }
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.delay_us = 0;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    msg.delay_us = EF_PERIOD_US;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
}

static void test_watchdog_below_one_or_past_the_span_is_refused(void)
{
    const int32_t longest = (int32_t)(TVO_MAX_TICK_SPAN / (uint32_t)EF_PERIOD_US);
    const int32_t bad[] = {INT32_MIN, -1, 0};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.watchdog_periods = bad[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_WATCHDOG);
    }
    /* Past the clock's span: the core's init refuses it (the span is its contract), naming the watchdog. */
    static tvo_problem_t problem;
    static tvo_controller_t ctl;
    const int32_t past_span[] = {longest + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(past_span) / sizeof(past_span[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.watchdog_periods = past_span[i];
        tvo_session_timing_t timing;
        tvo_controller_config_t cfg;
        tvo_session_reject_t why;
        EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
        EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_unicycle(&msg, &cfg, &why));
        EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_problem(&msg, &desc, &why));
        EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, NULL));
        tvo_param_t culprit = TVO_PARAM_NONE;
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_controller_init(&ctl, &cfg, &problem.objective, 0u, &culprit));
        TEST_ASSERT_EQUAL_INT(TVO_SESSION_PARAM_WATCHDOG, tvo_session_param_of_unicycle(culprit));
    }
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.watchdog_periods = longest;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
    TEST_ASSERT_EQUAL_UINT32((uint32_t)longest, timing.watchdog_periods);
    msg.watchdog_periods = 1;
    EF_ASSERT_STATUS(TVO_OK, decode_timing(&timing, &why));
}

static void test_robot_count_clock_source_and_plant_kind_extremes_are_refused(void)
{
    const int32_t bad_counts[] = {INT32_MIN, -1, 0, TVO_MAX_ROBOTS + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad_counts) / sizeof(bad_counts[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.robot_count = bad_counts[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_ROBOT_COUNT);
    }
    const int32_t bad_kinds[] = {INT32_MIN, -1, 2, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad_kinds) / sizeof(bad_kinds[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.clock_source = bad_kinds[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_CLOCK_SOURCE);
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.plant_kind = bad_kinds[i];
        EXPECT_TIMING_REFUSED(TVO_SESSION_PARAM_PLANT_KIND);
    }
}

static void test_null_arguments_are_refused(void)
{
    tvo_session_timing_t timing;
    tvo_session_reject_t why;
    tvo_controller_config_t ucfg;
    tvo_chain_config_t ccfg;
    tvo_target_t target;
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_timing(NULL, &timing, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, why.status);
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_timing(&msg, NULL, &why));
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_timing(&msg, &timing, NULL)); /* why is optional */
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_unicycle(NULL, &ucfg, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_unicycle(&msg, NULL, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_chain(NULL, &ccfg, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_chain(&msg, NULL, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_problem(NULL, &desc, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_problem(&msg, NULL, &why));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_path(NULL, &target));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_session_decode_path(&msg.robot[0].target, NULL));
    tvo_session_ack(&msg, &why, 1, EF_BOOT, -1, NULL); /* must not crash */
}

/* ------------------------------------------------------------------------------------------------
 * Controller configurations
 * --------------------------------------------------------------------------------------------- */

static void test_unicycle_configuration_carries_every_field(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    msg.velocity_source = TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION;
    msg.zoh_aware = 1;
    msg.delay_compensation = 0;
    msg.robot[0].initial_speed_mps = 0.25;
    msg.robot[1].initial_speed_mps = -0.5;
    msg.robot[2].initial_speed_mps = 9.0; /* past robot_count: ignored */
    tvo_controller_config_t cfg;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_unicycle(&msg, &cfg, &why));
    TEST_ASSERT_EQUAL_UINT32(TVO_EDGE_TICK_HZ, cfg.tick_hz);
    TEST_ASSERT_EQUAL_UINT32(EF_PERIOD_US, cfg.period_ticks);
    TEST_ASSERT_EQUAL_UINT32(EF_DELAY_US, cfg.delay_ticks);
    TEST_ASSERT_EQUAL_UINT8(2u, cfg.robot_count);
    TEST_ASSERT_EQUAL_UINT8(0u, cfg.delay_compensation);
    TEST_ASSERT_EQUAL_UINT8(1u, cfg.zoh_aware);
    TEST_ASSERT_EQUAL_INT(TVO_VELOCITY_FROM_POSITION, cfg.velocity_source);
    TEST_ASSERT_EQUAL_UINT32(EF_WATCHDOG, cfg.watchdog_periods);
    TEST_ASSERT_TRUE(cfg.gain_kp == (tvo_real_t)40.0 && cfg.gain_kd == (tvo_real_t)13.0);
    TEST_ASSERT_TRUE(cfg.speed_max_mps == (tvo_real_t)2.0 && cfg.min_speed_mps == (tvo_real_t)0.05);
    TEST_ASSERT_TRUE(cfg.filter_tf_s == (tvo_real_t)0.05 && cfg.accel_max_mps2 == (tvo_real_t)15.0);
    TEST_ASSERT_TRUE(cfg.initial_speed_mps[0] == (tvo_real_t)0.25);
    TEST_ASSERT_TRUE(cfg.initial_speed_mps[1] == (tvo_real_t)-0.5);
    TEST_ASSERT_TRUE(cfg.initial_speed_mps[2] == TVO_R(0.0));
}

static void test_unicycle_velocity_source_extremes_are_refused(void)
{
    const int32_t bad[] = {INT32_MIN, -1, 2, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.velocity_source = bad[i];
        tvo_controller_config_t cfg;
        tvo_session_reject_t why;
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_unicycle(&msg, &cfg, &why));
        EF_ASSERT_PARAM(TVO_SESSION_PARAM_VELOCITY_SOURCE, why.param);
        tvo_chain_config_t ccfg;
        msg.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_chain(&msg, &ccfg, &why));
        EF_ASSERT_PARAM(TVO_SESSION_PARAM_VELOCITY_SOURCE, why.param);
    }
}

static void test_wire_doubles_beyond_the_scalar_become_infinite_not_undefined(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.gain_kp = 1e300;
    msg.gain_kd = -1e300;
    msg.filter_tf_s = (double)NAN;
    tvo_controller_config_t cfg;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_unicycle(&msg, &cfg, &why));
#if TVO_USE_DOUBLE
    TEST_ASSERT_TRUE(cfg.gain_kp == 1e300 && cfg.gain_kd == -1e300);
#else
    TEST_ASSERT_TRUE(isinf(cfg.gain_kp) && cfg.gain_kp > TVO_R(0.0));
    TEST_ASSERT_TRUE(isinf(cfg.gain_kd) && cfg.gain_kd < TVO_R(0.0));
#endif
    TEST_ASSERT_TRUE(isnan(cfg.filter_tf_s));
}

static void test_chain_configuration_and_relative_degree_extremes(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.plant_kind = TVO_LCM_SESSION_T_PLANT_CHAIN;
    msg.velocity_source = TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION;
    tvo_chain_config_t cfg;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_chain(&msg, &cfg, &why));
    TEST_ASSERT_EQUAL_UINT8(2u, cfg.relative_degree);
    TEST_ASSERT_EQUAL_UINT8(1u, cfg.filtered_derivatives);
    TEST_ASSERT_EQUAL_UINT32(EF_PERIOD_US, cfg.period_ticks);
    TEST_ASSERT_EQUAL_UINT32(EF_WATCHDOG, cfg.watchdog_periods);
    TEST_ASSERT_TRUE(cfg.gain[0] == (tvo_real_t)2.56 && cfg.gain[1] == (tvo_real_t)3.2);
    TEST_ASSERT_TRUE(cfg.input_max == (tvo_real_t)1000.0);
    const int32_t bad[] = {INT32_MIN, -1, 0, TVO_MAX_RELATIVE_DEGREE + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        msg.chain_relative_degree = bad[i];
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_chain(&msg, &cfg, &why));
        EF_ASSERT_PARAM(TVO_SESSION_PARAM_GAINS, why.param);
    }
    msg.chain_relative_degree = TVO_MAX_RELATIVE_DEGREE;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_chain(&msg, &cfg, &why));
}

/* ------------------------------------------------------------------------------------------------
 * Paths
 * --------------------------------------------------------------------------------------------- */

static void test_polynomial_path_evaluates_its_coefficients(void)
{
    tvo_lcm_path_t path;
    memset(&path, 0, sizeof(path));
    path.kind = TVO_LCM_PATH_T_KIND_POLYNOMIAL;
    double expected[2] = {0.0, 0.0};
    const double t = 0.5;
    double tj = 1.0;
    for (int j = 0; j <= TVO_POLY_MAX_DEGREE && j < TVO_LCM_PATH_T_MAX_COEFFS; ++j) {
        path.coeff[0][j] = 0.1 * (double)(j + 1);
        path.coeff[1][j] = -0.3 + 0.05 * (double)j;
        expected[0] += path.coeff[0][j] * tj;
        expected[1] += path.coeff[1][j] * tj;
        tj *= t;
    }
    tvo_target_t target;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
    TEST_ASSERT_EQUAL_INT(TVO_TARGET_POLYNOMIAL, target.kind);
    double p[2];
    position_at(&target, t, p);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, expected[0], p[0]);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, expected[1], p[1]);
}

static void test_polynomial_coefficients_past_the_builds_degree_are_refused(void)
{
#if TVO_POLY_MAX_DEGREE + 1 < TVO_LCM_PATH_T_MAX_COEFFS
    for (int axis = 0; axis < 2; ++axis) {
        for (int j = TVO_POLY_MAX_DEGREE + 1; j < TVO_LCM_PATH_T_MAX_COEFFS; ++j) {
            tvo_lcm_path_t path;
            ef_line_path(&path, 0.5, 0.0, 0.2);
            path.coeff[axis][j] = 1e-9;
            tvo_target_t target;
            EF_ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_session_decode_path(&path, &target));
        }
    }
    /* Through the problem: the robot's entry is named. */
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    msg.robot[1].target.coeff[1][TVO_LCM_PATH_T_MAX_COEFFS - 1] = -2.0;
    EXPECT_PROBLEM_REFUSED(TVO_ERR_CAPACITY, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 1);
    /* Zeros past the degree are no coefficient at all. */
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    EXPECT_PROBLEM_OK();
#else
    /* This build evaluates every coefficient the wire carries: the highest one counts. */
    tvo_lcm_path_t path;
    ef_line_path(&path, 0.0, 0.0, 0.0);
    path.coeff[0][TVO_LCM_PATH_T_MAX_COEFFS - 1] = 1.0;
    tvo_target_t target;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
    double p[2];
    position_at(&target, 2.0, p);
    TEST_ASSERT_DOUBLE_WITHIN(1e-3, ldexp(1.0, TVO_LCM_PATH_T_MAX_COEFFS - 1), p[0]);
#endif
}

static void test_circle_and_ellipse_paths_evaluate_their_parameters(void)
{
    tvo_lcm_path_t path;
    memset(&path, 0, sizeof(path));
    path.kind = TVO_LCM_PATH_T_KIND_CIRCLE;
    path.center_m[0] = 1.0;
    path.center_m[1] = -2.0;
    path.semi_axis_m[0] = 0.5;
    path.semi_axis_m[1] = 99.0; /* a circle reads only [0] */
    path.omega_radps = 2.0;
    path.phase_rad = 0.3;
    tvo_target_t target;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
    const double t = 0.7;
    double p[2];
    position_at(&target, t, p);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, 1.0 + 0.5 * cos(2.0 * t + 0.3), p[0]);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, -2.0 + 0.5 * sin(2.0 * t + 0.3), p[1]);

    path.kind = TVO_LCM_PATH_T_KIND_ELLIPSE;
    path.semi_axis_m[1] = 0.25;
    path.rotation_rad = 0.4;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
    position_at(&target, t, p);
    const double a = 0.5 * cos(2.0 * t + 0.3);
    const double b = 0.25 * sin(2.0 * t + 0.3);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, 1.0 + cos(0.4) * a - sin(0.4) * b, p[0]);
    TEST_ASSERT_DOUBLE_WITHIN(POS_TOL, -2.0 + sin(0.4) * a + cos(0.4) * b, p[1]);

    /* Their values are the core's to judge: a zero radius is the core's PARAM. */
    path.kind = TVO_LCM_PATH_T_KIND_CIRCLE;
    path.semi_axis_m[0] = 0.0;
    EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_path(&path, &target));
}

static void test_periodic_paths_refuse_a_rate_beyond_the_bound_on_the_wire_value(void)
{
    /* The bound is on the wire's double: 8192.0001 rounds to 8192.0f, which the core would take. */
    const double bound = (double)TVO_TARGET_MAX_OMEGA_RADPS;
    const double above = nextafter(bound, HUGE_VAL) > bound + 1e-4 ? nextafter(bound, HUGE_VAL) : bound + 1e-4;
    for (int32_t kind = TVO_LCM_PATH_T_KIND_CIRCLE; kind <= TVO_LCM_PATH_T_KIND_ELLIPSE; ++kind) {
        tvo_lcm_path_t path;
        memset(&path, 0, sizeof(path));
        path.kind = kind;
        path.semi_axis_m[0] = 0.5;
        path.semi_axis_m[1] = 0.25;
        tvo_target_t target;
        for (int sign = -1; sign <= 1; sign += 2) {
            path.omega_radps = sign * bound;
            EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
            path.omega_radps = sign * above;
            EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_path(&path, &target));
        }
        /* What the core refuses first is still the core's to say. */
        path.omega_radps = above;
        path.semi_axis_m[0] = (double)NAN;
        EF_ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_session_decode_path(&path, &target));
        /* In a START: the robot's target names the robot. */
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
        msg.robot[1].target = path;
        msg.robot[1].target.semi_axis_m[0] = 0.5;
        EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 1);
    }
}

static void test_streamed_path_waits_for_its_first_sample(void)
{
    tvo_lcm_path_t path;
    memset(&path, 0, sizeof(path));
    path.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    tvo_target_t target;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_path(&path, &target));
    TEST_ASSERT_EQUAL_INT(TVO_TARGET_STREAMED, target.kind);
    TEST_ASSERT_EQUAL_UINT8(0u, target.u.streamed.has_sample);
}

static void test_unknown_path_kinds_are_refused(void)
{
    const int32_t bad[] = {INT32_MIN, -1, TVO_LCM_PATH_T_KIND_STREAMED + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        tvo_lcm_path_t path;
        ef_line_path(&path, 0.0, 0.0, 0.0);
        path.kind = bad[i];
        tvo_target_t target;
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_path(&path, &target));
        /* In a START: the robot's target names the robot. */
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 3);
        msg.robot[2].target.kind = bad[i];
        EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, 2);
        /* In a formation offset: the offset's entry. */
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
        msg.offset_count = 1;
        msg.offset[0].robot_a = 0;
        msg.offset[0].robot_b = 1;
        ef_line_path(&msg.offset[0].offset, 0.0, 1.0, 0.0);
        EXPECT_PROBLEM_OK();
        msg.offset[0].offset.kind = bad[i];
        EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 0);
    }
}

static void test_a_streamed_formation_offset_is_refused(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    msg.offset_count = 1;
    msg.offset[0].robot_a = 0;
    msg.offset[0].robot_b = 1;
    msg.offset[0].offset.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 0);
}

/* ------------------------------------------------------------------------------------------------
 * The problem: counts, indices, barrier
 * --------------------------------------------------------------------------------------------- */

static void test_problem_decodes_every_part(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    msg.robot[1].tracking_weight[0] = 2.0;
    msg.robot[1].tracking_weight[1] = 3.0;
    msg.distance_count = 1;
    msg.distance[0].robot_a = 0;
    msg.distance[0].robot_b = 1;
    msg.distance[0].min_m = 0.3;
    msg.distance[0].max_m = 2.0;
    msg.halfspace_count = 1;
    msg.halfspace[0].robot = 1;
    msg.halfspace[0].normal[0] = 1.0;
    msg.halfspace[0].bound_m = 4.0;
    msg.obstacle_count = 1;
    msg.obstacle[0].center_m[0] = 3.0;
    msg.obstacle[0].center_m[1] = 3.0;
    msg.obstacle[0].radius_m = 0.5;
    msg.offset_count = 1;
    msg.offset[0].robot_a = 1;
    msg.offset[0].robot_b = 0;
    ef_line_path(&msg.offset[0].offset, 0.0, 1.0, 0.0);
    msg.barrier.relaxation_degree = 5;
    EXPECT_PROBLEM_OK();
    TEST_ASSERT_EQUAL_UINT8(2u, desc.robot_count);
    TEST_ASSERT_TRUE(desc.tracking_weight[1][0] == TVO_R(2.0) && desc.tracking_weight[1][1] == TVO_R(3.0));
    TEST_ASSERT_EQUAL_UINT8(1u, desc.distance_count);
    TEST_ASSERT_EQUAL_UINT8(1u, desc.distance[0].robot_b);
    TEST_ASSERT_TRUE(desc.distance[0].min_m == (tvo_real_t)0.3 && desc.distance[0].max_m == TVO_R(2.0));
    TEST_ASSERT_EQUAL_UINT8(1u, desc.halfspace_count);
    TEST_ASSERT_EQUAL_UINT8(1u, desc.halfspace[0].robot);
    TEST_ASSERT_TRUE(desc.halfspace[0].bound_m == TVO_R(4.0));
    TEST_ASSERT_EQUAL_UINT8(1u, desc.obstacle_count);
    TEST_ASSERT_TRUE(desc.obstacle[0].radius_m == TVO_R(0.5) && desc.robot_radius_m == (tvo_real_t)0.1);
    TEST_ASSERT_EQUAL_UINT8(1u, desc.offset_count);
    TEST_ASSERT_EQUAL_UINT8(1u, desc.offset[0].robot_a);
    TEST_ASSERT_EQUAL_UINT8(5u, desc.barrier.relaxation_degree);
    /* And the core builds it. */
    tvo_problem_t problem;
    tvo_problem_culprit_t part;
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
}

/* Sets the count of `part` in msg. */
static void set_count(int32_t part, int32_t count)
{
    switch (part) {
    case TVO_LCM_SESSION_ACK_T_PART_DISTANCE: msg.distance_count = count; break;
    case TVO_LCM_SESSION_ACK_T_PART_HALFSPACE: msg.halfspace_count = count; break;
    case TVO_LCM_SESSION_ACK_T_PART_OBSTACLES: msg.obstacle_count = count; break;
    default: msg.offset_count = count; break;
    }
}

static void test_counts_past_capacity_or_negative_are_refused(void)
{
    const struct {
        int32_t part;
        int32_t capacity; /* the smaller of the wire's and the core's */
    } parts[] = {
        {TVO_LCM_SESSION_ACK_T_PART_DISTANCE,
         TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS < TVO_MAX_DISTANCE_BOUNDS ? TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS
                                                                        : TVO_MAX_DISTANCE_BOUNDS},
        {TVO_LCM_SESSION_ACK_T_PART_HALFSPACE,
         TVO_LCM_SESSION_T_MAX_HALFSPACES < TVO_MAX_HALFSPACES ? TVO_LCM_SESSION_T_MAX_HALFSPACES : TVO_MAX_HALFSPACES},
        {TVO_LCM_SESSION_ACK_T_PART_OBSTACLES,
         TVO_LCM_SESSION_T_MAX_OBSTACLES < TVO_MAX_OBSTACLES ? TVO_LCM_SESSION_T_MAX_OBSTACLES : TVO_MAX_OBSTACLES},
        {TVO_LCM_SESSION_ACK_T_PART_OFFSETS,
         TVO_LCM_SESSION_T_MAX_OFFSETS < TVO_MAX_OFFSET_EQUALITIES ? TVO_LCM_SESSION_T_MAX_OFFSETS
                                                                   : TVO_MAX_OFFSET_EQUALITIES},
    };
    for (size_t p = 0; p < sizeof(parts) / sizeof(parts[0]); ++p) {
        const int32_t bad[] = {INT32_MIN, -1, parts[p].capacity + 1, INT32_MAX};
        for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
            ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
            set_count(parts[p].part, bad[i]);
            EXPECT_PROBLEM_REFUSED(TVO_ERR_CAPACITY, parts[p].part, -1);
        }
        /* A full table is a count the codec takes (entries valid in robot indices). */
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
        for (int32_t i = 0; i < TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS; ++i) {
            msg.distance[i].robot_b = 1;
        }
        for (int32_t i = 0; i < TVO_LCM_SESSION_T_MAX_OFFSETS; ++i) {
            msg.offset[i].robot_b = 1;
            ef_line_path(&msg.offset[i].offset, 0.0, 1.0, 0.0);
        }
        set_count(parts[p].part, parts[p].capacity);
        EXPECT_PROBLEM_OK();
    }
}

static void test_robot_indices_past_robot_count_are_refused_by_entry(void)
{
    const int32_t bad[] = {INT32_MIN, -1, 2, INT32_MAX}; /* robot_count is 2 */
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        for (int side = 0; side < 2; ++side) {
            ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
            msg.distance_count = 2;
            msg.distance[0].robot_b = 1;
            msg.distance[1].robot_b = 1;
            if (side == 0) {
                msg.distance[1].robot_a = bad[i];
            } else {
                msg.distance[1].robot_b = bad[i];
            }
            EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_DISTANCE, 1);

            ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
            msg.offset_count = 2;
            for (int o = 0; o < 2; ++o) {
                msg.offset[o].robot_b = 1;
                ef_line_path(&msg.offset[o].offset, 0.0, 1.0, 0.0);
            }
            if (side == 0) {
                msg.offset[1].robot_a = bad[i];
            } else {
                msg.offset[1].robot_b = bad[i];
            }
            EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_OFFSETS, 1);
        }
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
        msg.halfspace_count = 3;
        msg.halfspace[2].robot = bad[i];
        EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, 2);
    }
}

static void test_relaxation_degree_outside_a_byte_is_refused(void)
{
    const int32_t bad[] = {INT32_MIN, -1, (int32_t)UINT8_MAX + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.barrier.relaxation_degree = bad[i];
        EXPECT_PROBLEM_REFUSED(TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_BARRIER, -1);
    }
    /* In range for the codec; the barrier's own range is the core's (only with inequalities). */
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.barrier.relaxation_degree = UINT8_MAX;
    EXPECT_PROBLEM_OK();
    TEST_ASSERT_EQUAL_UINT8(UINT8_MAX, desc.barrier.relaxation_degree);
}

static void test_problem_robot_count_extremes_are_refused(void)
{
    const int32_t bad[] = {INT32_MIN, -1, 0, TVO_MAX_ROBOTS + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
        msg.robot_count = bad[i];
        tvo_session_reject_t why;
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_session_decode_problem(&msg, &desc, &why));
        EF_ASSERT_PARAM(TVO_SESSION_PARAM_ROBOT_COUNT, why.param);
    }
}

static void test_problem_parts_map_to_the_acks_names(void)
{
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_ROBOTS, tvo_session_part_from_problem(0));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_BARRIER, tvo_session_part_from_problem(1));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_DISTANCE, tvo_session_part_from_problem(2));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, tvo_session_part_from_problem(3));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, tvo_session_part_from_problem(4));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_OFFSETS, tvo_session_part_from_problem(5));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_NONE, tvo_session_part_from_problem(6));
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_NONE, tvo_session_part_from_problem(UINT8_MAX));
}

/* ------------------------------------------------------------------------------------------------
 * Ack and content hash
 * --------------------------------------------------------------------------------------------- */

static void test_ack_carries_the_message_the_reason_and_the_running_session(void)
{
    ef_start(&msg, INT32_MIN, TVO_LCM_SESSION_T_CLOCK_PLANT, 1);
    msg.utime = 123456789;
    const tvo_session_reject_t why = {TVO_NODE_OK, TVO_ERR_CAPACITY, TVO_SESSION_PARAM_OBJECTIVE,
                                      TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, 3};
    tvo_lcm_session_ack_t ack;
    memset(&ack, 0x5A, sizeof(ack));
    tvo_session_ack(&msg, &why, INT32_MAX, INT64_MAX, 7, &ack);
    TEST_ASSERT_EQUAL_INT64(123456789, ack.utime);
    TEST_ASSERT_EQUAL_INT32(INT32_MIN, ack.session_id);
    TEST_ASSERT_EQUAL_INT64(INT64_MAX, ack.boot_id); /* the answering node's boot and robot */
    TEST_ASSERT_EQUAL_INT(7, ack.own_robot);
    TEST_ASSERT_EQUAL_INT8(TVO_LCM_SESSION_T_ACTION_START, ack.action);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY, ack.status); /* the core's error, in the wire's numbers */
    EF_ASSERT_PARAM(TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE, ack.bad_param);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, ack.bad_part);
    TEST_ASSERT_EQUAL_INT32(3, ack.bad_index);
    TEST_ASSERT_EQUAL_INT32(INT32_MAX, ack.running_session_id);

    /* The edge's own refusals, in the wire's numbers. */
    const tvo_session_reject_t conflict = {TVO_NODE_SESSION_CONFLICT, TVO_OK, TVO_SESSION_PARAM_NONE,
                                           TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    tvo_session_ack(&msg, &conflict, 1, EF_BOOT, -1, &ack);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_SESSION_CONFLICT, ack.status);
    const tvo_session_reject_t no_session = {TVO_NODE_NO_SESSION, TVO_OK, TVO_SESSION_PARAM_NONE,
                                             TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    tvo_session_ack(&msg, &no_session, 1, EF_BOOT, -1, &ack);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_SESSION, ack.status);
    const tvo_session_reject_t unknown = {TVO_NODE_UNKNOWN_ACTION, TVO_OK, TVO_SESSION_PARAM_NONE,
                                          TVO_LCM_SESSION_ACK_T_PART_NONE, -1};
    tvo_session_ack(&msg, &unknown, 1, EF_BOOT, -1, &ack);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM, ack.status);

    /* Without a reason: done, nothing named; with no session running: -1. */
    memset(&ack, 0x5A, sizeof(ack));
    tvo_session_ack(&msg, NULL, -1, EF_BOOT, -1, &ack);
    EF_ASSERT_STATUS(TVO_OK, ack.status);
    TEST_ASSERT_EQUAL_INT32(0, ack.bad_param);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_NONE, ack.bad_part);
    TEST_ASSERT_EQUAL_INT32(-1, ack.bad_index);
    TEST_ASSERT_EQUAL_INT64(-1, ack.running_session_id);

    /* Through the wire and back. */
    uint8_t buffer[TVO_NODE_BUFFER_BYTES];
    tvo_session_ack(&msg, &why, 77, EF_BOOT, 2, &ack);
    const int n = tvo_lcm_session_ack_t_encode(buffer, 0, (int)sizeof(buffer), &ack);
    TEST_ASSERT_TRUE(n > 0);
    tvo_lcm_session_ack_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_session_ack_t_decode(buffer, 0, n, &back));
    TEST_ASSERT_EQUAL_INT32(3, back.bad_index);
    TEST_ASSERT_EQUAL_INT32(TVO_LCM_SESSION_ACK_T_PART_HALFSPACE, back.bad_part);
    TEST_ASSERT_EQUAL_INT32(77, back.running_session_id);
    TEST_ASSERT_EQUAL_INT64(EF_BOOT, back.boot_id);
    TEST_ASSERT_EQUAL_INT(2, back.own_robot);
    TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_SESSION_ACK), n);
}

static uint8_t encoded_a[16384];
static uint8_t encoded_b[16384];

static void test_content_hash_ignores_only_the_utime(void)
{
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    const int n = tvo_lcm_session_t_encode(encoded_a, 0, (int)sizeof(encoded_a), &msg);
    TEST_ASSERT_TRUE(n > 16);
    const uint64_t hash = tvo_session_content_hash(encoded_a, (uint32_t)n);

    /* Another utime (bytes 8..15 after the 8-byte fingerprint): the same content. */
    msg.utime = EF_UTIME + 100000;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_session_t_encode(encoded_b, 0, (int)sizeof(encoded_b), &msg));
    TEST_ASSERT_EQUAL_HEX64(hash, tvo_session_content_hash(encoded_b, (uint32_t)n));
    for (int i = 8; i < 16; ++i) {
        memcpy(encoded_b, encoded_a, (size_t)n);
        encoded_b[i] ^= 0xFFu;
        TEST_ASSERT_EQUAL_HEX64(hash, tvo_session_content_hash(encoded_b, (uint32_t)n));
    }
    /* Every other byte of the content counts. */
    for (int i = 16; i < n; ++i) {
        memcpy(encoded_b, encoded_a, (size_t)n);
        encoded_b[i] ^= 0x01u;
        if (tvo_session_content_hash(encoded_b, (uint32_t)n) == hash) {
            static char text[80];
            (void)snprintf(text, sizeof(text), "flipping byte %d of %d does not change the hash", i, n);
            TEST_FAIL_MESSAGE(text);
        }
    }
    /* A field change, as a plant would make it. */
    ef_start(&msg, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    msg.obstacle[7].radius_m = 1.0; /* past obstacle_count: still content (it is on the wire) */
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_session_t_encode(encoded_b, 0, (int)sizeof(encoded_b), &msg));
    TEST_ASSERT_NOT_EQUAL(hash, tvo_session_content_hash(encoded_b, (uint32_t)n));
    /* Short or absent data: no read past the end. */
    (void)tvo_session_content_hash(encoded_a, 3u);
    (void)tvo_session_content_hash(NULL, 100u);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_valid_start_decodes_its_timing);
    RUN_TEST(test_protocol_version_other_than_this_wires_is_refused_first);
    RUN_TEST(test_telemetry_every_zero_is_the_default_rate_and_its_range_is_checked);
    RUN_TEST(test_a_chain_session_has_one_robot);
    RUN_TEST(test_utime_and_epoch_outside_the_wire_range_name_the_epoch);
    RUN_TEST(test_times_at_the_ends_of_the_wire_range_are_accepted);
    RUN_TEST(test_epoch_lead_is_limited_to_the_controllers_tick_span);
    RUN_TEST(test_period_outside_one_to_two_pow_thirty_is_refused);
    RUN_TEST(test_delay_outside_zero_to_period_is_refused);
    RUN_TEST(test_watchdog_below_one_or_past_the_span_is_refused);
    RUN_TEST(test_robot_count_clock_source_and_plant_kind_extremes_are_refused);
    RUN_TEST(test_null_arguments_are_refused);
    RUN_TEST(test_unicycle_configuration_carries_every_field);
    RUN_TEST(test_unicycle_velocity_source_extremes_are_refused);
    RUN_TEST(test_wire_doubles_beyond_the_scalar_become_infinite_not_undefined);
    RUN_TEST(test_chain_configuration_and_relative_degree_extremes);
    RUN_TEST(test_polynomial_path_evaluates_its_coefficients);
    RUN_TEST(test_polynomial_coefficients_past_the_builds_degree_are_refused);
    RUN_TEST(test_circle_and_ellipse_paths_evaluate_their_parameters);
    RUN_TEST(test_periodic_paths_refuse_a_rate_beyond_the_bound_on_the_wire_value);
    RUN_TEST(test_streamed_path_waits_for_its_first_sample);
    RUN_TEST(test_unknown_path_kinds_are_refused);
    RUN_TEST(test_a_streamed_formation_offset_is_refused);
    RUN_TEST(test_problem_decodes_every_part);
    RUN_TEST(test_counts_past_capacity_or_negative_are_refused);
    RUN_TEST(test_robot_indices_past_robot_count_are_refused_by_entry);
    RUN_TEST(test_relaxation_degree_outside_a_byte_is_refused);
    RUN_TEST(test_problem_robot_count_extremes_are_refused);
    RUN_TEST(test_problem_parts_map_to_the_acks_names);
    RUN_TEST(test_ack_carries_the_message_the_reason_and_the_running_session);
    RUN_TEST(test_content_hash_ignores_only_the_utime);
    return UNITY_END();
}
