/*
 * The step codec on its own (firmware/edge/step_codec.c): measurements (unicycle and chain) from the
 * wire, commands and telemetry to the wire, each through an LCM encode/decode round trip; robot
 * counts at the int32 extremes; a streamed target sample refused whole (before any robot's target
 * changes) when one value is not finite.
 */
#include "edge_fixture.h"

#include "tvo/target.h"
#include "internal/barrier.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static uint8_t buffer[8192];

/* A wire measurement with distinct values per robot and field. */
static void distinct_measurement(tvo_lcm_measurement_t *m, int32_t robots)
{
    ef_measurement(m, 9, 1000, 7, robots);
    for (int32_t r = 0; r < TVO_LCM_MEASUREMENT_T_MAX_ROBOTS; ++r) {
        m->position_m[r][0] = 1.25 + r;
        m->position_m[r][1] = -0.5 - r;
        m->heading_rad[r] = 0.125 * (r + 1);
        m->speed_mps[r] = 0.75 - 0.25 * r;
        m->output_rate_mps[r][0] = 0.5 * r + 0.1;
        m->output_rate_mps[r][1] = -0.5 * r - 0.2;
        m->output_accel_mps2[r][0] = 2.0 + r;
        m->output_accel_mps2[r][1] = -3.0 - r;
    }
    m->speed_valid = 1;
}

/* Encodes and decodes a measurement: what the node sees of what the plant sent. */
static void through_the_wire(tvo_lcm_measurement_t *m)
{
    const int n = tvo_lcm_measurement_t_encode(buffer, 0, (int)sizeof(buffer), m);
    TEST_ASSERT_TRUE(n > 0);
    tvo_lcm_measurement_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_measurement_t_decode(buffer, 0, n, &back));
    *m = back;
}

/* The node's two steps from a measurement_t: the joint measurement it carries, then the core's. */
static tvo_step_measurement_t joint;
static tvo_status_t unicycle_from_lcm(const tvo_lcm_measurement_t *wire, uint8_t robots, uint32_t tick, tvo_measurement_t *meas)
{
    tvo_step_measurement_from_wire(wire, &joint);
    return tvo_step_unicycle_measurement(wire != NULL ? &joint : NULL, robots, tick, meas);
}
static tvo_status_t chain_from_lcm(const tvo_lcm_measurement_t *wire, uint8_t robots, uint32_t tick,
                                   tvo_chain_measurement_t *meas)
{
    tvo_step_measurement_from_wire(wire, &joint);
    return tvo_step_chain_measurement(wire != NULL ? &joint : NULL, robots, tick, meas);
}

static void test_measurement_round_trip_keeps_every_robot_and_field(void)
{
    tvo_lcm_measurement_t wire;
    distinct_measurement(&wire, 3);
    through_the_wire(&wire);
    tvo_measurement_t meas;
    memset(&meas, 0x5A, sizeof(meas));
    EF_ASSERT_STATUS(TVO_OK, unicycle_from_lcm(&wire, 3u, 0xFFFFFFF0u, &meas));
    TEST_ASSERT_EQUAL_HEX32(0xFFFFFFF0u, meas.stamp_tick);
    for (int r = 0; r < 3; ++r) {
        TEST_ASSERT_TRUE(meas.position_m[r][0] == (tvo_real_t)(1.25 + r));
        TEST_ASSERT_TRUE(meas.position_m[r][1] == (tvo_real_t)(-0.5 - r));
        TEST_ASSERT_TRUE(meas.heading_rad[r] == (tvo_real_t)(0.125 * (r + 1)));
        TEST_ASSERT_TRUE(meas.speed_mps[r] == (tvo_real_t)(0.75 - 0.25 * r));
    }
    /* Robots past the count are not read (zero, not the wire's values). */
    TEST_ASSERT_TRUE(meas.position_m[3][0] == TVO_R(0.0) && meas.speed_mps[3] == TVO_R(0.0));
    TEST_ASSERT_EQUAL_UINT8(1u, meas.heading_valid);
    TEST_ASSERT_EQUAL_UINT8(1u, meas.speed_valid);
    /* A boolean is 1 for any non-zero byte on the wire. */
    wire.heading_valid = -7;
    wire.speed_valid = 0;
    EF_ASSERT_STATUS(TVO_OK, unicycle_from_lcm(&wire, 3u, 0u, &meas));
    TEST_ASSERT_EQUAL_UINT8(1u, meas.heading_valid);
    TEST_ASSERT_EQUAL_UINT8(0u, meas.speed_valid);
}

static void test_a_robot_count_the_message_cannot_carry_becomes_minus_one(void)
{
    const int32_t bad[] = {INT32_MIN, -3, -1, TVO_WIRE_SESSION_ROBOTS + 1, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        tvo_lcm_measurement_t wire;
        distinct_measurement(&wire, TVO_WIRE_SESSION_ROBOTS);
        wire.robot_count = bad[i];
        tvo_step_measurement_t out;
        memset(&out, 0x5A, sizeof(out));
        tvo_step_measurement_from_wire(&wire, &out);
        TEST_ASSERT_EQUAL_INT32(-1, out.robot_count);
        TEST_ASSERT_TRUE(out.robot[0].position_m[0] == 0.0 && out.robot[0].heading_rad == 0.0); /* none copied */
        TEST_ASSERT_EQUAL_INT64(wire.sequence, out.sequence);
    }
    tvo_lcm_measurement_t wire;
    distinct_measurement(&wire, TVO_WIRE_SESSION_ROBOTS);
    tvo_step_measurement_t out;
    tvo_step_measurement_from_wire(&wire, &out);
    TEST_ASSERT_EQUAL_INT32(TVO_WIRE_SESSION_ROBOTS, out.robot_count);
    TEST_ASSERT_TRUE(out.robot[TVO_WIRE_SESSION_ROBOTS - 1].position_m[0] == wire.position_m[TVO_WIRE_SESSION_ROBOTS - 1][0]);
}

static void test_measurement_robot_count_must_match_the_session(void)
{
    const int32_t bad[] = {INT32_MIN, -1, 0, 2, 4, TVO_MAX_ROBOTS + 1, INT32_MAX}; /* the session has 3 */
    tvo_measurement_t meas;
    tvo_chain_measurement_t chain;
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        tvo_lcm_measurement_t wire;
        distinct_measurement(&wire, 3);
        wire.robot_count = bad[i];
        EF_ASSERT_STATUS(TVO_ERR_DIMENSION, unicycle_from_lcm(&wire, 3u, 0u, &meas));
        EF_ASSERT_STATUS(TVO_ERR_DIMENSION, chain_from_lcm(&wire, 3u, 0u, &chain));
    }
    /* A session count past the core's: refused even when the message agrees. */
    tvo_lcm_measurement_t wire;
    distinct_measurement(&wire, TVO_MAX_ROBOTS + 1);
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION,
                     unicycle_from_lcm(&wire, (uint8_t)(TVO_MAX_ROBOTS + 1), 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION,
                     chain_from_lcm(&wire, (uint8_t)(TVO_MAX_ROBOTS + 1), 0u, &chain));
    EF_ASSERT_STATUS(TVO_ERR_NULL, unicycle_from_lcm(NULL, 1u, 0u, &meas));
    EF_ASSERT_STATUS(TVO_ERR_NULL, unicycle_from_lcm(&wire, 1u, 0u, NULL));
    EF_ASSERT_STATUS(TVO_ERR_NULL, chain_from_lcm(NULL, 1u, 0u, &chain));
    EF_ASSERT_STATUS(TVO_ERR_NULL, chain_from_lcm(&wire, 1u, 0u, NULL));
}

static void test_measurement_values_beyond_the_scalar_become_infinite(void)
{
    tvo_lcm_measurement_t wire;
    distinct_measurement(&wire, 1);
    wire.position_m[0][0] = 1e300;
    wire.heading_rad[0] = -1e300;
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, unicycle_from_lcm(&wire, 1u, 0u, &meas));
#if TVO_USE_DOUBLE
    TEST_ASSERT_TRUE(meas.position_m[0][0] == 1e300 && meas.heading_rad[0] == -1e300);
#else
    TEST_ASSERT_TRUE(isinf(meas.position_m[0][0]) && meas.position_m[0][0] > TVO_R(0.0));
    TEST_ASSERT_TRUE(isinf(meas.heading_rad[0]) && meas.heading_rad[0] < TVO_R(0.0));
#endif
}

static void test_chain_measurement_reads_derivatives_only_when_valid(void)
{
    tvo_lcm_measurement_t wire;
    distinct_measurement(&wire, 2);
    wire.derivatives_valid = 1;
    through_the_wire(&wire);
    tvo_chain_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, chain_from_lcm(&wire, 2u, 77u, &meas));
    TEST_ASSERT_EQUAL_UINT32(77u, meas.stamp_tick);
    for (int r = 0; r < 2; ++r) {
        for (int axis = 0; axis < 2; ++axis) {
            const int i = 2 * r + axis;
            TEST_ASSERT_TRUE(meas.y.d[0][i] == (tvo_real_t)wire.position_m[r][axis]);
            TEST_ASSERT_TRUE(meas.y.d[1][i] == (tvo_real_t)wire.output_rate_mps[r][axis]);
#if TVO_MAX_RELATIVE_DEGREE >= 3
            TEST_ASSERT_TRUE(meas.y.d[2][i] == (tvo_real_t)wire.output_accel_mps2[r][axis]);
#endif
        }
    }
    wire.derivatives_valid = 0;
    EF_ASSERT_STATUS(TVO_OK, chain_from_lcm(&wire, 2u, 77u, &meas));
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(meas.y.d[0][i] != TVO_R(0.0));
        TEST_ASSERT_TRUE(meas.y.d[1][i] == TVO_R(0.0));
    }
}

static void test_command_round_trip_carries_the_stamp_and_each_robot(void)
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
    const tvo_step_stamp_t stamp = {EF_TWO_POW_60, INT64_MIN, -1, {TVO_NODE_OK, TVO_OK, TVO_REASON_WATCHDOG}, 2u};
    tvo_lcm_command_t msg;
    memset(&msg, 0x5A, sizeof(msg));
    tvo_step_command_to_lcm(&cmd, &stamp, &msg);
    const int n = tvo_lcm_command_t_encode(buffer, 0, (int)sizeof(buffer), &msg);
    TEST_ASSERT_TRUE(n > 0);
    tvo_lcm_command_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_command_t_decode(buffer, 0, n, &back));
    TEST_ASSERT_EQUAL_INT64(EF_TWO_POW_60, back.utime);
    TEST_ASSERT_EQUAL_INT64(INT64_MIN, back.session_id);
    TEST_ASSERT_EQUAL_INT64(-1, back.measurement_sequence);
    TEST_ASSERT_EQUAL_INT32(2, back.robot_count);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG, back.status);
    TEST_ASSERT_EQUAL_HEX32(TVO_FLAG_PREDICTED | TVO_FLAG_SPEED_MISMATCH | TVO_LCM_COMMAND_T_FLAG_SAFE_STOP,
                            (uint32_t)back.flags);
    for (int r = 0; r < 2; ++r) {
        TEST_ASSERT_TRUE(back.speed_mps[r] == (double)cmd.speed_mps[r]);
        TEST_ASSERT_TRUE(back.turn_rate_radps[r] == (double)cmd.turn_rate_radps[r]);
    }
    for (int r = 2; r < TVO_MAX_ROBOTS; ++r) {
        TEST_ASSERT_TRUE(back.speed_mps[r] == 0.0 && back.turn_rate_radps[r] == 0.0);
    }
    for (int i = 0; i < 8; ++i) {
        TEST_ASSERT_TRUE(back.input[i] == 0.0);
    }
    /* A robot count past the arrays writes nothing out of bounds (ASan variant watches). */
    const tvo_step_stamp_t wide = {0, 0, 0, {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE}, UINT8_MAX};
    tvo_step_command_to_lcm(&cmd, &wide, &msg);
    TEST_ASSERT_TRUE(msg.speed_mps[TVO_MAX_ROBOTS - 1] == (double)cmd.speed_mps[TVO_MAX_ROBOTS - 1]);
    tvo_step_command_to_lcm(NULL, &stamp, &msg); /* NULLs: nothing, no crash */
    tvo_step_command_to_lcm(&cmd, NULL, &msg);
    tvo_step_command_to_lcm(&cmd, &stamp, NULL);
}

static void test_chain_command_carries_u_per_output(void)
{
    tvo_chain_command_t cmd;
    memset(&cmd, 0, sizeof(cmd));
    for (int i = 0; i < TVO_MAX_OUTPUT_DIM; ++i) {
        cmd.u[i] = (tvo_real_t)(0.25 * (i + 1));
    }
    cmd.flags = TVO_FLAG_ACCEL_SATURATED;
    const tvo_step_stamp_t stamp = {123, 5, 6, {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE}, 1u};
    tvo_lcm_command_t msg;
    tvo_step_chain_command_to_lcm(&cmd, &stamp, &msg);
    const int n = tvo_lcm_command_t_encode(buffer, 0, (int)sizeof(buffer), &msg);
    tvo_lcm_command_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_command_t_decode(buffer, 0, n, &back));
    TEST_ASSERT_TRUE(back.input[0] == 0.25 && back.input[1] == 0.5);
    for (int i = 2; i < 8; ++i) {
        TEST_ASSERT_TRUE(back.input[i] == 0.0); /* one robot: two outputs */
    }
    TEST_ASSERT_EQUAL_INT64(6, back.measurement_sequence);
    TEST_ASSERT_EQUAL_HEX32(TVO_FLAG_ACCEL_SATURATED, (uint32_t)back.flags);
    const tvo_step_stamp_t wide = {0, 0, 0, {TVO_NODE_OK, TVO_OK, TVO_REASON_NONE}, UINT8_MAX};
    tvo_step_chain_command_to_lcm(&cmd, &wide, &msg);
    TEST_ASSERT_TRUE(msg.input[TVO_MAX_OUTPUT_DIM - 1] == (double)cmd.u[TVO_MAX_OUTPUT_DIM - 1]);
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
    uint8_t part = 0;
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
    tvo_controller_config_t cfg;
    EF_ASSERT_STATUS(TVO_OK, tvo_session_decode_unicycle(&start, &cfg, &why));
    tvo_param_t bad = TVO_PARAM_NONE;
    const uint32_t epoch = 1000u;
    EF_ASSERT_STATUS(TVO_OK, tvo_controller_init(&ctl, &cfg, &problem.objective, epoch, &bad));
    tvo_lcm_measurement_t wire;
    ef_measurement(&wire, EF_SESSION_ID, 0, 0, 2);
    const uint32_t apply = epoch + (uint32_t)EF_PERIOD_US;
    tvo_measurement_t meas;
    EF_ASSERT_STATUS(TVO_OK, unicycle_from_lcm(&wire, 2u, apply - (uint32_t)EF_DELAY_US, &meas));
    tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0), TVO_R(0.0), TVO_R(0.0), TVO_R(1.0)};
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, y, TVO_R(0.0)));
    tvo_command_t cmd;
    EF_ASSERT_STATUS(TVO_OK, tvo_controller_step(&ctl, &meas, apply, &cmd));
    TEST_ASSERT_EQUAL_INT(TVO_OUTCOME_APPLIED, cmd.outcome);
}

static void test_telemetry_round_trip_carries_the_controllers_last_step(void)
{
    stepped_controller(1);
    tvo_lcm_telemetry_t tel;
    memset(&tel, 0, sizeof(tel));
    tvo_step_telemetry_to_lcm(&ctl.telemetry, ctl.cfg.robot_count, ctl.internal.speed_state_mps, &problem, &tel);
    const tvo_step_stamp_t stamp = {4242, 17, 99, {TVO_NODE_OK, TVO_OK, TVO_REASON_STALE}, 2u};
    tvo_step_telemetry_stamp(&stamp, tvo_step_wire_flags(0u, TVO_OUTCOME_HELD), &tel);
    tel.counters.accepted = 5;
    tel.counters.refused[TVO_LCM_COMMAND_T_STATUS_ERR_STALE] = 2;
    const int n = tvo_lcm_telemetry_t_encode(buffer, 0, (int)sizeof(buffer), &tel);
    TEST_ASSERT_TRUE(n > 0 && n <= TVO_NODE_BUFFER_BYTES);
    tvo_lcm_telemetry_t back;
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_telemetry_t_decode(buffer, 0, n, &back));
    TEST_ASSERT_EQUAL_INT64(4242, back.utime);
    TEST_ASSERT_EQUAL_INT64(17, back.session_id);
    TEST_ASSERT_EQUAL_INT64(99, back.measurement_sequence);
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_T_STATUS_ERR_STALE, back.status);
    TEST_ASSERT_EQUAL_HEX32(TVO_LCM_COMMAND_T_FLAG_HOLDING, (uint32_t)back.flags);
    TEST_ASSERT_EQUAL_INT32(4, back.dim);
    TEST_ASSERT_TRUE(back.objective_time_s == (double)ctl.telemetry.objective_time_s);
    for (int i = 0; i < 4; ++i) {
        TEST_ASSERT_TRUE(back.gradient[i] == (double)ctl.telemetry.gradient[i]);
        TEST_ASSERT_TRUE(back.gradient_rate[i] == (double)ctl.telemetry.gradient_rate[i]);
        TEST_ASSERT_TRUE(back.output_m[i] == (double)ctl.telemetry.output_m[i]);
        TEST_ASSERT_TRUE(back.output_rate_mps[i] == (double)ctl.telemetry.output_rate_mps[i]);
        TEST_ASSERT_TRUE(back.output_accel_mps2[i] == (double)ctl.telemetry.output_accel_mps2[i]);
    }
    TEST_ASSERT_TRUE(back.output_m[3] == 1.0); /* robot 1 stands at y = 1 */
    for (int r = 0; r < 2; ++r) {
        TEST_ASSERT_TRUE(back.speed_state_mps[r] == (double)ctl.internal.speed_state_mps[r]);
        TEST_ASSERT_TRUE(back.speed_state_mps[r] != 0.0); /* the first step accelerated */
    }
    /* The barrier's schedule at the law's time, with the slack the rule chose. */
    tvo_real_t c = TVO_R(0.0);
    tvo_real_t slack = TVO_R(0.0);
    tvo_real_t delta = TVO_R(0.0);
    EF_ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&problem.barrier, ctl.telemetry.objective_time_s, &c, &slack, &delta));
    TEST_ASSERT_TRUE(back.barrier_c == (double)c && back.barrier_c > 0.0);
    TEST_ASSERT_TRUE(back.barrier_slack == (double)slack);
    TEST_ASSERT_EQUAL_INT32(5, back.counters.accepted);
    TEST_ASSERT_EQUAL_INT32(2, back.counters.refused[TVO_LCM_COMMAND_T_STATUS_ERR_STALE]);

    /* Without inequalities: no barrier figures. */
    stepped_controller(0);
    memset(&tel, 0, sizeof(tel));
    tvo_step_telemetry_to_lcm(&ctl.telemetry, ctl.cfg.robot_count, ctl.internal.speed_state_mps, &problem, &tel);
    TEST_ASSERT_TRUE(tel.barrier_c == 0.0 && tel.barrier_slack == 0.0);
    TEST_ASSERT_EQUAL_INT32(4, tel.dim);
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
    uint8_t part = 0;
    EF_ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
}

static void target_sample(tvo_lcm_target_t *t)
{
    memset(t, 0, sizeof(*t));
    t->utime = 1000;
    t->session_id = EF_SESSION_ID;
    t->robot_count = 2;
    for (int r = 0; r < 2; ++r) {
        for (int axis = 0; axis < 2; ++axis) {
            t->position_m[r][axis] = 1.0 + r + 0.5 * axis;
            t->velocity_mps[r][axis] = 0.1 * (r + 1);
            t->acceleration_mps2[r][axis] = -0.2;
            t->jerk_mps3[r][axis] = 0.05;
        }
    }
}

static void test_target_sample_feeds_every_robots_stream(void)
{
    streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
    tvo_lcm_target_t t;
    target_sample(&t);
    const int n = tvo_lcm_target_t_encode(buffer, 0, (int)sizeof(buffer), &t);
    TEST_ASSERT_EQUAL_INT(n, tvo_lcm_target_t_decode(buffer, 0, n, &t));
    EF_ASSERT_STATUS(TVO_OK, tvo_step_target_from_lcm(&t, 2u, 5000u, &problem));
    for (uint8_t r = 0; r < 2u; ++r) {
        const tvo_target_t *target = tvo_problem_target(&problem, r);
        TEST_ASSERT_NOT_NULL(target);
        TEST_ASSERT_EQUAL_UINT8(1u, target->u.streamed.has_sample);
        TEST_ASSERT_EQUAL_UINT64(5000u, target->u.streamed.stamp_ticks);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[0][1] == (tvo_real_t)t.position_m[r][1]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[1][0] == (tvo_real_t)t.velocity_mps[r][0]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[2][0] == (tvo_real_t)t.acceleration_mps2[r][0]);
        TEST_ASSERT_TRUE(target->u.streamed.deriv[3][1] == (tvo_real_t)t.jerk_mps3[r][1]);
    }
}

static void test_non_finite_target_value_is_refused_before_any_robot_changes(void)
{
    const double bad_values[] = {(double)NAN, (double)INFINITY, -(double)INFINITY, 1e300};
    for (int field = 0; field < 4; ++field) {
        for (size_t v = 0; v < sizeof(bad_values) / sizeof(bad_values[0]); ++v) {
#if TVO_USE_DOUBLE
            if (bad_values[v] == 1e300) {
                continue; /* finite in double precision */
            }
#endif
            streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
            tvo_lcm_target_t t;
            target_sample(&t);
            EF_ASSERT_STATUS(TVO_OK, tvo_step_target_from_lcm(&t, 2u, 5000u, &problem)); /* a first sample */
            tvo_problem_t before;
            memcpy(&before, &problem, sizeof(problem));
            t.position_m[0][0] = 7.0; /* robot 0's part of the sample is fine */
            double *slot = field == 0   ? &t.position_m[1][1]
                           : field == 1 ? &t.velocity_mps[1][0]
                           : field == 2 ? &t.acceleration_mps2[1][1]
                                        : &t.jerk_mps3[1][0];
            *slot = bad_values[v];
            EF_ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_step_target_from_lcm(&t, 2u, 6000u, &problem));
            TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
        }
    }
}

static void test_target_sample_for_a_non_streamed_target_or_wrong_count_is_refused(void)
{
    streamed_problem(TVO_LCM_PATH_T_KIND_POLYNOMIAL);
    tvo_lcm_target_t t;
    target_sample(&t);
    tvo_problem_t before;
    memcpy(&before, &problem, sizeof(problem));
    EF_ASSERT_STATUS(TVO_ERR_PARAM, tvo_step_target_from_lcm(&t, 2u, 5000u, &problem));
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem)); /* robot 0 not fed either */

    streamed_problem(TVO_LCM_PATH_T_KIND_STREAMED);
    memcpy(&before, &problem, sizeof(problem));
    const int32_t bad[] = {INT32_MIN, -1, 0, 1, 3, INT32_MAX};
    for (size_t i = 0; i < sizeof(bad) / sizeof(bad[0]); ++i) {
        t.robot_count = bad[i];
        EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_target_from_lcm(&t, 2u, 5000u, &problem));
    }
    t.robot_count = TVO_MAX_ROBOTS + 1;
    EF_ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_step_target_from_lcm(&t, (uint8_t)(TVO_MAX_ROBOTS + 1), 5000u, &problem));
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
    t.robot_count = 2;
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_target_from_lcm(NULL, 2u, 5000u, &problem));
    EF_ASSERT_STATUS(TVO_ERR_NULL, tvo_step_target_from_lcm(&t, 2u, 5000u, NULL));
    tvo_problem_t empty;
    memset(&empty, 0, sizeof(empty));
    EF_ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_step_target_from_lcm(&t, 2u, 5000u, &empty));
}

/* The wire's statuses, written here from lcm_types/README.md's table, not from the codec's: every core
 * reason, core error and edge status a command can carry, and which vocabulary wins. */
static void test_wire_status_of_each_reason_error_and_edge_status(void)
{
    static const struct {
        tvo_reason_t reason;
        int32_t wire;
    } reasons[] = {
        {TVO_REASON_NONE, TVO_LCM_COMMAND_T_STATUS_OK},
        {TVO_REASON_NOT_FINITE, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_FINITE},
        {TVO_REASON_IMPLAUSIBLE_MEASUREMENT, TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT},
        {TVO_REASON_STALE, TVO_LCM_COMMAND_T_STATUS_ERR_STALE},
        {TVO_REASON_FUTURE_STAMP, TVO_LCM_COMMAND_T_STATUS_ERR_FUTURE_STAMP},
        {TVO_REASON_STAMP_NOT_NEWER, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_REASON_MISSING_FIELD, TVO_LCM_COMMAND_T_STATUS_ERR_MISSING_FIELD},
        {TVO_REASON_SOURCE_NOT_LINKED, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_INITIALIZED},
        {TVO_REASON_TARGET_NOT_READY, TVO_LCM_COMMAND_T_STATUS_ERR_TARGET_NOT_READY},
        {TVO_REASON_NUMERIC, TVO_LCM_COMMAND_T_STATUS_ERR_NUMERIC},
        {TVO_REASON_NOT_POSITIVE_DEFINITE, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_POSITIVE_DEFINITE},
        {TVO_REASON_NO_MEASUREMENT, TVO_LCM_COMMAND_T_STATUS_ERR_NO_MEASUREMENT},
        {TVO_REASON_WATCHDOG, TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG},
        {TVO_REASON_SPEED_MISMATCH, TVO_LCM_COMMAND_T_STATUS_OK}, /* taken: the stop is in the flags */
        {TVO_REASON_STOP_REQUESTED, TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG},
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
        {TVO_OK, TVO_LCM_COMMAND_T_STATUS_OK},
        {TVO_ERR_NULL, TVO_LCM_COMMAND_T_STATUS_ERR_NULL},
        {TVO_ERR_NOT_FINITE, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_FINITE},
        {TVO_ERR_DIMENSION, TVO_LCM_COMMAND_T_STATUS_ERR_DIMENSION},
        {TVO_ERR_PARAM, TVO_LCM_COMMAND_T_STATUS_ERR_PARAM},
        {TVO_ERR_CAPACITY, TVO_LCM_COMMAND_T_STATUS_ERR_CAPACITY},
        {TVO_ERR_NOT_INITIALIZED, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_INITIALIZED},
        {TVO_ERR_TICK_NOT_ADVANCING, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_BEFORE_EPOCH, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_CLOCK_STARTED, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_NOT_POSITIVE_DEFINITE, TVO_LCM_COMMAND_T_STATUS_ERR_NOT_POSITIVE_DEFINITE},
        {TVO_ERR_NUMERIC, TVO_LCM_COMMAND_T_STATUS_ERR_NUMERIC},
        {TVO_ERR_STALE, TVO_LCM_COMMAND_T_STATUS_ERR_STALE},
        {TVO_ERR_FUTURE_STAMP, TVO_LCM_COMMAND_T_STATUS_ERR_FUTURE_STAMP},
        {TVO_ERR_STAMP_NOT_NEWER, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_ERR_TARGET_NOT_READY, TVO_LCM_COMMAND_T_STATUS_ERR_TARGET_NOT_READY},
    };
    TEST_ASSERT_EQUAL_INT(TVO_STATUS_COUNT, (int)(sizeof(errors) / sizeof(errors[0])));
    for (size_t i = 0; i < sizeof(errors) / sizeof(errors[0]); ++i) {
        const tvo_step_why_t why = {TVO_NODE_OK, errors[i].error, TVO_REASON_WATCHDOG}; /* the error wins */
        EF_ASSERT_STATUS(i == 0 ? TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG : errors[i].wire, tvo_step_wire_status(&why));
    }
    static const struct {
        tvo_node_status_t node;
        int32_t wire;
    } edge[] = {
        {TVO_NODE_OK, TVO_LCM_COMMAND_T_STATUS_OK},
        {TVO_NODE_WRONG_ROBOT_COUNT, TVO_LCM_COMMAND_T_STATUS_ERR_DIMENSION},
        {TVO_NODE_IMPLAUSIBLE_STAMP, TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_STAMP},
        {TVO_NODE_NOT_LATER_PERIOD, TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER},
        {TVO_NODE_STALE, TVO_LCM_COMMAND_T_STATUS_ERR_STALE},
        {TVO_NODE_MISSING_DERIVATIVES, TVO_LCM_COMMAND_T_STATUS_ERR_MISSING_FIELD},
        {TVO_NODE_REFUSAL_STREAK, TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG},
        {TVO_NODE_SESSION_CONFLICT, TVO_LCM_COMMAND_T_STATUS_ERR_SESSION_CONFLICT},
        {TVO_NODE_NO_SESSION, TVO_LCM_COMMAND_T_STATUS_ERR_NO_SESSION},
        {TVO_NODE_UNKNOWN_ACTION, TVO_LCM_COMMAND_T_STATUS_ERR_PARAM},
    };
    TEST_ASSERT_EQUAL_INT(TVO_NODE_STATUS_COUNT, (int)(sizeof(edge) / sizeof(edge[0])));
    for (size_t i = 1; i < sizeof(edge) / sizeof(edge[0]); ++i) {
        const tvo_step_why_t why = {edge[i].node, TVO_ERR_NUMERIC, TVO_REASON_STALE}; /* the edge's wins */
        EF_ASSERT_STATUS(edge[i].wire, tvo_step_wire_status(&why));
        TEST_ASSERT_TRUE(strcmp(tvo_node_status_str(edge[i].node), tvo_node_status_str(TVO_NODE_STATUS_COUNT)) != 0);
    }
    EF_ASSERT_STATUS(TVO_LCM_COMMAND_T_STATUS_ERR_NULL, tvo_step_wire_status(NULL));
}

/* HOLDING and SAFE_STOP say the outcome, and only it; the core's flags pass unchanged. */
static void test_wire_flags_say_the_outcome(void)
{
    const uint32_t shaping = TVO_FLAG_OMEGA_SATURATED | TVO_FLAG_PREDICTED | TVO_FLAG_SPEED_MISMATCH;
    TEST_ASSERT_EQUAL_HEX32(shaping, tvo_step_wire_flags(shaping, TVO_OUTCOME_APPLIED));
    TEST_ASSERT_EQUAL_HEX32(shaping | TVO_LCM_COMMAND_T_FLAG_HOLDING, tvo_step_wire_flags(shaping, TVO_OUTCOME_HELD));
    TEST_ASSERT_EQUAL_HEX32(shaping | TVO_LCM_COMMAND_T_FLAG_SAFE_STOP,
                            tvo_step_wire_flags(shaping, TVO_OUTCOME_STOPPED));
    /* Stray outcome bits in the core's flags do not survive an applied outcome. */
    TEST_ASSERT_EQUAL_HEX32(0u, tvo_step_wire_flags(TVO_LCM_COMMAND_T_FLAG_HOLDING | TVO_LCM_COMMAND_T_FLAG_SAFE_STOP,
                                                    TVO_OUTCOME_APPLIED));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_measurement_round_trip_keeps_every_robot_and_field);
    RUN_TEST(test_wire_status_of_each_reason_error_and_edge_status);
    RUN_TEST(test_wire_flags_say_the_outcome);
    RUN_TEST(test_measurement_robot_count_must_match_the_session);
    RUN_TEST(test_a_robot_count_the_message_cannot_carry_becomes_minus_one);
    RUN_TEST(test_measurement_values_beyond_the_scalar_become_infinite);
    RUN_TEST(test_chain_measurement_reads_derivatives_only_when_valid);
    RUN_TEST(test_command_round_trip_carries_the_stamp_and_each_robot);
    RUN_TEST(test_chain_command_carries_u_per_output);
    RUN_TEST(test_telemetry_round_trip_carries_the_controllers_last_step);
    RUN_TEST(test_target_sample_feeds_every_robots_stream);
    RUN_TEST(test_non_finite_target_value_is_refused_before_any_robot_changes);
    RUN_TEST(test_target_sample_for_a_non_streamed_target_or_wrong_count_is_refused);
    return UNITY_END();
}
