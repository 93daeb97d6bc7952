/*
 * Targets y_d(t) and their time derivatives, against hand-differentiated closed forms.
 *
 * The derivatives are the plain time derivatives d^j y_d / dt^j at t: the time jet's rate (1 along
 * the trajectory, 0 for Hessian columns, see objective.h) is the tracking term's business, not the
 * target's, so the same values come out whatever the rate.
 */
#include "test_support.h"
#include "internal/objective.h"
#include "internal/target.h"

void setUp(void) {}
void tearDown(void) {}

#define ORD TVO_JET_MAX_ORDER

static tvo_time_jet_t time_at(double t_s, double rate)
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), test_r(rate), 1000u, (uint64_t)llround(t_s * 1000.0));
    return t;
}

static void fill(tvo_real_t d[ORD + 1][2], double v)
{
    for (int j = 0; j <= ORD; ++j) {
        d[j][0] = test_r(v);
        d[j][1] = test_r(v);
    }
}

static void assert_derivs(double e[ORD + 1][2], tvo_real_t d[ORD + 1][2], uint8_t order,
                          double scale)
{
    for (uint8_t j = 0; j <= order; ++j) {
        for (uint8_t a = 0; a < 2; ++a) {
            char msg[48];
            (void)snprintf(msg, sizeof(msg), "derivative %u axis %u", (unsigned)j, (unsigned)a);
            ASSERT_NEAR_MSG(e[j][a], d[j][a], TEST_TOL(64, scale), msg);
        }
    }
}

/* ------------------------------------------------------------------------------------------------
 * Polynomial
 * --------------------------------------------------------------------------------------------- */

/*
 * x(t) = 1 - 2t + 0.5t^2 + 0.25t^3 + 0.1t^7        y(t) = 3 + 0.2t - t^2 + 0.05t^5
 * x'   = -2 + t + 0.75t^2 + 0.7t^6                 y'   = 0.2 - 2t + 0.25t^4
 * x''  = 1 + 1.5t + 4.2t^5                         y''  = -2 + t^3
 * x''' = 1.5 + 21t^4                               y''' = 3t^2
 */
static void poly_init(tvo_target_t *target)
{
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    c[0][0] = TVO_R(1.0);
    c[0][1] = TVO_R(-2.0);
    c[0][2] = TVO_R(0.5);
    c[0][3] = TVO_R(0.25);
    c[0][7] = TVO_R(0.1);
    c[1][0] = TVO_R(3.0);
    c[1][1] = TVO_R(0.2);
    c[1][2] = TVO_R(-1.0);
    c[1][5] = TVO_R(0.05);
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(target, TEST_CONST_POLY(c)));
}

static void poly_expected(double t, double e[ORD + 1][2])
{
    e[0][0] = 1 - 2 * t + 0.5 * t * t + 0.25 * pow(t, 3) + 0.1 * pow(t, 7);
    e[1][0] = -2 + t + 0.75 * t * t + 0.7 * pow(t, 6);
    e[2][0] = 1 + 1.5 * t + 4.2 * pow(t, 5);
    e[3][0] = 1.5 + 21 * pow(t, 4);
    e[0][1] = 3 + 0.2 * t - t * t + 0.05 * pow(t, 5);
    e[1][1] = 0.2 - 2 * t + 0.25 * pow(t, 4);
    e[2][1] = -2 + pow(t, 3);
    e[3][1] = 3 * t * t;
}

static void test_polynomial_derivatives_match_hand_derivation(void)
{
    tvo_target_t target;
    poly_init(&target);
    const double ts[] = {0.0, 1.3, -0.7, 2.0};
    for (size_t i = 0; i < sizeof(ts) / sizeof(ts[0]); ++i) {
        const tvo_time_jet_t t = time_at(ts[i], 1.0);
        tvo_real_t d[ORD + 1][2];
        fill(d, -99.0);
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
        double e[ORD + 1][2];
        poly_expected(test_d(t.t_s), e);
        assert_derivs(e, d, ORD, 21.0 * pow(fabs(ts[i]) + 1.0, 4) + 0.1 * pow(fabs(ts[i]), 7));
    }
}

static void test_polynomial_lower_order_gives_the_same_leading_derivatives(void)
{
    tvo_target_t target;
    poly_init(&target);
    const tvo_time_jet_t t = time_at(0.9, 1.0);
    double e[ORD + 1][2];
    poly_expected(test_d(t.t_s), e);
    for (uint8_t order = 0; order <= ORD; ++order) {
        tvo_real_t d[ORD + 1][2];
        fill(d, -99.0);
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, order, d));
        assert_derivs(e, d, order, 25.0);
    }
}

static void test_polynomial_derivatives_do_not_depend_on_jet_rate(void)
{
    tvo_target_t target;
    poly_init(&target);
    const tvo_time_jet_t t1 = time_at(1.3, 1.0);
    const tvo_time_jet_t t0 = time_at(1.3, 0.0);
    tvo_real_t d1[ORD + 1][2], d0[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t1, ORD, d1));
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t0, ORD, d0));
    TEST_ASSERT_EQUAL_MEMORY(d1, d0, sizeof(d1));
    double e[ORD + 1][2];
    poly_expected(test_d(t0.t_s), e);
    assert_derivs(e, d0, ORD, 70.0);
}

static void test_polynomial_rejects_non_finite_coefficient(void)
{
    tvo_target_t target;
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    c[1][TVO_POLY_MAX_DEGREE] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_polynomial(&target, TEST_CONST_POLY(c)));
    c[1][TVO_POLY_MAX_DEGREE] = TEST_INF;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_polynomial(&target, TEST_CONST_POLY(c)));
}

/* ------------------------------------------------------------------------------------------------
 * Circle and ellipse
 * --------------------------------------------------------------------------------------------- */

/*
 * Circle, phi = w t + p:  y = c + r (cos phi, sin phi)
 *   y'   = r w   (-sin phi,  cos phi)
 *   y''  = r w^2 (-cos phi, -sin phi)
 *   y''' = r w^3 ( sin phi, -cos phi)
 */
static void circle_expected(double cx, double cy, double r, double w, double p, double t, double e[ORD + 1][2])
{
    const double phi = w * t + p;
    const double c = cos(phi), s = sin(phi);
    e[0][0] = cx + r * c;
    e[0][1] = cy + r * s;
    e[1][0] = -r * w * s;
    e[1][1] = r * w * c;
    e[2][0] = -r * w * w * c;
    e[2][1] = -r * w * w * s;
    e[3][0] = r * w * w * w * s;
    e[3][1] = -r * w * w * w * c;
}

static void test_circle_derivatives_match_closed_form(void)
{
    const tvo_real_t centre[2] = {TVO_R(1.0), TVO_R(-2.0)};
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_circle(&target, centre, TVO_R(0.5), TVO_R(2.0), TVO_R(0.3)));
    const double ts[] = {0.0, 0.37, 5.1};
    for (size_t i = 0; i < sizeof(ts) / sizeof(ts[0]); ++i) {
        const tvo_time_jet_t t = time_at(ts[i], 1.0);
        tvo_real_t d[ORD + 1][2];
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
        double e[ORD + 1][2];
        circle_expected(1.0, -2.0, 0.5, 2.0, 0.3, test_d(t.t_s), e);
        assert_derivs(e, d, ORD, 12.0);
    }
}

static void test_circle_with_negative_rate_runs_clockwise(void)
{
    /* w = -2 pi / 10 (clockwise), phase pi/2: at t = 2.5 the parameter is pi/2 - pi/2 = 0. */
    const tvo_real_t centre[2] = {TVO_R(0.0), TVO_R(0.0)};
    const double w = -2.0 * TEST_PI / 10.0;
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_circle(&target, centre, TVO_R(1.0), test_r(w), test_r(TEST_PI / 2.0)));
    const tvo_time_jet_t t = time_at(2.5, 1.0);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
    double e[ORD + 1][2];
    circle_expected(0.0, 0.0, 1.0, w, TEST_PI / 2.0, 2.5, e);
    assert_derivs(e, d, ORD, 2.0);
    /* Hand values: at phi = 0 the target is at (1, 0) moving with velocity (0, w) = downward. */
    ASSERT_NEAR(1.0, d[0][0], TEST_TOL(64, 1.0));
    ASSERT_NEAR(w, d[1][1], TEST_TOL(64, 1.0));
}

/*
 * Ellipse: p(phi) = (a cos phi, b sin phi), y = c + R(rho) p,
 *   y^(j) = R(rho) (a cos^(j)(phi), b sin^(j)(phi)) w^j  (j >= 1),
 * with cos^(j) = cos, -sin, -cos, sin and sin^(j) = sin, cos, -sin, -cos.
 */
static void ellipse_expected(const tvo_target_ellipse_t *el, double t, double e[ORD + 1][2])
{
    const double a = test_d(el->semi_axis_m[0]), b = test_d(el->semi_axis_m[1]);
    const double w = test_d(el->omega_radps), rho = test_d(el->rotation_rad);
    const double phi = w * t + test_d(el->phase_rad);
    const double c = cos(phi), s = sin(phi);
    const double dc[4] = {c, -s, -c, s};
    const double ds[4] = {s, c, -s, -c};
    double wj = 1.0;
    for (int j = 0; j <= ORD; ++j) {
        const double u = a * dc[j] * wj, v = b * ds[j] * wj;
        e[j][0] = cos(rho) * u - sin(rho) * v;
        e[j][1] = sin(rho) * u + cos(rho) * v;
        wj *= w;
    }
    e[0][0] += test_d(el->center_m[0]);
    e[0][1] += test_d(el->center_m[1]);
}

static tvo_target_ellipse_t ellipse_params(void)
{
    tvo_target_ellipse_t el;
    el.center_m[0] = TVO_R(-1.0);
    el.center_m[1] = TVO_R(0.5);
    el.semi_axis_m[0] = TVO_R(2.0);
    el.semi_axis_m[1] = TVO_R(0.75);
    el.omega_radps = TVO_R(1.3);
    el.phase_rad = TVO_R(-0.4);
    el.rotation_rad = TVO_R(0.6);
    el.rate_turns_q64 = 0u;
    return el;
}

static void test_ellipse_derivatives_match_closed_form(void)
{
    const tvo_target_ellipse_t el = ellipse_params();
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(&target, &el));
    const double ts[] = {0.0, 0.8, 3.3};
    for (size_t i = 0; i < sizeof(ts) / sizeof(ts[0]); ++i) {
        const tvo_time_jet_t t = time_at(ts[i], 1.0);
        tvo_real_t d[ORD + 1][2];
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
        double e[ORD + 1][2];
        ellipse_expected(&el, test_d(t.t_s), e);
        assert_derivs(e, d, ORD, 8.0);
    }
}

static void test_ellipse_hand_point_at_zero_phase(void)
{
    /* phi = 0 (t = 0, phase 0), rotation pi/2: p = (a, 0) -> R p = (0, a); p' = (0, b w) -> (-b w, 0). */
    tvo_target_ellipse_t el = ellipse_params();
    el.phase_rad = TVO_R(0.0);
    el.rotation_rad = test_r(TEST_PI / 2.0);
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(&target, &el));
    const tvo_time_jet_t t = time_at(0.0, 1.0);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, 1, d));
    ASSERT_NEAR(-1.0 + 0.0, d[0][0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(0.5 + 2.0, d[0][1], TEST_TOL(16, 2.0));
    ASSERT_NEAR(-0.75 * 1.3, d[1][0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(0.0, d[1][1], TEST_TOL(16, 2.0));
}

static void test_ellipse_derivatives_do_not_depend_on_jet_rate(void)
{
    const tvo_target_ellipse_t el = ellipse_params();
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(&target, &el));
    const tvo_time_jet_t t1 = time_at(0.8, 1.0);
    const tvo_time_jet_t t0 = time_at(0.8, 0.0);
    tvo_real_t d1[ORD + 1][2], d0[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t1, ORD, d1));
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t0, ORD, d0));
    TEST_ASSERT_EQUAL_MEMORY(d1, d0, sizeof(d1));
}

static void test_circle_rejects_nonpositive_radius(void)
{
    const tvo_real_t centre[2] = {TVO_R(0.0), TVO_R(0.0)};
    tvo_target_t target;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_circle(&target, centre, TVO_R(0.0), TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_circle(&target, centre, TVO_R(-1.0), TVO_R(1.0), TVO_R(0.0)));
}

static void test_circle_rejects_non_finite_values(void)
{
    const tvo_real_t centre[2] = {TVO_R(0.0), TVO_R(0.0)};
    const tvo_real_t bad_centre[2] = {TEST_NAN, TVO_R(0.0)};
    tvo_target_t target;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_circle(&target, bad_centre, TVO_R(1.0), TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_circle(&target, centre, TEST_NAN, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_circle(&target, centre, TVO_R(1.0), TEST_INF, TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_circle(&target, centre, TVO_R(1.0), TVO_R(1.0), TEST_NAN));
}

static void test_ellipse_rejects_nonpositive_semi_axes(void)
{
    tvo_target_ellipse_t el = ellipse_params();
    tvo_target_t target;
    el.semi_axis_m[0] = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_ellipse(&target, &el));
    el = ellipse_params();
    el.semi_axis_m[1] = TVO_R(-0.5);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_ellipse(&target, &el));
    el = ellipse_params();
    el.rotation_rad = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_init_ellipse(&target, &el));
}

static void test_ellipse_rejects_a_rate_beyond_the_bound_and_runs_at_it(void)
{
    tvo_target_ellipse_t el = ellipse_params();
    tvo_target_t target;
    el.omega_radps = TVO_TARGET_MAX_OMEGA_RADPS * TVO_R(1.0001);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_ellipse(&target, &el));
    el.omega_radps = -el.omega_radps;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_ellipse(&target, &el));
    const tvo_real_t centre[2] = {TVO_R(0.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_init_circle(&target, centre, TVO_R(1.0), el.omega_radps, TVO_R(0.0)));
    /* At the bound (either sign), the fraction of a second just below one adds the largest angle:
     * still evaluated, every derivative the law reads. */
    for (int sign = -1; sign <= 1; sign += 2) {
        el.omega_radps = (tvo_real_t)sign * TVO_TARGET_MAX_OMEGA_RADPS;
        ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(&target, &el));
        const tvo_time_jet_t t = time_at(3.999, 1.0);
        TEST_ASSERT_EQUAL_UINT32(t.tick_hz - 1u, t.frac_ticks);
        tvo_real_t d[ORD + 1][2];
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, (uint8_t)ORD, d));
        double e[ORD + 1][2];
        ellipse_expected(&el, 3.999, e);
        /* The angle is known to float32's rounding of the product omega t (~1e-3 rad here), not
         * better: derivative j, of amplitude up to 2 omega^j, to 1e-2 omega^j. */
        double scale = 1.0;
        for (int j = 0; j <= ORD; ++j) {
            ASSERT_NEAR(e[j][0], d[j][0], 1e-2 * scale);
            ASSERT_NEAR(e[j][1], d[j][1], 1e-2 * scale);
            scale *= (double)TVO_TARGET_MAX_OMEGA_RADPS;
        }
    }
}

static void test_derivatives_reject_order_above_maximum(void)
{
    tvo_target_t target;
    poly_init(&target);
    const tvo_time_jet_t t = time_at(0.5, 1.0);
    tvo_real_t d[ORD + 1][2];
    TEST_ASSERT_TRUE(tvo_target_derivatives(&target, &t, (uint8_t)(ORD + 1), d) != TVO_OK);
}

static void test_derivatives_reject_non_finite_time(void)
{
    tvo_target_t target;
    poly_init(&target);
    tvo_time_jet_t t = time_at(0.5, 1.0);
    t.t_s = TEST_NAN;
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_derivatives(&target, &t, ORD, d));
}

static void test_target_functions_reject_null(void)
{
    tvo_target_t target;
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    const tvo_time_jet_t t = time_at(0.5, 1.0);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_init_polynomial(NULL, TEST_CONST_POLY(c)));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_init_ellipse(&target, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_init_streamed(NULL));
    poly_init(&target);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_derivatives(NULL, &t, ORD, d));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_derivatives(&target, NULL, ORD, d));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_derivatives(&target, &t, ORD, NULL));
}

/* ------------------------------------------------------------------------------------------------
 * Streamed
 * --------------------------------------------------------------------------------------------- */

/* Sample: position (1, -2), velocity (0.5, 0.25), acceleration (-0.2, 0.4), jerk (0.06, -0.12). */
static void stream_sample(tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2])
{
    s[0][0] = TVO_R(1.0);
    s[0][1] = TVO_R(-2.0);
    s[1][0] = TVO_R(0.5);
    s[1][1] = TVO_R(0.25);
    s[2][0] = TVO_R(-0.2);
    s[2][1] = TVO_R(0.4);
    s[3][0] = TVO_R(0.06);
    s[3][1] = TVO_R(-0.12);
}

/* Causal Taylor extrapolation over age T:
 *   p + v T + a T^2/2 + j T^3/6,   v + a T + j T^2/2,   a + j T,   j. */
static void stream_expected(tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2], double T, double e[ORD + 1][2])
{
    for (int axis = 0; axis < 2; ++axis) {
        const double p = test_d(s[0][axis]), v = test_d(s[1][axis]);
        const double a = test_d(s[2][axis]), j = test_d(s[3][axis]);
        e[0][axis] = p + v * T + a * T * T / 2.0 + j * T * T * T / 6.0;
        e[1][axis] = v + a * T + j * T * T / 2.0;
        e[2][axis] = a + j * T;
        e[3][axis] = j;
    }
}

static tvo_time_jet_t ticks_time(uint64_t ticks, uint32_t hz)
{
    tvo_time_jet_t t = test_time_jet(tvo_ticks_to_seconds(ticks, hz), TVO_R(1.0), hz, ticks);
    return t;
}

/* Without a sample a streamed target is not ready (the step's reason); evaluating it anyway is misuse. */
static void test_streamed_is_not_ready_before_a_sample(void)
{
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    const tvo_time_jet_t t = ticks_time(1000, 1000);
    tvo_real_t d[ORD + 1][2];
    TEST_ASSERT_EQUAL_INT(TVO_REASON_TARGET_NOT_READY, target_ready_at(&target, t.ticks));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_target_derivatives(&target, &t, ORD, d));
}

static void test_streamed_at_its_stamp_returns_the_sample(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    const tvo_time_jet_t t = ticks_time(5000, 1000);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
    for (int j = 0; j <= ORD; ++j) {
        ASSERT_NEAR(s[j][0], d[j][0], 0.0);
        ASSERT_NEAR(s[j][1], d[j][1], 0.0);
    }
}

static void test_streamed_extrapolates_by_taylor_polynomial(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    const uint64_t ages_ms[] = {1, 10, 250, 1500};
    for (size_t i = 0; i < sizeof(ages_ms) / sizeof(ages_ms[0]); ++i) {
        const tvo_time_jet_t t = ticks_time(5000 + ages_ms[i], 1000);
        tvo_real_t d[ORD + 1][2];
        ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
        double e[ORD + 1][2];
        stream_expected(s, (double)ages_ms[i] / 1000.0, e);
        assert_derivs(e, d, ORD, 3.0);
    }
}

static void test_streamed_age_is_exact_far_from_the_epoch(void)
{
    /* Stamp 2^40 + 3 us after the epoch (12.7 days): t_s in float has a resolution of 0.125 s there,
     * but the age comes from integer ticks and must be exactly 0.25 s. */
    const uint64_t stamp = (1ull << 40) + 3u;
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, stamp, TEST_CONST_STREAM(s)));
    const tvo_time_jet_t t = ticks_time(stamp + 250000u, 1000000u);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
    double e[ORD + 1][2];
    stream_expected(s, 0.25, e);
    assert_derivs(e, d, ORD, 3.0);
}

static void test_streamed_age_beyond_two_to_the_32_ticks_keeps_float_precision(void)
{
    /* 2^33 + 0.5e6 ticks at 1 MHz: an age of 8590.434592 s, converted without a 64-bit division. */
    const uint64_t stamp = 5u;
    const uint64_t age_ticks = (1ull << 33) + 500000u;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2] = {{TVO_R(1.0), TVO_R(2.0)}, {TVO_R(0.5), TVO_R(-0.25)}};
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, stamp, TEST_CONST_STREAM(s)));
    const tvo_time_jet_t t = ticks_time(stamp + age_ticks, 1000000u);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, 1u, d));
    const double age_s = (double)age_ticks / 1e6;
    ASSERT_NEAR(1.0 + 0.5 * age_s, d[0][0], 8.0 * TEST_EPS * (1.0 + 0.5 * age_s));
    ASSERT_NEAR(2.0 - 0.25 * age_s, d[0][1], 8.0 * TEST_EPS * (0.25 * age_s));
    ASSERT_NEAR(0.5, d[1][0], TEST_TOL(8, 1.0));
}

static void test_streamed_derivatives_do_not_depend_on_jet_rate(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    tvo_time_jet_t t1 = ticks_time(5300, 1000);
    tvo_time_jet_t t0 = t1;
    t0.rate = TVO_R(0.0);
    tvo_real_t d1[ORD + 1][2], d0[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t1, ORD, d1));
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t0, ORD, d0));
    TEST_ASSERT_EQUAL_MEMORY(d1, d0, sizeof(d1));
}

/* Before its stamp a streamed target is stamped in the future (the step's reason); evaluating it there
 * is misuse (causal extrapolation only); from the stamp on it is ready. */
static void test_streamed_before_its_stamp_is_a_future_stamp_error(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    const tvo_time_jet_t t = ticks_time(4999, 1000);
    tvo_real_t d[ORD + 1][2];
    TEST_ASSERT_EQUAL_INT(TVO_REASON_FUTURE_STAMP, target_ready_at(&target, t.ticks));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_derivatives(&target, &t, ORD, d));
    TEST_ASSERT_EQUAL_INT(TVO_REASON_NONE, target_ready_at(&target, 5000u));
}

static void test_streamed_rejects_non_finite_sample_and_keeps_the_old_one(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    tvo_real_t bad[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(bad);
    bad[0][0] = TVO_R(100.0);
    bad[3][1] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_stream_update(&target, 6000, TEST_CONST_STREAM(bad)));
    bad[3][1] = TEST_INF;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_target_stream_update(&target, 6000, TEST_CONST_STREAM(bad)));
    const tvo_time_jet_t t = ticks_time(5250, 1000);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
    double e[ORD + 1][2];
    stream_expected(s, 0.25, e);
    assert_derivs(e, d, ORD, 3.0);
}

static void test_streamed_rejects_stamps_that_do_not_advance(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    tvo_real_t other[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(other);
    other[0][0] = TVO_R(100.0);
    ASSERT_STATUS(TVO_ERR_TICK_NOT_ADVANCING, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(other)));
    ASSERT_STATUS(TVO_ERR_TICK_NOT_ADVANCING, tvo_target_stream_update(&target, 4000, TEST_CONST_STREAM(other)));
    /* The original sample is still the one in force. */
    const tvo_time_jet_t t = ticks_time(5000, 1000);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, 0, d));
    ASSERT_NEAR(1.0, d[0][0], 0.0);
}

static void test_streamed_newer_sample_replaces_the_old_one(void)
{
    tvo_target_t target;
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)));
    tvo_real_t s2[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s2);
    s2[0][0] = TVO_R(4.0);
    s2[1][1] = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&target, 5100, TEST_CONST_STREAM(s2)));
    const tvo_time_jet_t t = ticks_time(5200, 1000);
    tvo_real_t d[ORD + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&target, &t, ORD, d));
    double e[ORD + 1][2];
    stream_expected(s2, 0.1, e);
    assert_derivs(e, d, ORD, 5.0);
    /* Asking for a time between the two stamps is now before the stamp in force. */
    const tvo_time_jet_t early = ticks_time(5050, 1000);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_target_derivatives(&target, &early, ORD, d));
}

static void test_stream_update_rejects_non_streamed_target(void)
{
    tvo_target_t target;
    poly_init(&target);
    tvo_real_t s[TVO_STREAM_MAX_DERIV + 1][2];
    stream_sample(s);
    TEST_ASSERT_TRUE(tvo_target_stream_update(&target, 5000, TEST_CONST_STREAM(s)) != TVO_OK);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_target_stream_update(NULL, 5000, TEST_CONST_STREAM(s)));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_polynomial_derivatives_match_hand_derivation);
    RUN_TEST(test_polynomial_lower_order_gives_the_same_leading_derivatives);
    RUN_TEST(test_polynomial_derivatives_do_not_depend_on_jet_rate);
    RUN_TEST(test_polynomial_rejects_non_finite_coefficient);
    RUN_TEST(test_circle_derivatives_match_closed_form);
    RUN_TEST(test_circle_with_negative_rate_runs_clockwise);
    RUN_TEST(test_ellipse_derivatives_match_closed_form);
    RUN_TEST(test_ellipse_hand_point_at_zero_phase);
    RUN_TEST(test_ellipse_derivatives_do_not_depend_on_jet_rate);
    RUN_TEST(test_circle_rejects_nonpositive_radius);
    RUN_TEST(test_circle_rejects_non_finite_values);
    RUN_TEST(test_ellipse_rejects_nonpositive_semi_axes);
    RUN_TEST(test_ellipse_rejects_a_rate_beyond_the_bound_and_runs_at_it);
    RUN_TEST(test_derivatives_reject_order_above_maximum);
    RUN_TEST(test_derivatives_reject_non_finite_time);
    RUN_TEST(test_target_functions_reject_null);
    RUN_TEST(test_streamed_is_not_ready_before_a_sample);
    RUN_TEST(test_streamed_at_its_stamp_returns_the_sample);
    RUN_TEST(test_streamed_extrapolates_by_taylor_polynomial);
    RUN_TEST(test_streamed_age_is_exact_far_from_the_epoch);
    RUN_TEST(test_streamed_age_beyond_two_to_the_32_ticks_keeps_float_precision);
    RUN_TEST(test_streamed_derivatives_do_not_depend_on_jet_rate);
    RUN_TEST(test_streamed_before_its_stamp_is_a_future_stamp_error);
    RUN_TEST(test_streamed_rejects_non_finite_sample_and_keeps_the_old_one);
    RUN_TEST(test_streamed_rejects_stamps_that_do_not_advance);
    RUN_TEST(test_streamed_newer_sample_replaces_the_old_one);
    RUN_TEST(test_stream_update_rejects_non_streamed_target);
    return UNITY_END();
}
