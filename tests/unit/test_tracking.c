/*
 * Tracking term f0 = 1/2 (y_r - yd(t))^T W (y_r - yd(t)): its gradient jets.
 *
 * Along y(tau) = sum_j y_j tau^j and t(tau) = t + rate tau, the gradient is
 *   W (y(tau) - yd(t + rate tau)),   whose coefficient j is   W (y_j - yd^(j)(t) rate^j / j!).
 * With rate 1 that gives the total time derivatives; with rate 0 (Hessian columns) the target is
 * frozen and only y moves.
 */
#include "test_support.h"

#include "tvo/law.h"
#include "internal/jet.h"
#include "internal/law.h"
#include "internal/objective.h"
#include "internal/target.h"

void setUp(void) {}
void tearDown(void) {}

#define ORD TVO_JET_MAX_ORDER

/* yd(t) = (1 + 2t - t^2 + 0.5t^3, -1 + 0.25t^2 - t^3):
 *   yd'   = (2 - 2t + 1.5t^2, 0.5t - 3t^2),  yd'' = (-2 + 3t, 0.5 - 6t),  yd''' = (3, -6). */
static void poly_target(tvo_target_t *target)
{
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    c[0][0] = TVO_R(1.0);
    c[0][1] = TVO_R(2.0);
    c[0][2] = TVO_R(-1.0);
    c[0][3] = TVO_R(0.5);
    c[1][0] = TVO_R(-1.0);
    c[1][2] = TVO_R(0.25);
    c[1][3] = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(target, TEST_CONST_POLY(c)));
}

static void yd_at(double t, double yd[ORD + 1][2])
{
    yd[0][0] = 1 + 2 * t - t * t + 0.5 * t * t * t;
    yd[0][1] = -1 + 0.25 * t * t - t * t * t;
    yd[1][0] = 2 - 2 * t + 1.5 * t * t;
    yd[1][1] = 0.5 * t - 3 * t * t;
    yd[2][0] = -2 + 3 * t;
    yd[2][1] = 0.5 - 6 * t;
    yd[3][0] = 3;
    yd[3][1] = -6;
}

static const double FACT[ORD + 1] = {1, 1, 2, 6};

/* y coefficients for the robot block: y_j per axis. */
static const double YC[ORD + 1][2] = {{0.3, 0.7}, {-1.0, 0.4}, {0.25, -0.5}, {0.1, 0.05}};

static void make_y(tvo_jet_t *y, uint8_t dim, uint8_t offset)
{
    for (uint8_t i = 0; i < dim; ++i) {
        tvo_jet_constant(test_r(100.0 + i), &y[i]); /* other robots' coordinates: must be ignored */
    }
    for (uint8_t a = 0; a < 2; ++a) {
        for (int j = 0; j <= ORD; ++j) {
            y[offset + a].c[j] = test_r(YC[j][a]);
        }
    }
}

static tvo_time_jet_t time_at(double t, double rate)
{
    tvo_time_jet_t tj = test_time_jet(test_r(t), test_r(rate), 1000, (uint64_t)llround(t * 1000.0));
    return tj;
}

static void test_init_rejects_nonpositive_weights(void)
{
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const tvo_real_t w0[2] = {TVO_R(0.0), TVO_R(1.0)};
    const tvo_real_t wn[2] = {TVO_R(1.0), TVO_R(-1.0)};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_tracking_init(&term, &target, w0, 0));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_tracking_init(&term, &target, wn, 0));
}

static void test_init_rejects_non_finite_weights(void)
{
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const tvo_real_t w[2] = {TEST_NAN, TVO_R(1.0)};
    TEST_ASSERT_TRUE(tvo_tracking_init(&term, &target, w, 0) != TVO_OK);
}

static void test_init_rejects_null(void)
{
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_init(NULL, &target, w, 0));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_init(&term, NULL, w, 0));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_init(&term, &target, NULL, 0));
}

static void test_gradient_jet_along_trajectory(void)
{
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const double w[2] = {3.0, 0.5};
    const tvo_real_t wr[2] = {test_r(w[0]), test_r(w[1])};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, wr, 0));
    tvo_jet_t y[2], g[2];
    make_y(y, 2, 0);
    tvo_jet_constant(TVO_R(0.0), &g[0]);
    tvo_jet_constant(TVO_R(0.0), &g[1]);
    const tvo_time_jet_t t = time_at(0.6, 1.0);
    ASSERT_STATUS(TVO_OK, tvo_tracking_gradient_jet(&term, y, 2, &t, ORD, g));
    double yd[ORD + 1][2];
    yd_at(test_d(t.t_s), yd);
    for (int a = 0; a < 2; ++a) {
        for (int j = 0; j <= ORD; ++j) {
            ASSERT_NEAR(w[a] * (YC[j][a] - yd[j][a] / FACT[j]), g[a].c[j], TEST_TOL(16, 20.0));
        }
    }
}

static void test_gradient_jet_with_frozen_time(void)
{
    /* rate 0: the target contributes only its value; the jet's higher coefficients are W y_j. */
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const double w[2] = {3.0, 0.5};
    const tvo_real_t wr[2] = {test_r(w[0]), test_r(w[1])};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, wr, 0));
    tvo_jet_t y[2], g[2];
    make_y(y, 2, 0);
    tvo_jet_constant(TVO_R(0.0), &g[0]);
    tvo_jet_constant(TVO_R(0.0), &g[1]);
    const tvo_time_jet_t t = time_at(0.6, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_tracking_gradient_jet(&term, y, 2, &t, ORD, g));
    double yd[ORD + 1][2];
    yd_at(test_d(t.t_s), yd);
    for (int a = 0; a < 2; ++a) {
        ASSERT_NEAR(w[a] * (YC[0][a] - yd[0][a]), g[a].c[0], TEST_TOL(16, 20.0));
        for (int j = 1; j <= ORD; ++j) {
            ASSERT_NEAR(w[a] * YC[j][a], g[a].c[j], TEST_TOL(16, 20.0));
        }
    }
}

static void test_gradient_jet_accumulates_into_its_block_only(void)
{
    /* dim 6, robot at offset 2: grad[2..3] += W (y - yd); grad[0..1] and grad[4..5] untouched. */
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const tvo_real_t wr[2] = {TVO_R(1.0), TVO_R(2.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, wr, 2));
    tvo_jet_t y[6], g[6];
    make_y(y, 6, 2);
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j <= ORD; ++j) {
            g[i].c[j] = test_r(7.0 + i + 0.5 * j); /* pre-existing sum from other terms */
        }
    }
    const tvo_time_jet_t t = time_at(-0.3, 1.0);
    ASSERT_STATUS(TVO_OK, tvo_tracking_gradient_jet(&term, y, 6, &t, ORD, g));
    double yd[ORD + 1][2];
    yd_at(test_d(t.t_s), yd);
    const double w[2] = {1.0, 2.0};
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j <= ORD; ++j) {
            const double before = 7.0 + i + 0.5 * j;
            double expected = before;
            if (i == 2 || i == 3) {
                const int a = i - 2;
                expected += w[a] * (YC[j][a] - yd[j][a] / FACT[j]);
            }
            ASSERT_NEAR(expected, g[i].c[j], TEST_TOL(16, 20.0));
        }
    }
}

static void test_gradient_jet_rejects_block_outside_dimension(void)
{
    /* Offset 2 needs dim >= 4. */
    tvo_target_t target;
    poly_target(&target);
    tvo_tracking_term_t term;
    const tvo_real_t wr[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, wr, 2));
    tvo_jet_t y[3], g[3];
    make_y(y, 3, 0);
    const tvo_time_jet_t t = time_at(0.0, 1.0);
    TEST_ASSERT_TRUE(tvo_tracking_gradient_jet(&term, y, 3, &t, ORD, g) != TVO_OK);
}

static void test_gradient_jet_with_streamed_target_uses_tick_age(void)
{
    /* Streamed sample at tick 1000 (1 kHz) p = (1, 2), v = (0.5, -1), a = j = 0; evaluated at tick
     * 1400: yd = p + 0.4 v = (1.2, 1.6), yd' = v. W = I, rate 1: coefficient 0 = y0 - yd,
     * coefficient 1 = y1 - v. */
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    memset(s, 0, sizeof(s));
    s[0][0] = TVO_R(1.0);
    s[0][1] = TVO_R(2.0);
    s[1][0] = TVO_R(0.5);
    s[1][1] = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 1000, TEST_CONST_STREAM(s)));
    tvo_tracking_term_t term;
    const tvo_real_t wr[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, wr, 0));
    tvo_jet_t y[2], g[2];
    make_y(y, 2, 0);
    tvo_jet_constant(TVO_R(0.0), &g[0]);
    tvo_jet_constant(TVO_R(0.0), &g[1]);
    const tvo_time_jet_t t = time_at(1.4, 1.0);
    ASSERT_STATUS(TVO_OK, tvo_tracking_gradient_jet(&term, y, 2, &t, 1, g));
    ASSERT_NEAR(YC[0][0] - 1.2, g[0].c[0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(YC[0][1] - 1.6, g[1].c[0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(YC[1][0] - 0.5, g[0].c[1], TEST_TOL(16, 2.0));
    ASSERT_NEAR(YC[1][1] + 1.0, g[1].c[1], TEST_TOL(16, 2.0));
}

/* The closed form refuses what tvo_target_derivatives refused, in its order: a term never initialised
 * (no target) with TVO_ERR_NULL, then an order above the jets' with TVO_ERR_PARAM (also with a time
 * that is not finite), then such a time; and the law's tracking path declines the uninitialised
 * term instead of reading through it. */
static void test_closed_form_refuses_like_the_target_did(void)
{
    static tvo_tracking_term_t blank;
    memset(&blank, 0, sizeof(blank));
    tvo_jet_t y[2];
    tvo_jet_t grad[2];
    static tvo_hessian_t h;
    tvo_jet_constant(TVO_R(0.0), &y[0]);
    tvo_jet_constant(TVO_R(0.0), &y[1]);
    tvo_time_jet_t t;
    ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks(1000u, 1000u, TVO_R(1.0), &t));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_gradient_hessian(&blank, y, 2u, &t, 2u, grad, &h));
    t.t_s = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NULL, tvo_tracking_gradient_hessian(&blank, y, 2u, &t, 2u, grad, &h));

    static tvo_target_t target;
    const tvo_real_t center[2] = {TVO_R(0.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_target_init_circle(&target, center, TVO_R(1.0), TVO_R(1.0), TVO_R(0.0)));
    static tvo_tracking_term_t term;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, w, 0u));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_tracking_gradient_hessian(&term, y, 2u, &t, TVO_JET_MAX_ORDER + 1u, grad, &h));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_tracking_gradient_hessian(&term, y, 2u, &t, 2u, grad, &h));

    static tvo_objective_t objective;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&objective, 2u));
    const tvo_term_t closed = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &blank, TVO_TERM_TRACKING};
    ASSERT_STATUS(TVO_OK, tvo_objective_add(&objective, &closed));
    TEST_ASSERT_EQUAL_UINT8(1u, objective.tracking_only);
    const tvo_real_t gains[2] = {TVO_R(4.0), TVO_R(4.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2u, 2u, gains);
    tvo_output_derivs_t state;
    memset(&state, 0, sizeof(state));
    ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks(1000u, 1000u, TVO_R(1.0), &t));
    tvo_real_t out[2];
    ASSERT_STATUS(TVO_ERR_NULL, tvo_law_evaluate(&law, &objective, &state, &t, out, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_init_rejects_nonpositive_weights);
    RUN_TEST(test_init_rejects_non_finite_weights);
    RUN_TEST(test_init_rejects_null);
    RUN_TEST(test_gradient_jet_along_trajectory);
    RUN_TEST(test_gradient_jet_with_frozen_time);
    RUN_TEST(test_gradient_jet_accumulates_into_its_block_only);
    RUN_TEST(test_gradient_jet_rejects_block_outside_dimension);
    RUN_TEST(test_gradient_jet_with_streamed_target_uses_tick_age);
    RUN_TEST(test_closed_form_refuses_like_the_target_did);
    return UNITY_END();
}
