/*
 * The barrier's s0 chosen by the controllers' step (the objective's start rule, tvo/problem.h), one
 * robot behind a half-space x <= 1 (f = x - 1), so a start at x > 1 is infeasible and s0 > 0:
 *   - refused first measurements (not finite, stale, a target not ready yet) leave s0 at 0, not
 *     chosen, though a finite one would have chosen another s0 than the accepted one; a refused
 *     step leaves the problem as it was, byte for byte;
 *   - the first accepted measurement chooses s0 exactly as tvo_problem_choose_slack would from its
 *     positions at t = 0, and later ones change nothing;
 *   - s0 chosen by tvo_problem_choose_slack before the first step is kept;
 * for the unicycle controller and for the integrator chain.
 */
#include "test_support.h"

#include "tvo/chain_controller.h"
#include "tvo/problem.h"

void setUp(void) {}
void tearDown(void) {}

static tvo_problem_t problem;   /* the controller's */
static tvo_problem_t reference; /* tvo_problem_choose_slack on the same description */
static tvo_problem_desc_t desc;

#define EPOCH 1000u

/* One robot, tracking a line (or a streamed target), behind x <= 1; k the controller's degree. */
static void init_problems(uint8_t k, int streamed)
{
    ASSERT_STATUS(TVO_OK, tvo_problem_desc_default(&desc));
    desc.robot_count = 1u;
    if (streamed) {
        ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&desc.target[0]));
    } else {
        fx_line_target(&desc.target[0], 0.0, 0.0, 0.5, 0.0);
    }
    desc.halfspace_count = 1u;
    desc.halfspace[0].normal[0] = TVO_R(1.0);
    desc.halfspace[0].bound_m = TVO_R(1.0);
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, k, NULL));
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&reference, &desc, k, NULL));
}

/* s0 as tvo_problem_choose_slack chooses it from y = (x, y1) at t = 0, on a fresh reference. */
static tvo_real_t reference_slack(uint8_t k, tvo_real_t x, tvo_real_t y1)
{
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&reference, &desc, k, NULL));
    const tvo_real_t y[2] = {x, y1};
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&reference, y, TVO_R(0.0)));
    TEST_ASSERT_EQUAL_UINT8(1u, reference.slack_chosen);
    return reference.barrier.slack0;
}

static tvo_problem_t before; /* the problem before a refused step */

static void snapshot(void)
{
    memcpy(&before, &problem, sizeof(problem));
}

/* s0 not chosen, and the refused step left the problem as it was, byte for byte. */
static void assert_not_chosen(void)
{
    TEST_ASSERT_EQUAL_UINT8(0u, problem.slack_chosen);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == TVO_R(0.0));
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
}

/* ---- unicycle ---------------------------------------------------------------------------------- */

static fx_t fx;

static void unicycle_on_problem(int streamed)
{
    init_problems(2u, streamed);
    fx_reset(&fx, 1u);
    ASSERT_STATUS(TVO_OK, tvo_controller_init(&fx.ctl, &fx.cfg, &problem.objective, EPOCH, &fx.bad_param));
    fx.apply = EPOCH + fx.cfg.period_ticks;
}

static void unicycle_measure(tvo_real_t x, uint32_t stamp, tvo_measurement_t *m)
{
    const tvo_pose_t pose = {{x, TVO_R(0.2)}, TVO_R(0.0)};
    fx_measure(&fx, &pose, stamp, m);
}

/* Once s0 is chosen: a stale measurement at x is refused and leaves the problem as it was, byte for
 * byte; the next one at x is accepted, and s0 is still `kept`. */
static void unicycle_stale_then_accepted_keep_s0(tvo_real_t x, tvo_real_t kept)
{
    tvo_measurement_t m;
    tvo_command_t cmd;
    unicycle_measure(x, fx.apply - fx.cfg.period_ticks - 1u, &m);
    snapshot();
    ASSERT_PERIOD(HELD(STALE), tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
    unicycle_measure(x, fx.apply - fx.cfg.delay_ticks, &m);
    ASSERT_PERIOD(APPLIED, tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == kept);
}

static void test_unicycle_refused_first_measurements_leave_s0_unchosen(void)
{
    unicycle_on_problem(0);
    const uint32_t stamp = fx.apply - fx.cfg.delay_ticks;
    tvo_measurement_t m;
    tvo_command_t cmd;
    /* What a kept refused sample would have chosen differs from the accepted one's s0. */
    const tvo_real_t s0_refused = reference_slack(2u, TVO_R(3.0), TVO_R(0.2));
    const tvo_real_t s0_accepted = reference_slack(2u, TVO_R(1.5), TVO_R(0.2));
    TEST_ASSERT_TRUE(s0_refused != s0_accepted);
    ASSERT_LE(0.5, s0_accepted, "an infeasible start: s0 > 0");

    unicycle_measure(TVO_R(3.0), stamp, &m);
    m.position_m[0][1] = TEST_NAN;
    snapshot();
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    assert_not_chosen();

    unicycle_measure(TVO_R(3.0), fx.apply - fx.cfg.period_ticks - 1u, &m);
    snapshot();
    ASSERT_PERIOD(HELD(STALE), tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    assert_not_chosen();

    unicycle_measure(TVO_R(1.5), stamp, &m);
    ASSERT_PERIOD(APPLIED, tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    TEST_ASSERT_EQUAL_UINT8(1u, problem.slack_chosen);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == s0_accepted);

    /* Later periods change nothing, refused or applied. */
    fx.apply += fx.cfg.period_ticks;
    unicycle_stale_then_accepted_keep_s0(TVO_R(3.0), s0_accepted);
}

static void test_unicycle_law_refusal_takes_the_choice_back(void)
{
    /* The measurement passes every check; the period is refused (its streamed target has no sample:
     * the loop's check before the law). */
    unicycle_on_problem(1);
    tvo_measurement_t m;
    tvo_command_t cmd;
    unicycle_measure(TVO_R(3.0), fx.apply - fx.cfg.delay_ticks, &m);
    snapshot();
    ASSERT_PERIOD(HELD(TARGET_NOT_READY), tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    assert_not_chosen();

    const tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2] = {{TVO_R(0.0), TVO_R(0.0)}};
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(tvo_problem_target(&problem, 0u), 0u, deriv));
    unicycle_measure(TVO_R(1.5), fx.apply - fx.cfg.delay_ticks, &m);
    ASSERT_PERIOD(APPLIED, tvo_controller_step(&fx.ctl, &m, fx.apply, &cmd), cmd);
    TEST_ASSERT_EQUAL_UINT8(1u, problem.slack_chosen);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == reference_slack(2u, TVO_R(1.5), TVO_R(0.2)));
}

static void test_unicycle_keeps_s0_chosen_before_the_first_step(void)
{
    unicycle_on_problem(0);
    const tvo_real_t y[2] = {TVO_R(3.0), TVO_R(0.2)};
    ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, y, TVO_R(0.0)));
    const tvo_real_t chosen = problem.barrier.slack0;
    unicycle_stale_then_accepted_keep_s0(TVO_R(1.5), chosen);
    TEST_ASSERT_TRUE(chosen == reference_slack(2u, TVO_R(3.0), TVO_R(0.2)));
}

/* ---- integrator chain ------------------------------------------------------------------------- */

static tvo_chain_controller_t chain;

static void chain_on_problem(void)
{
    init_problems(2u, 0);
    tvo_chain_config_t cfg;
    ASSERT_STATUS(TVO_OK, tvo_chain_config_default(&cfg));
    cfg.relative_degree = 2u;
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_NONE;
    ASSERT_STATUS(TVO_OK, tvo_chain_controller_init(&chain, &cfg, &problem.objective, EPOCH, &bad));
}

static void chain_measure(tvo_real_t x, uint32_t stamp, tvo_chain_measurement_t *m)
{
    memset(m, 0, sizeof(*m));
    m->stamp_tick = stamp;
    m->y.d[0][0] = x;
    m->y.d[0][1] = TVO_R(0.2);
}

static void test_chain_refused_first_measurements_leave_s0_unchosen(void)
{
    chain_on_problem();
    const uint32_t period = chain.cfg.period_ticks;
    const uint32_t apply = EPOCH + period;
    const uint32_t stamp = apply - chain.cfg.delay_ticks;
    tvo_chain_measurement_t m;
    tvo_chain_command_t cmd;
    const tvo_real_t s0_accepted = reference_slack(2u, TVO_R(1.5), TVO_R(0.2));
    TEST_ASSERT_TRUE(reference_slack(2u, TVO_R(3.0), TVO_R(0.2)) != s0_accepted);

    chain_measure(TVO_R(3.0), stamp, &m);
    m.y.d[0][1] = TEST_NAN;
    snapshot();
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&chain, &m, apply, &cmd), cmd);
    assert_not_chosen();

    chain_measure(TVO_R(3.0), apply - period - 1u, &m);
    snapshot();
    ASSERT_PERIOD(HELD(STALE), tvo_chain_controller_step(&chain, &m, apply, &cmd), cmd);
    assert_not_chosen();

    chain_measure(TVO_R(1.5), stamp, &m);
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&chain, &m, apply, &cmd), cmd);
    TEST_ASSERT_EQUAL_UINT8(1u, problem.slack_chosen);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == s0_accepted);

    chain_measure(TVO_R(3.0), apply - 1u, &m);
    snapshot();
    ASSERT_PERIOD(HELD(STALE), tvo_chain_controller_step(&chain, &m, apply + period, &cmd), cmd);
    TEST_ASSERT_EQUAL_MEMORY(&before, &problem, sizeof(problem));
    chain_measure(TVO_R(3.0), stamp + period, &m);
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&chain, &m, apply + period, &cmd), cmd);
    TEST_ASSERT_TRUE(problem.barrier.slack0 == s0_accepted);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_unicycle_refused_first_measurements_leave_s0_unchosen);
    RUN_TEST(test_unicycle_law_refusal_takes_the_choice_back);
    RUN_TEST(test_unicycle_keeps_s0_chosen_before_the_first_step);
    RUN_TEST(test_chain_refused_first_measurements_leave_s0_unchosen);
    return UNITY_END();
}
