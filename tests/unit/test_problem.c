/*
 * Problem assembly (tvo/problem.h) and the controller driving a problem:
 *   - a formation with minimum and maximum distance gives two distance terms; obstacles give one
 *     free-space term per robot; an offset adds two multipliers;
 *   - a bad description is rejected with the part named and leaves the problem uninitialised;
 *   - the s0 rule through tvo_problem_choose_slack acts on the first call only;
 *   - the controller on an indefinite Hessian (minimum distance, barrier curvature dominating) returns
 *     TVO_OK with TVO_FLAG_REGULARIZED and finite commands; the multipliers of a violated offset
 *     equality evolve in telemetry.
 */
#include "test_support.h"

#include "tvo/problem.h"
#include "internal/objective.h"

void setUp(void) {}
void tearDown(void) {}

enum { PART_ROBOTS = 0, PART_BARRIER = 1, PART_DISTANCE = 2, PART_HALFSPACE = 3, PART_OBSTACLES = 4, PART_OFFSETS = 5 };

static tvo_problem_t problem; /* large: static */

static void two_robot_desc(tvo_problem_desc_t *desc)
{
    ASSERT_STATUS(TVO_OK, tvo_problem_desc_default(desc));
    desc->robot_count = 2;
    fx_line_target(&desc->target[0], 0.0, 0.0, 0.5, 0.0);
    fx_line_target(&desc->target[1], 2.0, 0.0, 0.5, 0.0);
}

static void assert_uninitialised(void)
{
    TEST_ASSERT_EQUAL_UINT8(0, problem.initialized);
    const tvo_real_t y[8] = {TVO_R(0.0)};
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_problem_choose_slack(&problem, y, TVO_R(0.0)));
    TEST_ASSERT_NULL(tvo_problem_target(&problem, 0));
}

static void test_formation_with_min_and_max_distance_gives_two_distance_terms(void)
{
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    desc.distance_count = 1;
    desc.distance[0].robot_a = 0;
    desc.distance[0].robot_b = 1;
    desc.distance[0].min_m = TVO_R(1.0);
    desc.distance[0].max_m = TVO_R(3.0);
    desc.distance[0].max_rate_mps = TVO_R(-0.1);
    tvo_problem_culprit_t part = {99u, 99};
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, &part));
    TEST_ASSERT_EQUAL_UINT8(0u, part.part); /* no culprit */
    TEST_ASSERT_EQUAL_INT16(-1, part.index);
    TEST_ASSERT_EQUAL_UINT8(1, problem.initialized);
    TEST_ASSERT_EQUAL_UINT8(1, problem.has_inequalities);
    TEST_ASSERT_EQUAL_UINT8(2, problem.distance_term_count);
    TEST_ASSERT_EQUAL_UINT8(4, problem.objective.term_count); /* 2 tracking + 2 distance */
    TEST_ASSERT_TRUE(problem.objective.terms[2].constraint_max != NULL);
    TEST_ASSERT_TRUE(problem.objective.terms[3].constraint_max != NULL);
    /* The start rule sees the larger side: |D| = 2 gives 1 - 4 (minimum) and 4 - 9 (maximum). */
    const tvo_real_t y[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(2.0), TVO_R(0.0)};
    tvo_real_t worst = TVO_R(0.0);
    uint8_t has = 0u;
    ASSERT_STATUS(TVO_OK, tvo_objective_constraint_max(&problem.objective, y, TVO_R(0.0), &worst, &has));
    TEST_ASSERT_EQUAL_UINT8(1, has);
    ASSERT_NEAR(-3.0, worst, 0.0);
    TEST_ASSERT_EQUAL_UINT8(4, problem.objective.dim);
    TEST_ASSERT_EQUAL_INT(TVO_DISTANCE_MIN, problem.distance[0].kind);
    TEST_ASSERT_EQUAL_INT(TVO_DISTANCE_MAX, problem.distance[1].kind);
    ASSERT_NEAR(1.0, problem.distance[0].bound_m, 0.0);
    ASSERT_NEAR(3.0, problem.distance[1].bound_m, 0.0);
    ASSERT_NEAR(-0.1, problem.distance[1].bound_rate_mps, TEST_TOL(1, 0.1));
    TEST_ASSERT_TRUE(tvo_problem_target(&problem, 1) == &problem.target[1]);
    TEST_ASSERT_NULL(tvo_problem_target(&problem, 2));

    /* Max only: one term. */
    desc.distance[0].min_m = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, &part));
    TEST_ASSERT_EQUAL_UINT8(1, problem.distance_term_count);
    TEST_ASSERT_EQUAL_INT(TVO_DISTANCE_MAX, problem.distance[0].kind);
}

/* Three robots or more (the block plan's problems): a bound's two sides are one objective term over its
 * two distance terms, whose constraint value is the larger side's. */
static void test_three_robots_take_a_bound_with_both_sides_as_one_term(void)
{
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    desc.robot_count = 3;
    fx_line_target(&desc.target[2], 4.0, 0.0, 0.5, 0.0);
    desc.distance_count = 2;
    desc.distance[0].robot_a = 0;
    desc.distance[0].robot_b = 1;
    desc.distance[0].min_m = TVO_R(1.0);
    desc.distance[0].max_m = TVO_R(3.0);
    desc.distance[1].robot_a = 1;
    desc.distance[1].robot_b = 2;
    desc.distance[1].max_m = TVO_R(3.0); /* one side: a term of its own */
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    TEST_ASSERT_EQUAL_UINT8(3, problem.distance_term_count);
#if TVO_BLOCK_SOLVE
    TEST_ASSERT_EQUAL_UINT8(5, problem.objective.term_count); /* 3 tracking + the bound + the one side */
    TEST_ASSERT_TRUE(problem.objective.terms[3].term == &problem.distance[0]);
    TEST_ASSERT_TRUE(problem.objective.terms[4].term == &problem.distance[2]);
    TEST_ASSERT_TRUE(problem.objective.plan == &problem.plan);
#else
    TEST_ASSERT_EQUAL_UINT8(6, problem.objective.term_count);
#endif
    /* |y0 - y1| = 2: 1 - 4 (minimum) and 4 - 9 (maximum); |y1 - y2| = 1: 1 - 9. */
    const tvo_real_t y[6] = {TVO_R(0.0), TVO_R(0.0), TVO_R(2.0), TVO_R(0.0), TVO_R(3.0), TVO_R(0.0)};
    tvo_real_t worst = TVO_R(0.0);
    uint8_t has = 0u;
    ASSERT_STATUS(TVO_OK, tvo_objective_constraint_max(&problem.objective, y, TVO_R(0.0), &worst, &has));
    TEST_ASSERT_EQUAL_UINT8(1, has);
    ASSERT_NEAR(-3.0, worst, 0.0);
}

static void test_obstacles_give_one_free_space_term_per_robot(void)
{
    tvo_problem_desc_t desc;
    ASSERT_STATUS(TVO_OK, tvo_problem_desc_default(&desc));
    desc.robot_count = 3;
    for (uint8_t r = 0; r < 3; ++r) {
        fx_line_target(&desc.target[r], (double)r, 0.0, 0.0, 0.5);
    }
    desc.obstacle_count = 2;
    desc.robot_radius_m = TVO_R(0.2);
    desc.obstacle[0].center_m[0] = TVO_R(5.0);
    desc.obstacle[0].radius_m = TVO_R(1.0);
    desc.obstacle[1].center_m[0] = TVO_R(-5.0);
    desc.obstacle[1].radius_m = TVO_R(0.5);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    TEST_ASSERT_EQUAL_UINT8(6, problem.objective.term_count); /* 3 tracking + 3 free space */
    TEST_ASSERT_EQUAL_UINT8(6, problem.objective.dim);
    for (uint8_t r = 0; r < 3; ++r) {
        TEST_ASSERT_EQUAL_UINT8(2u * r, problem.free_space[r].offset);
        TEST_ASSERT_EQUAL_UINT8(2, problem.free_space[r].obstacle_count);
        TEST_ASSERT_TRUE(problem.objective.terms[3 + r].term == &problem.free_space[r]);
    }
}

static void test_offset_adds_multipliers(void)
{
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    desc.offset_count = 1;
    desc.offset[0].robot_a = 1;
    desc.offset[0].robot_b = 0;
    fx_line_target(&desc.offset[0].offset, 2.0, 0.0, 0.0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    TEST_ASSERT_EQUAL_UINT8(0, problem.has_inequalities);
    TEST_ASSERT_EQUAL_UINT8(6, problem.objective.dim);
    TEST_ASSERT_EQUAL_UINT8(2, problem.objective.dual_dim);
    TEST_ASSERT_EQUAL_UINT8(3, problem.objective.term_count);
    TEST_ASSERT_TRUE(problem.offset[0].offset == &problem.offset_function[0]);
}

/* Initialises a valid problem first, so a rejection must also clear it. */
static void expect_rejected(const tvo_problem_desc_t *bad, uint8_t relative_degree, tvo_status_t status,
                            uint8_t expected_part, int16_t expected_index, const char *what)
{
    tvo_problem_desc_t good;
    two_robot_desc(&good);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &good, 2, NULL));
    tvo_problem_culprit_t culprit = {99u, 99};
    ASSERT_STATUS(status, tvo_problem_init(&problem, bad, relative_degree, &culprit));
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(expected_part, culprit.part, what);
    TEST_ASSERT_EQUAL_INT16_MESSAGE(expected_index, culprit.index, what);
    assert_uninitialised();
}

static void test_bad_descriptions_name_the_part_and_leave_the_problem_uninitialised(void)
{
    tvo_problem_desc_t desc;

    two_robot_desc(&desc);
    desc.robot_count = 0;
    expect_rejected(&desc, 2, TVO_ERR_DIMENSION, PART_ROBOTS, -1, "no robots");
    desc.robot_count = TVO_MAX_ROBOTS + 1;
    expect_rejected(&desc, 2, TVO_ERR_DIMENSION, PART_ROBOTS, -1, "too many robots");
    two_robot_desc(&desc);
    desc.tracking_weight[1][0] = TVO_R(0.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_ROBOTS, 1, "zero tracking weight");

    two_robot_desc(&desc);
    desc.distance_count = 1;
    desc.distance[0].robot_b = 1;
    desc.distance[0].max_m = TVO_R(3.0);
    desc.barrier.relaxation_degree = 2; /* m_r < k + 1 = 3 */
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_BARRIER, -1, "m_r < k + 1");
    desc.barrier.relaxation_degree = 3;
    expect_rejected(&desc, 3, TVO_ERR_PARAM, PART_BARRIER, -1, "m_r = 3 < k + 1 = 4");

    two_robot_desc(&desc);
    desc.distance_count = 1;
    desc.distance[0].robot_b = 1;
    desc.distance[0].min_m = TVO_R(3.0);
    desc.distance[0].max_m = TVO_R(3.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_DISTANCE, 0, "min >= max");
    desc.distance[0].min_m = TVO_R(0.0);
    desc.distance[0].max_m = TVO_R(0.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_DISTANCE, 0, "no bound at all");
    desc.distance[0].max_m = TVO_R(3.0);
    desc.distance[0].robot_b = 2;
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_DISTANCE, 0, "distance robot out of range");
    desc.distance[0].robot_b = 0;
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_DISTANCE, 0, "distance to itself");

    two_robot_desc(&desc);
    desc.halfspace_count = 1;
    desc.halfspace[0].robot = 1;
    desc.halfspace[0].bound_m = TVO_R(1.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_HALFSPACE, 0, "zero normal");
    desc.halfspace[0].normal[0] = TVO_R(1.0);
    desc.halfspace[0].robot = 2;
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_HALFSPACE, 0, "half-space robot out of range");
    desc.halfspace[0].robot = 1;
    desc.halfspace_count = 2;
    desc.halfspace[1] = desc.halfspace[0];
    desc.halfspace[1].normal[1] = TEST_NAN;
    expect_rejected(&desc, 2, TVO_ERR_NOT_FINITE, PART_HALFSPACE, 1, "a NaN normal in the second half-space");

    two_robot_desc(&desc);
    desc.obstacle_count = 2;
    desc.robot_radius_m = TVO_R(0.2);
    desc.obstacle[0].radius_m = TVO_R(1.0);
    desc.obstacle[1].center_m[0] = TVO_R(1.5);
    desc.obstacle[1].radius_m = TVO_R(1.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_OBSTACLES, 1, "intersecting obstacles");
    desc.obstacle_count = TVO_MAX_OBSTACLES + 1;
    expect_rejected(&desc, 2, TVO_ERR_CAPACITY, PART_OBSTACLES, -1, "too many obstacles");

    two_robot_desc(&desc);
    desc.offset_count = 1;
    desc.offset[0].robot_a = 0;
    desc.offset[0].robot_b = 2;
    fx_line_target(&desc.offset[0].offset, 1.0, 0.0, 0.0, 0.0);
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_OFFSETS, 0, "offset robot out of range");
    desc.offset[0].robot_b = 0;
    expect_rejected(&desc, 2, TVO_ERR_PARAM, PART_OFFSETS, 0, "offset to itself");

    ASSERT_STATUS(TVO_ERR_NULL, tvo_problem_init(&problem, NULL, 2, NULL));
}

static void test_choose_slack_acts_on_the_first_call_only(void)
{
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    desc.barrier.slack_margin = TVO_R(0.25);
    desc.distance_count = 1;
    desc.distance[0].robot_b = 1;
    desc.distance[0].min_m = TVO_R(1.0);
    desc.distance[0].max_m = TVO_R(3.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    ASSERT_NEAR(0.0, problem.barrier.slack0, 0.0);
    /* |D| = 4: max(1 - 16, 16 - 9) = 7: infeasible, s0 = 7.25. */
    const tvo_real_t far[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(4.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, far, TVO_R(0.0)));
    ASSERT_NEAR(7.25, problem.barrier.slack0, TEST_TOL(4, 8.0));
    /* A later call changes nothing, feasible or not. */
    const tvo_real_t ok[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(2.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, ok, TVO_R(0.0)));
    ASSERT_NEAR(7.25, problem.barrier.slack0, TEST_TOL(4, 8.0));

    /* A feasible first call: s0 = 0, and it stays 0. */
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, ok, TVO_R(0.0)));
    ASSERT_NEAR(0.0, problem.barrier.slack0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, far, TVO_R(0.0)));
    ASSERT_NEAR(0.0, problem.barrier.slack0, 0.0);

    /* Too close: max(1 - 0.25, 0.25 - 9) = 0.75: s0 = 1. */
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    const tvo_real_t close[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(0.0), TVO_R(0.5)};
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, close, TVO_R(0.0)));
    ASSERT_NEAR(1.0, problem.barrier.slack0, TEST_TOL(4, 1.0));

    /* Without inequalities: a no-op that succeeds. */
    two_robot_desc(&desc);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, far, TVO_R(0.0)));
    ASSERT_NEAR(0.0, problem.barrier.slack0, 0.0);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_problem_choose_slack(&problem, NULL, TVO_R(0.0)));
}

/* ------------------------------------------------------------------------------------------------
 * The controller with a problem
 * --------------------------------------------------------------------------------------------- */

static fx_t fx;

/* Binds the fixture's controller to problem.objective, plant at the given poses, s0 chosen there. */
static void controller_on_problem(const tvo_pose_t *poses)
{
    fx_reset(&fx, (uint8_t)(problem.objective.primal_dim / 2u));
    tvo_real_t y[TVO_MAX_OUTPUT_DIM];
    for (uint8_t r = 0; r < fx.cfg.robot_count; ++r) {
        fx.pose[r] = poses[r];
        y[2 * r] = poses[r].position_m[0];
        y[2 * r + 1] = poses[r].position_m[1];
    }
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, y, TVO_R(0.0)));
    fx.epoch = 1000u;
    fx.apply = fx.epoch + fx.cfg.period_ticks;
    ASSERT_STATUS(TVO_OK, tvo_controller_init(&fx.ctl, &fx.cfg, &problem.objective, fx.epoch, &fx.bad_param));
}

static void test_indefinite_hessian_is_regularised_and_flagged(void)
{
    /* Two robots 1.2 m apart with a 1 m minimum distance, each pulled through the other by its target.
     * sigma = |D|^2 - 1 = 0.44, w = 1/(c sigma) ~ 2.3: along (e_perp, -e_perp) the Hessian is
     * 1 - 4 w < 0 (the barrier's negative curvature -2 w I per robot pair dominates W = I). */
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    fx_line_target(&desc.target[0], 1.5, 0.0, 0.0, 0.0);
    fx_line_target(&desc.target[1], -0.3, 0.0, 0.0, 0.0);
    desc.distance_count = 1;
    desc.distance[0].robot_b = 1;
    desc.distance[0].min_m = TVO_R(1.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    tvo_pose_t poses[2];
    memset(poses, 0, sizeof(poses));
    poses[1].position_m[0] = TVO_R(1.2);
    poses[1].heading_rad = test_r(TEST_PI);
    controller_on_problem(poses);
    ASSERT_NEAR(0.0, problem.barrier.slack0, 0.0); /* a feasible start */
    tvo_command_t cmd;
    for (int step = 0; step < 3; ++step) {
        ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &cmd), cmd);
        ASSERT_FLAG_SET(cmd.flags, TVO_FLAG_REGULARIZED);
        TEST_ASSERT_TRUE(fx.ctl.telemetry.regularization > TVO_R(0.0));
        for (int r = 0; r < 2; ++r) {
            TEST_ASSERT_TRUE(test_is_finite(cmd.speed_mps[r]) && test_is_finite(cmd.turn_rate_radps[r]));
        }
    }
    /* Far apart the barrier is weak, the Hessian definite: no flag. */
    fx_line_target(&desc.target[1], 5.0, 0.0, 0.0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    poses[1].position_m[0] = TVO_R(5.0);
    controller_on_problem(poses);
    ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &cmd), cmd);
    ASSERT_FLAG_CLEAR(cmd.flags, TVO_FLAG_REGULARIZED);
    ASSERT_NEAR(0.0, fx.ctl.telemetry.regularization, 0.0);
}

static void test_multipliers_evolve_when_the_offset_is_violated(void)
{
    /*
     * y_0 - y_1 = d = (1.5, 0.5) demanded while the targets sit (1, 0) apart at equal velocity, and the
     * robots start violating it. With W = I the dual rows decouple: adding and subtracting the primal
     * rows, nu'' + k_d nu' + k_p (nu - nu*) = 0 with nu* = (yd_0 - yd_1 - d)/2 = (-0.25, -0.25)
     * (stationarity y_0 - yd_0 + nu = 0, y_1 - yd_1 - nu = 0). The controller integrates nu exactly for the
     * nu'' it is given over each period, so telemetry must follow that recursion from nu = nu' = 0.
     * (With targets consistent with d, nu* = 0 and nu stays 0 whatever the initial violation: the
     * multiplier prices the conflict between tracking and the equality, not the robots' error.)
     */
    tvo_problem_desc_t desc;
    two_robot_desc(&desc);
    fx_line_target(&desc.target[0], 0.5, 0.0, 0.5, 0.0);
    fx_line_target(&desc.target[1], -0.5, 0.0, 0.5, 0.0);
    desc.offset_count = 1;
    desc.offset[0].robot_a = 0;
    desc.offset[0].robot_b = 1;
    fx_line_target(&desc.offset[0].offset, 1.5, 0.5, 0.0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2, NULL));
    tvo_pose_t poses[2];
    memset(poses, 0, sizeof(poses));
    poses[1].position_m[1] = TVO_R(0.5);
    controller_on_problem(poses);
    const double kp = test_d(fx.cfg.gain_kp), kd = test_d(fx.cfg.gain_kd);
    const double h = (double)fx.cfg.period_ticks / (double)fx.cfg.tick_hz;
    const double nu_star[2] = {-0.25, -0.25};
    double nu[2] = {0.0, 0.0}, nud[2] = {0.0, 0.0};
    tvo_command_t cmd;
    for (int step = 0; step < 20; ++step) {
        ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &cmd), cmd);
        for (int q = 0; q < 2; ++q) {
            const double acc = -kd * nud[q] - kp * (nu[q] - nu_star[q]);
            nu[q] += (nud[q] + 0.5 * acc * h) * h;
            nud[q] += acc * h;
            /* nu'' comes from the KKT solve (a few hundred ulps of kp |nu*| ~ 10), integrated with h^2:
             * the rounding of the integration itself (|nu| <= 0.25 per step) dominates. */
            ASSERT_NEAR_MSG(nu[q], fx.ctl.telemetry.multiplier[q], TEST_TOL(16 * (step + 1), 0.25), "nu vs recursion");
        }
    }
    /* After 20 periods (0.2 s) the multipliers are well on their way to nu*. */
    for (int q = 0; q < 2; ++q) {
        ASSERT_LE(0.02, -test_d(fx.ctl.telemetry.multiplier[q]), "nu moved toward nu* = -0.25");
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_formation_with_min_and_max_distance_gives_two_distance_terms);
    RUN_TEST(test_three_robots_take_a_bound_with_both_sides_as_one_term);
    RUN_TEST(test_obstacles_give_one_free_space_term_per_robot);
    RUN_TEST(test_offset_adds_multipliers);
    RUN_TEST(test_bad_descriptions_name_the_part_and_leave_the_problem_uninitialised);
    RUN_TEST(test_choose_slack_acts_on_the_first_call_only);
    RUN_TEST(test_indefinite_hessian_is_regularised_and_flagged);
    RUN_TEST(test_multipliers_evolve_when_the_offset_is_violated);
    return UNITY_END();
}
