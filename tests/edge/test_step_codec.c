/*
 * The step codec on its own (firmware/edge/step_codec.c): a period's rows (sampled or predicted) into
 * the core's measurement, the chain's sample, commands and telemetry of one robot to the wire, each
 * through an LCM encode/decode round trip (and at its channel's one size); the joint digest; robot
 * indices at the int8 extremes; a streamed target sample refused whole when one value is not finite.
 */
#include <float.h>

#include "edge_fixture.h"

#include "tvo/target.h"
#include "internal/barrier.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static uint8_t buffer[8192];

/* Robot r's sample with distinct values per robot and field, through an encode/decode round trip. */
static void distinct_sample(tvo_lcm_unicycle_sample_t *m, int8_t robot)
{
    ef_sample(m, 9, 1000, 7, robot);
    m->position_m[0] = 1.25 + robot;
    m->position_m[1] = -0.5 - robot;
    m->heading_rad = 0.125f * (float)(robot + 1);
    m->speed_mps = 0.75f - 0.25f * (float)robot;
    m->has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    const int n = tvo_lcm_unicycle_sample_t_encode(buffer, 0, (int)sizeof(buffer), m);
    TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_SAMPLE), n);
    tvo_lcm_unicycle_sample_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_unicycle_sample_t_decode(buffer, 0, n, &back));
    *m = back;
}

static tvo_lcm_unicycle_sample_t samples[TVO_MAX_ROBOTS];
static tvo_step_period_t period;

/* Every robot of `robots` sampled (distinct values). */
static void sampled_period(uint8_t robots)
{
    memset(&period, 0, sizeof(period));
    for (uint8_t r = 0; r < robots; ++r) {
        distinct_sample(&samples[r], (int8_t)r);
        period.sample[r] = &samples[r];
    }
}

static void test_measurement_takes_each_robots_sample_once(void)
{
    const uint8_t robots = TVO_MAX_ROBOTS >= 3 ? 3u : (uint8_t)TVO_MAX_ROBOTS;
    sampled_period(robots);
    tvo_measurement_t meas;
    memset(&meas, 0x5A, sizeof(meas));
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, robots, 0xFFFFFFF0u, &meas));
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFF0u, meas.stamp_tick);
    for (uint8_t r = 0; r < robots; ++r) {
        TEST_ASSERT_TRUE(meas.position_m[r][0] == (tvo_real_t)(1.25 + r));
        TEST_ASSERT_TRUE(meas.position_m[r][1] == (tvo_real_t)(-0.5 - r));
        TEST_ASSERT_TRUE(meas.heading_rad[r] == (tvo_real_t)(0.125f * (float)(r + 1)));
        TEST_ASSERT_TRUE(meas.speed_mps[r] == (tvo_real_t)(0.75f - 0.25f * (float)r));
    }
    /* Robots past the count are not read (zero). */
    if (robots < TVO_MAX_ROBOTS) {
        TEST_ASSERT_TRUE(meas.position_m[robots][0] == TVO_R(0.0) && meas.speed_mps[robots] == TVO_R(0.0));
    }
    TEST_ASSERT_EQUAL_UINT8(1u, meas.heading_valid);
    TEST_ASSERT_EQUAL_UINT8(1u, meas.speed_valid);
    /* One robot without a measured speed (or heading): the joint measurement has none; what it lacks is 0. */
    samples[robots - 1u].has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING;
    samples[robots - 1u].speed_mps = NAN;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, robots, 0u, &meas));
    TEST_ASSERT_EQUAL_UINT8(1u, meas.heading_valid);
    TEST_ASSERT_EQUAL_UINT8(0u, meas.speed_valid);
    TEST_ASSERT_TRUE(meas.speed_mps[robots - 1u] == TVO_R(0.0));
    samples[0].has = 0;
    samples[0].heading_rad = INFINITY;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, robots, 0u, &meas));
    TEST_ASSERT_EQUAL_UINT8(0u, meas.heading_valid);
    TEST_ASSERT_TRUE(meas.heading_rad[0] == TVO_R(0.0));
}

static void test_a_predicted_row_is_the_robots_predicted_state_with_heading_and_speed(void)
{
    if (TVO_MAX_ROBOTS < 2) {
        TEST_IGNORE_MESSAGE("a one-robot build predicts no other robot");
    }
    sampled_period(2u);
    samples[1].has = 0; /* the sampled robot lacks both: so does the joint measurement */
    period.sample[0] = NULL;
    period.predicted[0].position_m[0] = 3.5;
    period.predicted[0].position_m[1] = -4.25;
    period.predicted[0].heading_rad = 0.3;
    period.predicted[0].speed_mps = 0.2;
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, 2u, 5u, &meas));
    TEST_ASSERT_TRUE(meas.position_m[0][0] == (tvo_real_t)3.5 && meas.position_m[0][1] == (tvo_real_t)-4.25);
    TEST_ASSERT_TRUE(meas.heading_rad[0] == (tvo_real_t)0.3 && meas.speed_mps[0] == (tvo_real_t)0.2);
    TEST_ASSERT_EQUAL_UINT8(0u, meas.heading_valid);
    samples[1].has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING | TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, 2u, 5u, &meas));
    TEST_ASSERT_EQUAL_UINT8(1u, meas.heading_valid); /* a predicted row has both */
    TEST_ASSERT_EQUAL_UINT8(1u, meas.speed_valid);
}

static void test_measurement_robot_count_outside_the_build_and_nulls_are_refused(void)
{
    sampled_period(1u);
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_unicycle_measurement(&period, 0u, 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_unicycle_measurement(&period, (uint8_t)(TVO_MAX_ROBOTS + 1), 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_unicycle_measurement(&period, UINT8_MAX, 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_unicycle_measurement(NULL, 1u, 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_unicycle_measurement(&period, 1u, 0u, NULL));
    tvo_chain_measurement_t chain;
    tvo_lcm_chain_sample_t c;
    memset(&c, 0, sizeof(c));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_chain_measurement(NULL, 0u, &chain));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_chain_measurement(&c, 0u, NULL));
}

/* A finite wire double beyond the float32 core's range saturates to its largest value (the core then
 * refuses it as beyond the workspace, status 19); it never passes for an infinity (status 2). */
static void test_measurement_values_beyond_the_scalar_saturate(void)
{
    sampled_period(1u);
    samples[0].position_m[0] = 1e300;
    samples[0].position_m[1] = -1e300;
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, 1u, 0u, &meas));
#if TVO_USE_DOUBLE
    TEST_ASSERT_TRUE(meas.position_m[0][0] == 1e300 && meas.position_m[0][1] == -1e300);
#else
    TEST_ASSERT_TRUE(meas.position_m[0][0] == FLT_MAX && meas.position_m[0][1] == -FLT_MAX);
#endif
    samples[0].position_m[0] = (double)INFINITY;
    samples[0].position_m[1] = (double)NAN;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, 1u, 0u, &meas));
    TEST_ASSERT_TRUE(isinf(meas.position_m[0][0]) && meas.position_m[0][0] > TVO_R(0.0));
    TEST_ASSERT_TRUE(isnan(meas.position_m[0][1]));
}

static void test_a_samples_finiteness_is_judged_on_what_it_has(void)
{
    tvo_lcm_unicycle_sample_t m;
    distinct_sample(&m, 0);
    TEST_ASSERT_TRUE(tvo_step_unicycle_sample_finite(&m));
    m.position_m[1] = (double)NAN;
    TEST_ASSERT_FALSE(tvo_step_unicycle_sample_finite(&m));
    distinct_sample(&m, 0);
    m.heading_rad = INFINITY;
    TEST_ASSERT_FALSE(tvo_step_unicycle_sample_finite(&m));
    m.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED; /* the heading is not measured: not read */
    TEST_ASSERT_TRUE(tvo_step_unicycle_sample_finite(&m));
    m.speed_mps = -INFINITY;
    TEST_ASSERT_FALSE(tvo_step_unicycle_sample_finite(&m));
    TEST_ASSERT_FALSE(tvo_step_unicycle_sample_finite(NULL));
    /* Its state for a prediction: what it has, 0 for the rest. */
    distinct_sample(&m, 1);
    m.has = TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING;
    tvo_step_robot_state_t state;
    tvo_step_state_of(&m, &state);
    TEST_ASSERT_TRUE(state.position_m[0] == 2.25 && state.position_m[1] == -1.5);
    TEST_ASSERT_TRUE(state.heading_rad == (double)m.heading_rad && state.speed_mps == 0.0);
    TEST_ASSERT_EQUAL_INT64(7, state.sequence);
}

static void test_chain_measurement_reads_derivatives_only_when_the_sample_has_them(void)
{
    tvo_lcm_chain_sample_t c;
    memset(&c, 0, sizeof(c));
    c.position_m[0] = 1.5;
    c.position_m[1] = -2.5;
    c.output_rate_mps[0] = 0.25f;
    c.output_rate_mps[1] = -0.75f;
    c.output_accel_mps2[0] = 3.0f;
    c.output_accel_mps2[1] = -4.0f;
    c.has = TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES;
    const int n = tvo_lcm_chain_sample_t_encode(buffer, 0, (int)sizeof(buffer), &c);
    TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_CHAIN_SAMPLE), n);
    tvo_chain_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_chain_measurement(&c, 77u, &meas));
    TEST_ASSERT_EQUAL_UINT32(77u, meas.stamp_tick);
    for (int axis = 0; axis < 2; ++axis) {
        TEST_ASSERT_TRUE(meas.y.d[0][axis] == (tvo_real_t)c.position_m[axis]);
        TEST_ASSERT_TRUE(meas.y.d[1][axis] == (tvo_real_t)c.output_rate_mps[axis]);
#if TVO_MAX_RELATIVE_DEGREE >= 3
        TEST_ASSERT_TRUE(meas.y.d[2][axis] == (tvo_real_t)c.output_accel_mps2[axis]);
#endif
    }
    c.has = 0;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_chain_measurement(&c, 77u, &meas));
    for (int axis = 0; axis < 2; ++axis) {
        TEST_ASSERT_TRUE(meas.y.d[0][axis] != TVO_R(0.0));
        TEST_ASSERT_TRUE(meas.y.d[1][axis] == TVO_R(0.0));
    }
}

static void test_command_round_trip_carries_the_header_and_its_robots_row(void)
{
    tvo_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    for (int r = 0; r < TVO_MAX_ROBOTS; ++r) {
        cmd.speed_mps[r] = (tvo_real_t)(0.5 + r);
        cmd.turn_rate_radps[r] = (tvo_real_t)(-1.0 - r);
    }
    cmd.flags = TVO_FLAG_PREDICTED | TVO_FLAG_SPEED_MISMATCH;
    cmd.outcome = TVO_OUTCOME_STOPPED;
    cmd.reason = TVO_REASON_WATCHDOG;
    const tvo_step_stamp_t stamp = {EF_TWO_POW_60, INT32_MAX, -1, {TVO_NODE_OK, TVO_OK, TVO_REASON_WATCHDOG}};
    for (int32_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        tvo_lcm_unicycle_command_t msg;
        memset(&msg, 0x5A, sizeof(msg));
        tvo_step_unicycle_command(&cmd, &stamp, r, &msg);
        const int n = tvo_lcm_unicycle_command_t_encode(buffer, 0, (int)sizeof(buffer), &msg);
        TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_COMMAND), n);
        tvo_lcm_unicycle_command_t back;
        TEST_ASSERT_EQUAL_INT(n, tvo_lcm_unicycle_command_t_decode(buffer, 0, n, &back));
        TEST_ASSERT_EQUAL_INT64(EF_TWO_POW_60, back.header.utime);
        TEST_ASSERT_EQUAL_INT32(INT32_MAX, back.header.session_id);
        TEST_ASSERT_EQUAL_INT32(-1, back.header.measurement_sequence);
        TEST_ASSERT_EQUAL_INT(r, back.header.robot);
        EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG, back.header.status);
        TEST_ASSERT_EQUAL_HEX32(TVO_FLAG_PREDICTED | TVO_FLAG_SPEED_MISMATCH | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP,
                                (uint32_t)back.header.flags);
        TEST_ASSERT_TRUE(back.speed_mps == (float)cmd.speed_mps[r]);
        TEST_ASSERT_TRUE(back.turn_rate_radps == (float)cmd.turn_rate_radps[r]);
    }
    /* A robot the build does not have writes nothing (the ASan variant watches); NULLs, nothing. */
    tvo_lcm_unicycle_command_t msg;
    memset(&msg, 0x5A, sizeof(msg));
    const tvo_lcm_unicycle_command_t untouched = msg;
    tvo_step_unicycle_command(&cmd, &stamp, TVO_MAX_ROBOTS, &msg);
    tvo_step_unicycle_command(&cmd, &stamp, -1, &msg);
    tvo_step_unicycle_command(NULL, &stamp, 0, &msg);
    tvo_step_unicycle_command(&cmd, NULL, 0, &msg);
    tvo_step_unicycle_command(&cmd, &stamp, 0, NULL);
    TEST_ASSERT_EQUAL_MEMORY(&untouched, &msg, sizeof(msg));
}

static void test_chain_command_carries_u_of_its_robot(void)
{
    tvo_chain_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    for (int i = 0; i < TVO_MAX_OUTPUT_DIM; ++i) {
        cmd.u[i] = (tvo_real_t)(0.25 * (i + 1));
    }
    cmd.flags = TVO_FLAG_ACCEL_SATURATED;
    const tvo_step_stamp_t stamp = {123, 5, 6, {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE}};
    tvo_lcm_chain_command_t msg;
    tvo_step_chain_command(&cmd, &stamp, &msg);
    const int n = tvo_lcm_chain_command_t_encode(buffer, 0, (int)sizeof(buffer), &msg);
    TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_CHAIN_COMMAND), n);
    tvo_lcm_chain_command_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_chain_command_t_decode(buffer, 0, n, &back));
    TEST_ASSERT_TRUE(back.input[0] == 0.25f && back.input[1] == 0.5f);
    TEST_ASSERT_EQUAL_INT32(6, back.header.measurement_sequence);
    TEST_ASSERT_EQUAL_INT(0, back.header.robot);
    TEST_ASSERT_EQUAL_HEX32(TVO_FLAG_ACCEL_SATURATED, (uint32_t)back.header.flags);
    /* Its digest: the two inputs in the place of a speed and a turn rate. */
    const double u0 = 0.25, u1 = 0.5;
    TEST_ASSERT_TRUE(tvo_step_chain_digest(&cmd) == tvo_joint_digest(&u0, &u1, 1));
    TEST_ASSERT_TRUE(tvo_step_chain_digest(NULL) == 0u);
}

static void test_the_joint_digest_is_of_the_rows_the_wire_carries(void)
{
    tvo_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    double speed[TVO_MAX_ROBOTS], turn[TVO_MAX_ROBOTS];
    for (int r = 0; r < TVO_MAX_ROBOTS; ++r) {
        cmd.speed_mps[r] = (tvo_real_t)(0.1 * r + 0.3);
        cmd.turn_rate_radps[r] = (tvo_real_t)(-0.7 * r);
        speed[r] = (double)(float)cmd.speed_mps[r]; /* the wire's float32 values */
        turn[r] = (double)(float)cmd.turn_rate_radps[r];
    }
    for (uint8_t robots = 1u; robots <= TVO_MAX_ROBOTS; ++robots) {
        TEST_ASSERT_TRUE(tvo_step_unicycle_digest(&cmd, robots) == tvo_joint_digest(speed, turn, robots));
    }
    /* Rows past the count are not digested; every row is. */
    cmd.speed_mps[TVO_MAX_ROBOTS - 1] = TVO_R(9.0);
    if (TVO_MAX_ROBOTS > 1) {
        TEST_ASSERT_TRUE(tvo_step_unicycle_digest(&cmd, TVO_MAX_ROBOTS - 1u) ==
                         tvo_joint_digest(speed, turn, TVO_MAX_ROBOTS - 1));
    }
    TEST_ASSERT_TRUE(tvo_step_unicycle_digest(&cmd, TVO_MAX_ROBOTS) != tvo_joint_digest(speed, turn, TVO_MAX_ROBOTS));
    TEST_ASSERT_TRUE(tvo_step_unicycle_digest(&cmd, (uint8_t)(TVO_MAX_ROBOTS + 1)) == 0u);
    TEST_ASSERT_TRUE(tvo_step_unicycle_digest(NULL, 1u) == 0u);
}

/* A 2-robot unicycle session from the fixture START (optionally with one half-space) after its
 * first step, for the telemetry. */
static tvo_problem_t problem;
static tvo_controller_t ctl;

static void stepped_controller(int with_halfspace)
{
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    if (with_halfspace) {
        start.halfspace_count = 1;
        start.halfspace[0].robot = 1;
        start.halfspace[0].normal[1] = 1.0;
        start.halfspace[0].bound_m = 3.0;
    }
    tvo_problem_desc_t desc;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_problem(&start, &desc, &why));
    tvo_problem_culprit_t part;
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
    tvo_controller_config_t cfg;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_unicycle(&start, &cfg, &why));
    tvo_param_t bad = TVO_PARAM_NONE;
    const uint32_t epoch = 1000u;
    EF_ASSERT_STATUS(TVO_OK, tvo_controller_init(&ctl, &cfg, &problem.objective, epoch, &bad));
    memset(&period, 0, sizeof(period));
    for (int8_t r = 0; r < 2; ++r) {
        ef_sample(&samples[r], EF_SESSION_ID, 0, 0, r);
        period.sample[r] = &samples[r];
    }
    const uint32_t apply = epoch + (uint32_t)EF_PERIOD_US;
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, tvo_step_unicycle_measurement(&period, 2u, apply - (uint32_t)EF_DELAY_US, &meas));
    tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0), TVO_R(0.0), TVO_R(0.0), TVO_R(1.0)};
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, y, TVO_R(0.0)));
    tvo_command_t cmd;
    EF_ASSERT_STATUS(TVO_OK, tvo_controller_step(&ctl, &meas, apply, &cmd));
    TEST_ASSERT_EQUAL_INT(TVO_OUTCOME_APPLIED, cmd.outcome);
}

static void test_telemetry_round_trip_carries_a_robots_rows_of_the_last_step(void)
{
    if (TVO_MAX_ROBOTS < 2) {
        TEST_IGNORE_MESSAGE("a one-robot build has no 2-robot session");
    }
    stepped_controller(1);
    for (uint8_t r = 0; r < 2u; ++r) {
        tvo_lcm_telemetry_t tel;
        memset(&tel, 0, sizeof(tel));
        const tvo_step_stamp_t stamp = {4242, 17, 99, {TVO_NODE_OK, TVO_OK, TVO_REASON_STALE}};
        tvo_step_header(&stamp, tvo_step_wire_flags(0u, TVO_OUTCOME_HELD), r, &tel.header);
        tvo_step_telemetry_to_lcm(&ctl.telemetry, r, ctl.internal.speed_state_mps, &problem, &tel);
        const int n = tvo_lcm_telemetry_t_encode(buffer, 0, (int)sizeof(buffer), &tel);
        TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_TELEMETRY), n);
        tvo_lcm_telemetry_t back;
        TEST_ASSERT_EQUAL_INT(n, tvo_lcm_telemetry_t_decode(buffer, 0, n, &back));
        TEST_ASSERT_EQUAL_INT64(4242, back.header.utime);
        TEST_ASSERT_EQUAL_INT32(17, back.header.session_id);
        TEST_ASSERT_EQUAL_INT32(99, back.header.measurement_sequence);
        TEST_ASSERT_EQUAL_INT(r, back.header.robot);
        EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE, back.header.status);
        TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, (uint32_t)back.header.flags);
        TEST_ASSERT_EQUAL_INT64((int64_t)llround((double)ctl.telemetry.objective_time_s * 1e6), back.objective_time_us);
        TEST_ASSERT_TRUE(back.objective_time_us > 0);
        for (int axis = 0; axis < 2; ++axis) {
            const int i = 2 * r + axis;
            TEST_ASSERT_TRUE(back.gradient[axis] == (float)ctl.telemetry.gradient[i]);
            TEST_ASSERT_TRUE(back.gradient_rate[axis] == (float)ctl.telemetry.gradient_rate[i]);
            TEST_ASSERT_TRUE(back.output_m[axis] == (double)ctl.telemetry.output_m[i]);
            TEST_ASSERT_TRUE(back.output_rate_mps[axis] == (float)ctl.telemetry.output_rate_mps[i]);
            TEST_ASSERT_TRUE(back.output_accel_mps2[axis] == (float)ctl.telemetry.output_accel_mps2[i]);
        }
        TEST_ASSERT_TRUE(back.output_m[1] == (double)r); /* robot r stands at y = r */
        TEST_ASSERT_TRUE(back.speed_state_mps == (float)ctl.internal.speed_state_mps[r]);
        TEST_ASSERT_TRUE(back.speed_state_mps != 0.0f); /* the first step accelerated */
        /* The barrier's schedule at the law's time, with the slack the rule chose. */
        tvo_real_t c = TVO_R(0.0);
        tvo_real_t slack = TVO_R(0.0);
        tvo_real_t delta = TVO_R(0.0);
        EF_ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&problem.barrier, ctl.telemetry.objective_time_s, &c, &slack, &delta));
        TEST_ASSERT_TRUE(back.barrier_c == (float)c && back.barrier_c > 0.0f);
        TEST_ASSERT_TRUE(back.barrier_slack == (float)slack);
    }
    /* Without inequalities: no barrier figures. */
    stepped_controller(0);
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    tvo_step_telemetry_to_lcm(&ctl.telemetry, 1u, ctl.internal.speed_state_mps, &problem, &tel);
    TEST_ASSERT_TRUE(tel.barrier_c == 0.0f && tel.barrier_slack == 0.0f);
    TEST_ASSERT_TRUE(tel.output_m[1] == 1.0);
}

/* ------------------------------------------------------------------------------------------------
 * Streamed targets
 * --------------------------------------------------------------------------------------------- */

/* Two robots with streamed targets (robot 1's kind may be overridden). */
static void streamed_problem(int32_t robot1_kind)
{
    tvo_lcm_session_t start;
    ef_start(&start, EF_SESSION_ID, TVO_LCM_SESSION_T_CLOCK_PLANT, 2);
    start.robot[0].target.kind = TVO_LCM_PATH_T_KIND_STREAMED;
    start.robot[1].target.kind = robot1_kind;
    tvo_problem_desc_t desc;
    tvo_session_reject_t why;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_problem(&start, &desc, &why));
    tvo_problem_culprit_t part;
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
}

static void target_sample(tvo_lcm_target_t *t, int8_t robot)
{
    memset(t, 0, sizeof(*t));
    t->header.utime = 1000;
    t->header.session_id = EF_SESSION_ID;
    t->header.robot = robot;
    for (int axis = 0; axis < 2; ++axis) {
        t->position_m[axis] = 1.0 + robot + 0.5 * axis;
        t->velocity_mps[axis] = 0.1f * (float)(robot + 1);
        t->acceleration_mps2[axis] = -0.2f;
        t->jerk_mps3[axis] = 0.05f;
    }
}

static void test_a_target_sample_feeds_its_robots_stream_only(void)
{
    if (TVO_MAX_ROBOTS < 2) {
        TEST_IGNORE_MESSAGE("a one-robot build has no 2-robot session");
    }
    streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
    for (int8_t r = 1; r >= 0; --r) {
        tvo_lcm_target_t t;
        target_sample(&t, r);
        const int n = tvo_lcm_target_t_encode(buffer, 0, (int)sizeof(buffer), &t);
        TEST_ASSERT_EQUAL_INT((int)tvo_node_channel_message_bytes(TVO_NODE_CH_TARGET), n);
        TEST_ASSERT_EQUAL_INT(n, tvo_lcm_target_t_decode(buffer, 0, n, &t));
        EF_ASSERT_STATUS(TVO_OK, tvo_step_target_from_lcm_carried(&t, 2u, 5000u + (uint64_t)r, 0.0, &problem));
        const tvo_target_t *target = tvo_problem_target(&problem, (uint8_t)r);
        TEST_ASSERT_NOT_NULL(target);
        TEST_ASSERT_EQUAL_UINT8(1u, target->u.streamed.has_sample);
        TEST_ASSERT_EQUAL_UINT64(5000u + (uint64_t)r, target->u.streamed.stamp_ticks);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[0][1] == (tvo_real_t)t.position_m[1]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[1][0] == (tvo_real_t)t.velocity_mps[0]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[2][0] == (tvo_real_t)t.acceleration_mps2[0]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[3][1] == (tvo_real_t)t.jerk_mps3[1]);
        if (r == 1) {
            TEST_ASSERT_EQUAL_UINT8(0u, tvo_problem_target(&problem, 0u)->u.streamed.has_sample); /* not robot 0's */
        }
    }
}

static void test_non_finite_target_value_is_refused_before_anything_changes(void)
{
    const double bad_values[] = {(double)NAN, (double)INFINITY, -(double)INFINITY, 1e300};
    for (int field = 0; field < 4; ++field) {
        for (size_t v = 0; v < sizeof(bad_values) / sizeof(bad_values[0]); ++v) {
            if (field > 0 && bad_values[v] == 1e300) {
                continue; /* a float field cannot hold it */
            }
            streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
            tvo_lcm_target_t t;
            target_sample(&t, 0);
            EF_ASSERT_STATUS(TVO_OK, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, 0.0, &problem)); /* a first sample */
            tvo_problem_t before;
            memcpy(&before, &problem, sizeof(problem));
            if (field == 0) {
                t.position_m[1] = bad_values[v];
            } else {
                float *slot = field == 1 ? &t.velocity_mps[0] : field == 2 ? &t.acceleration_mps2[1] : &t.jerk_mps3[0];
                *slot = (float)bad_values[v];
            }
            /* A finite 1e300 is a position beyond the workspace (PARAM), not a non-finite one, in both builds. */
            EF_ASSERT_STATUS(bad_values[v] == 1e300 ? TVO_ERR_PARAM : TVO_ERR_NOT_FINITE,
                             tvo_step_target_from_lcm_carried(&t, 2u, 6000u, 0.0, &problem));
            TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
        }
    }
}

static void test_target_sample_for_a_non_streamed_target_or_another_robot_is_refused(void)
{
    streamed_problem(TVO_LCM_PATH_T_KIND_POLYNOMIAL);
    tvo_lcm_target_t t;
    target_sample(&t, 1);
    tvo_problem_t before;
    memcpy(&before, &problem, sizeof(problem));
    EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, 0.0, &problem));
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));

    streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
    memcpy(&before, &problem, sizeof(problem));
    const int8_t bad[] = {INT8_MIN, -1, 2, INT8_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        t.header.robot = bad[i];
        EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, 0.0, &problem));
    }
    t.header.robot = 0;
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION,
                     tvo_step_target_from_lcm_carried(&t, (uint8_t)(TVO_MAX_ROBOTS + 1), 5000u, 0.0, &problem));
    const double carries[] = {-1e-9, 1.0 + 1e-9, (double)NAN};
    for (size_t i = 0; i < sizeof(carries) / sizeof(carries[0]); ++i) {
        EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, carries[i], &problem));
    }
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_target_from_lcm_carried(NULL, 2u, 5000u, 0.0, &problem));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, 0.0, NULL));
    tvo_problem_t empty;
    memset(&empty, 0, sizeof(empty));
    EF_ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_step_target_from_lcm_carried(&t, 2u, 5000u, 0.0, &empty));
}

/* The wire's statuses, written here from lcm_types/README.md's table, not from the codec's: every core
 * reason, core error and edge status a command can carry, and which vocabulary wins. */
static void test_wire_status_of_each_reason_error_and_edge_status(void)
{
    static const struct {
        tvo_reason_t reason;
        int32_t wire;
    } reasons[] = {
        {TVO_REASON_NONE, TVO_LCM_COMMAND_HEADER_T_STATUS_OK},
        {TVO_REASON_NOT_FINITE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE},
        {TVO_REASON_IMPLAUSIBLE_MEASUREMENT, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT},
        {TVO_REASON_STALE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE},
        {TVO_REASON_FUTURE_STAMP, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_FUTURE_STAMP},
        {TVO_REASON_STAMP_NOT_NEWER, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_REASON_MISSING_FIELD, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_MISSING_FIELD},
        {TVO_REASON_SOURCE_NOT_LINKED, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_INITIALIZED},
        {TVO_REASON_TARGET_NOT_READY, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_TARGET_NOT_READY},
        {TVO_REASON_NUMERIC, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NUMERIC},
        {TVO_REASON_NOT_POSITIVE_DEFINITE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_POSITIVE_DEFINITE},
        {TVO_REASON_NO_MEASUREMENT, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT},
        {TVO_REASON_WATCHDOG, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG},
        {TVO_REASON_SPEED_MISMATCH, TVO_LCM_COMMAND_HEADER_T_STATUS_OK}, /* taken: the stop is in the flags */
        {TVO_REASON_STOP_REQUESTED, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG},
        {TVO_REASON_REFUSED, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT},
    };
    TEST_ASSERT_EQUAL_INT(TVO_REASON_COUNT, (int)(sizeof(reasons) / sizeof(reasons[0])));
    for (size_t i = 0; i < sizeof(reasons) / sizeof(reasons[0]); ++i) {
        const tvo_step_why_t why = {TVO_NODE_OK, TVO_OK, reasons[i].reason};
        EF_ASSERT_STATUS(reasons[i].wire, tvo_step_wire_status(&why));
    }
    static const struct {
        tvo_status_t error;
        int32_t wire;
    } errors[] = {
        {TVO_OK, TVO_LCM_COMMAND_HEADER_T_STATUS_OK},
        {TVO_ERR_NULL, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NULL},
        {TVO_ERR_NOT_FINITE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE},
        {TVO_ERR_DIMENSION, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION},
        {TVO_ERR_PARAM, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM},
        {TVO_ERR_CAPACITY, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_CAPACITY},
        {TVO_ERR_NOT_INITIALIZED, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_INITIALIZED},
        {TVO_ERR_TICK_NOT_ADVANCING, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_BEFORE_EPOCH, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_NOT_POSITIVE_DEFINITE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_POSITIVE_DEFINITE},
        {TVO_ERR_NUMERIC, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NUMERIC},
    };
    TEST_ASSERT_EQUAL_INT(TVO_STATUS_COUNT, (int)(sizeof(errors) / sizeof(errors[0])));
    for (size_t i = 0; i < sizeof(errors) / sizeof(errors[0]); ++i) {
        const tvo_step_why_t why = {TVO_NODE_OK, errors[i].error, TVO_REASON_WATCHDOG}; /* the error wins */
        EF_ASSERT_STATUS(i == 0 ? TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_WATCHDOG : errors[i].wire, tvo_step_wire_status(&why));
    }
    static const struct {
        tvo_node_status_t node;
        int32_t wire;
    } edge[] = {
        {TVO_NODE_OK, TVO_LCM_COMMAND_HEADER_T_STATUS_OK},
        {TVO_NODE_WRONG_ROBOT, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION},
        {TVO_NODE_IMPLAUSIBLE_STAMP, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP},
        {TVO_NODE_NOT_LATER_PERIOD, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_NODE_STALE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE},
        {TVO_NODE_MISSING_DERIVATIVES, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_MISSING_FIELD},
        {TVO_NODE_SESSION_CONFLICT, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_SESSION_CONFLICT},
        {TVO_NODE_NO_SESSION, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_SESSION},
        {TVO_NODE_UNKNOWN_ACTION, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM},
        {TVO_NODE_ROBOT_UNHEARD, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT},
        {TVO_NODE_WRONG_PLANT, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM},
        {TVO_NODE_NOT_FINITE, TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE},
    };
    TEST_ASSERT_EQUAL_INT(TVO_NODE_STATUS_COUNT, (int)(sizeof(edge) / sizeof(edge[0])));
    for (size_t i = 1; i < sizeof(edge) / sizeof(edge[0]); ++i) {
        const tvo_step_why_t why = {edge[i].node, TVO_ERR_NUMERIC, TVO_REASON_STALE}; /* the edge's wins */
        EF_ASSERT_STATUS(edge[i].wire, tvo_step_wire_status(&why));
    }
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NULL, tvo_step_wire_status(NULL));
}

/* HOLDING and SAFE_STOP say the outcome, and only it; the core's flags pass unchanged. */
static void test_wire_flags_say_the_outcome(void)
{
    const uint32_t shaping = TVO_FLAG_OMEGA_SATURATED | TVO_FLAG_PREDICTED | TVO_FLAG_SPEED_MISMATCH;
    TEST_ASSERT_EQUAL_HEX32(shaping, tvo_step_wire_flags(shaping, TVO_OUTCOME_APPLIED));
    TEST_ASSERT_EQUAL_HEX32(shaping | TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING, tvo_step_wire_flags(shaping, TVO_OUTCOME_HELD));
    TEST_ASSERT_EQUAL_HEX32(shaping | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP,
                            tvo_step_wire_flags(shaping, TVO_OUTCOME_STOPPED));
    /* Stray outcome bits in the core's flags do not survive an applied outcome. */
    TEST_ASSERT_EQUAL_HEX32(0u, tvo_step_wire_flags(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP,
                                                    TVO_OUTCOME_APPLIED));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_measurement_takes_each_robots_sample_once);
    RUN_TEST(test_a_predicted_row_is_the_robots_predicted_state_with_heading_and_speed);
    RUN_TEST(test_measurement_robot_count_outside_the_build_and_nulls_are_refused);
    RUN_TEST(test_measurement_values_beyond_the_scalar_saturate);
    RUN_TEST(test_a_samples_finiteness_is_judged_on_what_it_has);
    RUN_TEST(test_chain_measurement_reads_derivatives_only_when_the_sample_has_them);
    RUN_TEST(test_wire_status_of_each_reason_error_and_edge_status);
    RUN_TEST(test_wire_flags_say_the_outcome);
    RUN_TEST(test_command_round_trip_carries_the_header_and_its_robots_row);
    RUN_TEST(test_chain_command_carries_u_of_its_robot);
    RUN_TEST(test_the_joint_digest_is_of_the_rows_the_wire_carries);
    RUN_TEST(test_telemetry_round_trip_carries_a_robots_rows_of_the_last_step);
    RUN_TEST(test_a_target_sample_feeds_its_robots_stream_only);
    RUN_TEST(test_non_finite_target_value_is_refused_before_anything_changes);
    RUN_TEST(test_target_sample_for_a_non_streamed_target_or_another_robot_is_refused);
    return UNITY_END();
}
