/*
 * The size limits of tvo/config.h as a product sets them. Built against every twin of the core,
 * tvo_core_one_robot among them (one robot, no equality constraints: the saddle solve compiled out).
 * What exceeds a limit is refused (TVO_ERR_CAPACITY, TVO_ERR_DIMENSION) and leaves nothing behind;
 * under the limits, one robot is controlled as the default limits control it: the closed loop below
 * prints a digest of its commands, which limits_agree.cmake compares across the twins.
 */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "test_support.h"
#include "tvo/linsolve.h"
#include "tvo/objective.h"
#include "internal/linsolve.h"
#include "internal/objective.h"
#include "unity.h"

void setUp(void);
void tearDown(void);
void setUp(void) {}
void tearDown(void) {}

static fx_t fx;

/* How the one robot's tracking term joins the objective. */
enum {
    BY_JETS,      /* tvo_objective_add_term: jets only, the general mechanism (a term without a closed form) */
    CLOSED_FORM,  /* tvo_objective_add with its closed form: the law's tracking path, the general path linked */
    TRACKING_ADD  /* tvo_tracking_add: the tracking path alone, the general path not linked */
};

/* One robot on the fixture's circle, its tracking term added as `how` says. */
static void setup_one_robot(int how)
{
    const tvo_real_t weight[2] = {TVO_R(3.0), TVO_R(0.7)};
    fx_reset(&fx, 1u);
    fx_circle_target(&fx.target[0], 0.0, 0.0, 1.0, 0.5);
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&fx.objective, 2u));
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&fx.term[0], &fx.target[0], weight, 0u));
    if (how == CLOSED_FORM) {
        const tvo_term_t spec = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &fx.term[0], TVO_TERM_TRACKING};
        ASSERT_STATUS(TVO_OK, tvo_objective_add(&fx.objective, &spec));
    } else if (how == TRACKING_ADD) {
        ASSERT_STATUS(TVO_OK, tvo_tracking_add(&fx.objective, &fx.term[0]));
    } else {
        ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&fx.objective, tvo_tracking_gradient_jet, &fx.term[0]));
    }
    /* Which path the law takes, and whether the objective links the general path. */
    TEST_ASSERT_EQUAL_UINT8(how == BY_JETS ? 0u : 1u, fx.objective.tracking_only);
    TEST_ASSERT_TRUE((how == TRACKING_ADD) == (fx.objective.general_path == NULL));
    fx.epoch = 1000u;
    fx.apply = fx.epoch + fx.cfg.period_ticks;
    fx.pose[0].position_m[0] = TVO_R(1.5);
    fx.pose[0].position_m[1] = TVO_R(-0.5);
    fx.pose[0].heading_rad = TVO_R(0.3);
    tvo_param_t bad = TVO_PARAM_INITIAL_SPEED;
    ASSERT_STATUS(TVO_OK, tvo_controller_init(&fx.ctl, &fx.cfg, &fx.objective, fx.epoch, &bad));
    ASSERT_PARAM(TVO_PARAM_NONE, bad);
}

static void test_multipliers_beyond_the_limit_are_refused_and_leave_the_objective_as_it_was(void)
{
    tvo_objective_t objective;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&objective, TVO_MAX_OUTPUT_DIM));
    uint8_t first = 0xEEu;
    ASSERT_STATUS(TVO_ERR_CAPACITY,
                  tvo_objective_reserve_multipliers(&objective, (uint8_t)(TVO_MAX_EQUALITIES + 1), &first));
    TEST_ASSERT_EQUAL_UINT8(0u, objective.dual_dim);
    TEST_ASSERT_EQUAL_UINT8(TVO_MAX_OUTPUT_DIM, objective.dim);
    TEST_ASSERT_EQUAL_HEX8(0xEEu, first);
#if TVO_MAX_EQUALITIES == 0
    /* No equality constraints in this build: even one multiplier is beyond it. */
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_objective_reserve_multipliers(&objective, 1u, &first));
    TEST_ASSERT_EQUAL_UINT8(0u, objective.dual_dim);
#else
    ASSERT_STATUS(TVO_OK, tvo_objective_reserve_multipliers(&objective, 1u, &first));
    TEST_ASSERT_EQUAL_UINT8(TVO_MAX_OUTPUT_DIM, first);
    TEST_ASSERT_EQUAL_UINT8(1u, objective.dual_dim);
#endif
}

static void test_saddle_solve_refuses_more_multipliers_than_the_limit_and_solves_without_them(void)
{
    static tvo_matrix_t a;
    tvo_real_t b[TVO_MAX_Z_DIM] = {TVO_R(0.0)};
    tvo_real_t x[TVO_MAX_Z_DIM] = {TVO_R(0.0)};
    memset(a, 0, sizeof(a));
    a[0][0] = TVO_R(4.0);
    a[0][1] = TVO_R(1.0);
    a[1][0] = TVO_R(1.0);
    a[1][1] = TVO_R(3.0);
    b[0] = TVO_R(1.0);
    b[1] = TVO_R(2.0);
    x[0] = TVO_R(7.0);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_saddle_solve(a, 1u, (uint8_t)(TVO_MAX_EQUALITIES + 1), b, x, NULL));
    ASSERT_NEAR(7.0, x[0], 0.0); /* refused before anything was written */
    /* No multipliers: the primal solve, [4 1; 1 3] x = (1, 2) gives x = (1/11, 7/11). */
    tvo_real_t shift = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2u, 0u, b, x, &shift));
    ASSERT_ULPS(1.0 / 11.0, x[0], 8);
    ASSERT_ULPS(7.0 / 11.0, x[1], 8);
    ASSERT_NEAR(0.0, shift, 0.0);
}

/* FNV-1a over the bits of each command's fields (not the struct: padding is not compared). */
static uint64_t digest_add(uint64_t h, const void *bytes, size_t n)
{
    const unsigned char *p = (const unsigned char *)bytes;
    for (size_t i = 0; i < n; ++i) {
        h = (h ^ p[i]) * 1099511628211ull;
    }
    return h;
}

/* The law's tracking path keeps the general path's arithmetic and order (law.c), so the two agree to
 * the bit; the general path here is the one a term without a closed form takes in this build. The
 * tracking path without the general path linked (tvo_tracking_add) commands the same again. */
static void test_one_robot_tracks_through_the_closed_form_alone_or_not_and_through_jets_bit_for_bit(void)
{
    enum { steps = 1500 }; /* 15 s: three turns of the circle */
    static tvo_command_t by_jets[steps];
    setup_one_robot(BY_JETS);
    for (int n = 0; n < steps; ++n) {
        ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &by_jets[n]), by_jets[n]);
    }
    const double jets_error = fx_tracking_error(&fx, 0u);

    setup_one_robot(TRACKING_ADD);
    for (int n = 0; n < steps; ++n) {
        tvo_command_t cmd;
        ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &cmd), cmd);
        assert_commands_bit_identical(&by_jets[n], &cmd);
    }

    setup_one_robot(CLOSED_FORM);
    uint64_t digest = 14695981039346656037ull;
    for (int n = 0; n < steps; ++n) {
        tvo_command_t cmd;
        ASSERT_PERIOD(APPLIED, fx_closed_loop_step(&fx, &cmd), cmd);
        assert_commands_bit_identical(&by_jets[n], &cmd);
        digest = digest_add(digest, cmd.speed_mps, sizeof(cmd.speed_mps[0]));
        digest = digest_add(digest, cmd.turn_rate_radps, sizeof(cmd.turn_rate_radps[0]));
        digest = digest_add(digest, &cmd.flags, sizeof(cmd.flags));
    }
    const double closed_form_error = fx_tracking_error(&fx, 0u);
    /* Started 0.7 m off the circle: both converge onto it (the law's error decays like e^{-5t}). */
    ASSERT_LE(closed_form_error, 1e-3, "tracking error after 15 s, closed form (m)");
    ASSERT_LE(jets_error, 1e-3, "tracking error after 15 s, jets (m)");
    char line[96];
    /* In two halves: newlib-nano's printf (the target build) has no 64-bit conversions. */
    (void)snprintf(line, sizeof(line), "LIMITS_DIGEST one_robot_circle %08lx%08lx", (unsigned long)(digest >> 32),
                   (unsigned long)(digest & 0xFFFFFFFFu));
    TEST_MESSAGE(line);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_multipliers_beyond_the_limit_are_refused_and_leave_the_objective_as_it_was);
    RUN_TEST(test_saddle_solve_refuses_more_multipliers_than_the_limit_and_solves_without_them);
    RUN_TEST(test_one_robot_tracks_through_the_closed_form_alone_or_not_and_through_jets_bit_for_bit);
    return UNITY_END();
}
