/*
 * Dirty-derivative filter D(s) = s / (T_f s + 1), ramp-invariant discretization.
 *
 * Reference: the continuous filter's response, in closed form, to the piecewise-linear input
 * through the samples (which is exactly what the ramp-invariant discretization reproduces).
 *   - ramp u = s t from rest (y(0) = 0):     y(t) = s (1 - exp(-t / T_f))
 *   - input 0 at t = 0, ramping to 1 over [0, h], then 1 (the first-order hold of a sampled step):
 *       y(t) = (1/h)(1 - exp(-t/T_f))                        for t <= h
 *       y(t) = (1/h)(1 - exp(-h/T_f)) exp(-(t - h)/T_f)      for t >= h
 *     (derivative of the input is 1/h on [0, h] and 0 after; the filter is a first-order lag of it).
 */
#include "test_support.h"

#include "tvo/dirty_derivative.h"
#include "internal/dirty_derivative.h"

void setUp(void) {}
void tearDown(void) {}

static const double TF = 0.02;  /* s */
static const double H = 0.005;  /* s */

/* Outputs are O(slope); the recursion accumulates a rounding per step: allow a few hundred ulps
 * relative over a few hundred steps (float: ~2e-5). */
#define DD_TOL(scale) TEST_TOL(200, (scale))

/* Plus the rounding of input samples of magnitude up to umax: each difference u[n+1] - u[n] is off
 * by up to eps |u|, i.e. eps |u| / h in the derivative (the filter's unit DC gain passes it on). */
static double dd_tol(double scale, double umax)
{
    return DD_TOL(scale) + 2.0 * TEST_EPS * umax / H;
}

static void init_filter(tvo_dirty_derivative_t *f, uint8_t dim)
{
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_init(f, dim, test_r(TF), test_r(H)));
}

static void test_ramp_from_reset_matches_continuous_closed_form(void)
{
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = 1.7;
    const tvo_real_t u0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &u0, NULL));
    for (int n = 1; n <= 200; ++n) {
        const double t = n * H;
        const tvo_real_t u = test_r(s * t);
        tvo_real_t y = TVO_R(-99.0);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(H), &y));
        const double expected = s * (1.0 - exp(-t / TF));
        ASSERT_NEAR(expected, y, dd_tol(s, s * t));
        ASSERT_NEAR(expected, f.output[0], dd_tol(s, s * t));
    }
}

static void test_ramp_reaches_the_slope_without_bias(void)
{
    /* After 40 T_f the transient exp(-40) is gone: the output is the ramp's slope, with no
     * dt/(2 T_f) (= 12.5 % here) bias of a zero-order-hold discretization. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = -0.8;
    const tvo_real_t u0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &u0, NULL));
    tvo_real_t y = TVO_R(0.0);
    for (int n = 1; n <= 160; ++n) {
        const tvo_real_t u = test_r(s * n * H);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(H), &y));
    }
    ASSERT_NEAR(s, y, dd_tol(s, s * 160 * H));
}

static void test_unprimed_filter_primes_with_zero_output(void)
{
    /* Without reset the first sample primes (output 0); from then on the ramp response is the same
     * closed form, with t counted from the priming sample. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = 2.5;
    const double u_start = 3.0; /* the ramp starts from an offset: only differences matter */
    tvo_real_t y = TVO_R(-99.0);
    tvo_real_t u = test_r(u_start);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(H), &y));
    ASSERT_NEAR(0.0, y, 0.0);
    for (int n = 1; n <= 100; ++n) {
        const double t = n * H;
        u = test_r(u_start + s * t);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(H), &y));
        /* u_start + s t rounds to float; the reference uses the rounded samples' slope. */
        ASSERT_NEAR(s * (1.0 - exp(-t / TF)), y, dd_tol(s, u_start + s * t));
    }
}

static void test_step_matches_first_order_hold_closed_form(void)
{
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const tvo_real_t zero = TVO_R(0.0);
    const tvo_real_t one = TVO_R(1.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &zero, NULL)); /* sample 0: u = 0 */
    const double peak = (1.0 / H) * (1.0 - exp(-H / TF));
    for (int n = 1; n <= 60; ++n) {
        tvo_real_t y = TVO_R(-99.0);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &one, test_r(H), &y));
        const double t = n * H;
        const double expected = (n == 1) ? (1.0 / H) * (1.0 - exp(-t / TF)) : peak * exp(-(t - H) / TF);
        ASSERT_NEAR(expected, y, DD_TOL(1.0 / H));
    }
}

static void test_dropped_sample_uses_the_actual_interval(void)
{
    /* Ramp sampled at h, 2h, 3h, then 5h (the 4h sample was dropped, dt = 2h), 6h, 7h. The input is
     * still linear between samples, so the outputs still equal the continuous closed form. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = 1.3;
    const tvo_real_t u0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &u0, NULL));
    const int sample[] = {1, 2, 3, 5, 6, 7};
    int prev = 0;
    for (size_t i = 0; i < sizeof(sample) / sizeof(sample[0]); ++i) {
        const double t = sample[i] * H;
        const double dt = (sample[i] - prev) * H;
        const tvo_real_t u = test_r(s * t);
        tvo_real_t y = TVO_R(-99.0);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(dt), &y));
        ASSERT_NEAR(s * (1.0 - exp(-t / TF)), y, dd_tol(s, s * t));
        prev = sample[i];
    }
}

static void test_step_response_across_a_dropped_sample(void)
{
    /* After the step, a 2h gap with the input constant: the output decays by exp(-2h/T_f). */
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const tvo_real_t zero = TVO_R(0.0);
    const tvo_real_t one = TVO_R(1.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &zero, NULL));
    tvo_real_t y;
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &one, test_r(H), &y));
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &one, test_r(2.0 * H), &y));
    const double expected = (1.0 / H) * (1.0 - exp(-H / TF)) * exp(-2.0 * H / TF);
    ASSERT_NEAR(expected, y, DD_TOL(1.0 / H));
}

static void test_non_nominal_interval_ramp(void)
{
    /* An interval that is not a multiple of the period (jitter: 0.7 h) is discretized exactly too. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = 0.9;
    const tvo_real_t u0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &u0, NULL));
    double t = 0.0;
    for (int n = 1; n <= 30; ++n) {
        const double dt = (n % 2 == 0) ? 0.7 * H : 1.3 * H;
        t += test_d(test_r(dt)); /* the filter sees the rounded interval */
        const tvo_real_t u = test_r(s * t);
        tvo_real_t y;
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(dt), &y));
        ASSERT_NEAR(s * (1.0 - exp(-t / TF)), y, dd_tol(s, s * t));
    }
}

static void test_reset_with_initial_output_is_steady_on_that_ramp(void)
{
    /* "As if the input had been moving at y0 forever": a ramp of slope y0 continues at exactly y0. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 2);
    const tvo_real_t u0[2] = {TVO_R(1.0), TVO_R(-2.0)};
    const tvo_real_t y0[2] = {TVO_R(0.6), TVO_R(-1.4)};
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, u0, y0));
    for (int n = 1; n <= 50; ++n) {
        const tvo_real_t u[2] = {test_r(1.0 + 0.6 * n * H), test_r(-2.0 - 1.4 * n * H)};
        tvo_real_t y[2];
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, u, test_r(H), y));
        ASSERT_NEAR(0.6, y[0], dd_tol(0.6, 1.2));
        ASSERT_NEAR(-1.4, y[1], dd_tol(1.4, 2.4));
    }
}

static void test_channels_are_independent(void)
{
    /* Three channels: a ramp, a constant and a reversed ramp, filtered together. */
    tvo_dirty_derivative_t f;
    init_filter(&f, 3);
    const tvo_real_t u0[3] = {TVO_R(0.0), TVO_R(5.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, u0, NULL));
    for (int n = 1; n <= 40; ++n) {
        const double t = n * H;
        const tvo_real_t u[3] = {test_r(2.0 * t), TVO_R(5.0), test_r(-0.5 * t)};
        tvo_real_t y[3];
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, u, test_r(H), y));
        const double g = 1.0 - exp(-t / TF);
        ASSERT_NEAR(2.0 * g, y[0], dd_tol(2.0, 2.0 * t));
        ASSERT_NEAR(0.0, y[1], 0.0);
        ASSERT_NEAR(-0.5 * g, y[2], dd_tol(0.5, 0.5 * t));
    }
}

static void test_init_caches_nominal_decay(void)
{
    tvo_dirty_derivative_t f;
    init_filter(&f, 4);
    TEST_ASSERT_EQUAL_UINT8(4, f.dim);
    TEST_ASSERT_EQUAL_UINT8(0, f.primed);
    ASSERT_ULPS(exp(-H / TF), f.period_decay, 4);
}

static void test_init_rejects_nonpositive_time_constant(void)
{
    tvo_dirty_derivative_t f;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_dirty_derivative_init(&f, 1, TVO_R(0.0), test_r(H)));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_dirty_derivative_init(&f, 1, TVO_R(-0.01), test_r(H)));
}

static void test_init_rejects_nonpositive_period(void)
{
    tvo_dirty_derivative_t f;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_dirty_derivative_init(&f, 1, test_r(TF), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_dirty_derivative_init(&f, 1, test_r(TF), TVO_R(-0.005)));
}

static void test_init_rejects_nan(void)
{
    /* NaN compares false against everything: it must not slip through a "> 0" check. Either
     * "not finite" or "out of range" names the problem. */
    tvo_dirty_derivative_t f;
    const tvo_status_t a = tvo_dirty_derivative_init(&f, 1, TEST_NAN, test_r(H));
    const tvo_status_t b = tvo_dirty_derivative_init(&f, 1, test_r(TF), TEST_NAN);
    TEST_ASSERT_TRUE_MESSAGE(a == TVO_ERR_NOT_FINITE || a == TVO_ERR_PARAM, "NaN T_f accepted");
    TEST_ASSERT_TRUE_MESSAGE(b == TVO_ERR_NOT_FINITE || b == TVO_ERR_PARAM, "NaN period accepted");
}

static void test_init_rejects_dimension_zero_and_above_maximum(void)
{
    tvo_dirty_derivative_t f;
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_dirty_derivative_init(&f, 0, test_r(TF), test_r(H)));
    ASSERT_STATUS(TVO_ERR_DIMENSION,
                  tvo_dirty_derivative_init(&f, (uint8_t)(TVO_MAX_OUTPUT_DIM + 1), test_r(TF), test_r(H)));
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_init(&f, (uint8_t)TVO_MAX_OUTPUT_DIM, test_r(TF), test_r(H)));
}

static void test_init_rejects_null(void)
{
    ASSERT_STATUS(TVO_ERR_NULL, tvo_dirty_derivative_init(NULL, 1, test_r(TF), test_r(H)));
}

/* Runs a ramp to a known state, then a rejected step, then a valid step: the valid step's output
 * must equal the ramp closed form as if the rejected call had never happened. */
static void assert_rejected_step_leaves_state(tvo_real_t bad_u, tvo_real_t bad_dt, tvo_status_t expected)
{
    tvo_dirty_derivative_t f;
    init_filter(&f, 1);
    const double s = 1.0;
    const tvo_real_t u0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_reset(&f, &u0, NULL));
    tvo_real_t y;
    for (int n = 1; n <= 5; ++n) {
        const tvo_real_t u = test_r(s * n * H);
        ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u, test_r(H), &y));
    }
    const tvo_status_t st = tvo_dirty_derivative_step(&f, &bad_u, bad_dt, &y);
    if (expected == TVO_OK) {
        TEST_ASSERT_TRUE_MESSAGE(st != TVO_OK, "invalid step accepted");
    } else {
        ASSERT_STATUS(expected, st);
    }
    const tvo_real_t u6 = test_r(s * 6.0 * H);
    ASSERT_STATUS(TVO_OK, tvo_dirty_derivative_step(&f, &u6, test_r(H), &y));
    ASSERT_NEAR(s * (1.0 - exp(-6.0 * H / TF)), y, dd_tol(s, s * 6.0 * H));
}

static void test_step_rejects_zero_interval(void)
{
    /* The status for dt <= 0 is not pinned by the header (range or ordering): any error will do. */
    assert_rejected_step_leaves_state(test_r(6.0 * H), TVO_R(0.0), TVO_OK);
}

static void test_step_rejects_negative_interval(void)
{
    assert_rejected_step_leaves_state(test_r(6.0 * H), test_r(-H), TVO_OK);
}

static void test_step_rejects_nan_interval(void)
{
    assert_rejected_step_leaves_state(test_r(6.0 * H), TEST_NAN, TVO_OK);
}

static void test_step_rejects_nan_input(void)
{
    assert_rejected_step_leaves_state(TEST_NAN, test_r(H), TVO_ERR_NOT_FINITE);
}

static void test_step_rejects_infinite_input(void)
{
    assert_rejected_step_leaves_state(TEST_INF, test_r(H), TVO_ERR_NOT_FINITE);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_ramp_from_reset_matches_continuous_closed_form);
    RUN_TEST(test_ramp_reaches_the_slope_without_bias);
    RUN_TEST(test_unprimed_filter_primes_with_zero_output);
    RUN_TEST(test_step_matches_first_order_hold_closed_form);
    RUN_TEST(test_dropped_sample_uses_the_actual_interval);
    RUN_TEST(test_step_response_across_a_dropped_sample);
    RUN_TEST(test_non_nominal_interval_ramp);
    RUN_TEST(test_reset_with_initial_output_is_steady_on_that_ramp);
    RUN_TEST(test_channels_are_independent);
    RUN_TEST(test_init_caches_nominal_decay);
    RUN_TEST(test_init_rejects_nonpositive_time_constant);
    RUN_TEST(test_init_rejects_nonpositive_period);
    RUN_TEST(test_init_rejects_nan);
    RUN_TEST(test_init_rejects_dimension_zero_and_above_maximum);
    RUN_TEST(test_init_rejects_null);
    RUN_TEST(test_step_rejects_zero_interval);
    RUN_TEST(test_step_rejects_negative_interval);
    RUN_TEST(test_step_rejects_nan_interval);
    RUN_TEST(test_step_rejects_nan_input);
    RUN_TEST(test_step_rejects_infinite_input);
    return UNITY_END();
}
