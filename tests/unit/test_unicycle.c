/*
 * Unicycle: the flat map with dynamic extension, the exact held-command motion, angle wrapping.
 *
 * Flat map (y' = v e_theta, e_theta = (cos th, sin th), v' = a):
 *   y'' = a e_theta + v omega e_theta_perp   =>   a = y'' . e_theta,  omega = (e_theta x y'') / v
 * with e x w = e_x w_y - e_y w_x, and v replaced by sign(v) max(|v|, v_min) (sign(0) = +1).
 *
 * Held (v, w) over dt from (x0, y0, th):
 *   w != 0:  x = x0 + (v/w)(sin(th + w dt) - sin th),  y = y0 - (v/w)(cos(th + w dt) - cos th)
 *   w == 0:  x = x0 + v dt cos th,  y = y0 + v dt sin th;  heading th + w dt.
 * The reference is evaluated in double in the cancellation-free form
 *   (v/w)(sin(th + w dt) - sin th) = v dt sinc(w dt / 2) cos(th + w dt / 2), likewise for y.
 */
#include "test_support.h"
#include "internal/unicycle.h"

void setUp(void) {}
void tearDown(void) {}

/* ------------------------------------------------------------------------------------------------
 * Flat map
 * --------------------------------------------------------------------------------------------- */

static void flat_map_ok(double heading, double speed, double ax, double ay, double vmin, tvo_real_t *a,
                        tvo_real_t *w, uint8_t *low)
{
    const tvo_real_t ydd[2] = {test_r(ax), test_r(ay)};
    *a = TVO_R(-99.0);
    *w = TVO_R(-99.0);
    *low = 77;
    tvo_unicycle_flat_map(test_r(heading), test_r(speed), ydd, test_r(vmin), a, w, low);
}

static void test_flat_map_hand_case_heading_north(void)
{
    /* heading pi/2: e = (0, 1). y'' = (1, 3): a = 3; e x y'' = 0*3 - 1*1 = -1; omega = -1/2. */
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(TEST_PI / 2.0, 2.0, 1.0, 3.0, 0.1, &a, &w, &low);
    ASSERT_NEAR(3.0, a, TEST_TOL(8, 3.0));
    ASSERT_NEAR(-0.5, w, TEST_TOL(8, 1.0));
    TEST_ASSERT_EQUAL_UINT8(0, low);
}

static void test_flat_map_general_heading(void)
{
    const double th = 0.3, v = 1.5, ax = -0.7, ay = 2.2;
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(th, v, ax, ay, 0.1, &a, &w, &low);
    const double e_a = ax * cos(th) + ay * sin(th);
    const double e_w = (cos(th) * ay - sin(th) * ax) / v;
    ASSERT_NEAR(e_a, a, TEST_TOL(8, 3.0));
    ASSERT_NEAR(e_w, w, TEST_TOL(8, 3.0));
    TEST_ASSERT_EQUAL_UINT8(0, low);
}

static void test_flat_map_reconstructs_the_output_acceleration(void)
{
    /* Round trip: a e + v omega e_perp must give back y'' (for |v| above the floor). */
    const double th = -2.4, v = 0.8, ax = 0.35, ay = -1.9;
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(th, v, ax, ay, 0.05, &a, &w, &low);
    const double rx = test_d(a) * cos(th) - v * test_d(w) * sin(th);
    const double ry = test_d(a) * sin(th) + v * test_d(w) * cos(th);
    ASSERT_NEAR(ax, rx, TEST_TOL(16, 2.0));
    ASSERT_NEAR(ay, ry, TEST_TOL(16, 2.0));
}

static void test_flat_map_zero_speed_uses_floor_with_positive_sign(void)
{
    /* v = 0, floor 0.1, heading 0, y'' = (0.5, 1): a = 0.5; omega = (1*1 - 0*0.5) / (+0.1) = 10. */
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(0.0, 0.0, 0.5, 1.0, 0.1, &a, &w, &low);
    TEST_ASSERT_TRUE(test_is_finite(w));
    ASSERT_NEAR(0.5, a, TEST_TOL(8, 1.0));
    ASSERT_NEAR(10.0, w, TEST_TOL(16, 10.0));
    TEST_ASSERT_EQUAL_UINT8(1, low);
}

static void test_flat_map_small_negative_speed_uses_negative_floor(void)
{
    /* v = -0.03 with floor 0.1: v_reg = -0.1, so omega = 1 / -0.1 = -10 (reversing robot). */
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(0.0, -0.03, 0.5, 1.0, 0.1, &a, &w, &low);
    ASSERT_NEAR(-10.0, w, TEST_TOL(16, 10.0));
    TEST_ASSERT_EQUAL_UINT8(1, low);
}

static void test_flat_map_small_positive_speed_uses_floor(void)
{
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(0.0, 0.02, 0.5, 1.0, 0.1, &a, &w, &low);
    ASSERT_NEAR(10.0, w, TEST_TOL(16, 10.0));
    TEST_ASSERT_EQUAL_UINT8(1, low);
}

static void test_flat_map_negative_speed_divides_by_it(void)
{
    /* Driving backwards at v = -2 (heading 0): omega = (e x y'') / v = 1 / -2. */
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(0.0, -2.0, 0.5, 1.0, 0.1, &a, &w, &low);
    ASSERT_NEAR(0.5, a, TEST_TOL(8, 1.0));
    ASSERT_NEAR(-0.5, w, TEST_TOL(8, 1.0));
    TEST_ASSERT_EQUAL_UINT8(0, low);
}

static void test_flat_map_speed_at_floor_is_not_low(void)
{
    /* |v| < v_min is the low-speed condition; |v| == v_min is not. */
    tvo_real_t a, w;
    uint8_t low;
    flat_map_ok(0.0, 0.25, 0.0, 1.0, 0.25, &a, &w, &low);
    ASSERT_NEAR(4.0, w, TEST_TOL(8, 4.0));
    TEST_ASSERT_EQUAL_UINT8(0, low);
}




/* ------------------------------------------------------------------------------------------------
 * Prediction
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    double x, y, th;
} pose_d;

/* Exact arc in double, cancellation-free: chord length v dt sinc(w dt/2) along th + w dt/2. */
static pose_d arc(pose_d p, double v, double w, double dt)
{
    const double half = 0.5 * w * dt;
    const double sinc = (fabs(half) < 1e-9) ? 1.0 - half * half / 6.0 : sin(half) / half;
    const double chord = v * dt * sinc;
    const pose_d q = {p.x + chord * cos(p.th + half), p.y + chord * sin(p.th + half), p.th + w * dt};
    return q;
}

static tvo_pose_t to_pose(pose_d p)
{
    tvo_pose_t q;
    q.position_m[0] = test_r(p.x);
    q.position_m[1] = test_r(p.y);
    q.heading_rad = test_r(p.th);
    return q;
}

/* Heading compared modulo 2 pi (the header does not say whether the result is wrapped). */
static void assert_heading(double expected, tvo_real_t actual, double tol)
{
    const double d = remainder(test_d(actual) - expected, 2.0 * TEST_PI);
    ASSERT_NEAR(0.0, d, tol);
}

static void assert_pose(pose_d e, const tvo_pose_t *a, double tol)
{
    ASSERT_NEAR(e.x, a->position_m[0], tol);
    ASSERT_NEAR(e.y, a->position_m[1], tol);
    assert_heading(e.th, a->heading_rad, tol);
}

static void test_predict_arc_matches_the_textbook_closed_form(void)
{
    /* Directly the formula of the header, at a well-conditioned turn (w dt = 0.4). */
    const pose_d p = {1.0, -2.0, 0.7};
    const double v = 1.5, w = 0.8, dt = 0.5;
    const pose_d e = {p.x + v / w * (sin(p.th + w * dt) - sin(p.th)),
                      p.y - v / w * (cos(p.th + w * dt) - cos(p.th)), p.th + w * dt};
    const tvo_pose_t start = to_pose(p);
    tvo_pose_t out;
    tvo_unicycle_predict(&start, test_r(v), test_r(w), test_r(dt), &out);
    assert_pose(e, &out, TEST_TOL(16, 3.0));
}

static void test_predict_negative_turn_and_reverse_speed(void)
{
    const pose_d p = {-0.3, 0.4, -2.9};
    const double v = -0.9, w = -1.7, dt = 0.35;
    const pose_d e = {p.x + v / w * (sin(p.th + w * dt) - sin(p.th)),
                      p.y - v / w * (cos(p.th + w * dt) - cos(p.th)), p.th + w * dt};
    const tvo_pose_t start = to_pose(p);
    tvo_pose_t out;
    tvo_unicycle_predict(&start, test_r(v), test_r(w), test_r(dt), &out);
    assert_pose(e, &out, TEST_TOL(16, 4.0));
}

static void test_predict_full_circle_returns_to_start(void)
{
    /* w dt = 2 pi: back at the start, on a circle of radius v / w = 0.5 (never farther than 1 m). */
    const pose_d p = {2.0, 3.0, 0.25};
    const double v = 1.0, w = 2.0, dt = TEST_PI;
    const tvo_pose_t start = to_pose(p);
    tvo_pose_t out;
    tvo_unicycle_predict(&start, test_r(v), test_r(w), test_r(dt), &out);
    ASSERT_NEAR(2.0, out.position_m[0], TEST_TOL(32, 3.0));
    ASSERT_NEAR(3.0, out.position_m[1], TEST_TOL(32, 3.0));
    assert_heading(0.25, out.heading_rad, TEST_TOL(32, 7.0));
}

static void test_predict_half_circle_lands_one_diameter_across(void)
{
    /* Heading 0, v = 1, w = 1 (radius 1, centre (x0, y0 + 1)), dt = pi: lands at (x0, y0 + 2), heading pi. */
    const pose_d p = {0.5, -1.0, 0.0};
    const tvo_pose_t start = to_pose(p);
    tvo_pose_t out;
    tvo_unicycle_predict(&start, TVO_R(1.0), TVO_R(1.0), test_r(TEST_PI), &out);
    ASSERT_NEAR(0.5, out.position_m[0], TEST_TOL(32, 2.0));
    ASSERT_NEAR(1.0, out.position_m[1], TEST_TOL(32, 2.0));
    assert_heading(TEST_PI, out.heading_rad, TEST_TOL(32, 4.0));
}

static void test_predict_straight_line_when_turn_is_zero(void)
{
    const pose_d p = {1.0, 1.0, 2.2};
    const double v = 0.7, dt = 0.9;
    const tvo_pose_t start = to_pose(p);
    tvo_pose_t out;
    tvo_unicycle_predict(&start, test_r(v), TVO_R(0.0), test_r(dt), &out);
    ASSERT_NEAR(1.0 + v * dt * cos(2.2), out.position_m[0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(1.0 + v * dt * sin(2.2), out.position_m[1], TEST_TOL(16, 2.0));
    assert_heading(2.2, out.heading_rad, TEST_TOL(4, 2.2));
}

static void test_predict_is_continuous_through_tiny_turn_rates(void)
{
    /* A control period (10 ms at 1 m/s) with turn rates from 1e-1 down to 1e-12 and zero, both
     * signs. However the implementation switches between arc and series, the pose must match the
     * exact arc to position rounding: a few ulps of |x0| ~ 1 plus a small fraction of the 1 cm
     * step. The naive (v/w)(sin(th + w dt) - sin th) in float loses ~eps/w: 6e-5 m at w = 1e-3,
     * 6e-3 m at w = 1e-5, which this tolerance catches. */
    const pose_d p = {0.9, -1.1, 0.7};
    const double v = 1.0, dt = 0.01;
    const double rates[] = {1e-1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-9, 1e-12, 0.0};
    const double tol = TEST_TOL(8, 1.2) + 1e-4 * v * dt;
    const tvo_pose_t start = to_pose(p);
    const pose_d p_rounded = {test_d(start.position_m[0]), test_d(start.position_m[1]), test_d(start.heading_rad)};
    for (size_t i = 0; i < sizeof(rates) / sizeof(rates[0]); ++i) {
        for (int sign = -1; sign <= 1; sign += 2) {
            const double w = sign * rates[i];
            tvo_pose_t out;
            tvo_unicycle_predict(&start, test_r(v), test_r(w), test_r(dt), &out);
            const pose_d e = arc(p_rounded, v, test_d(test_r(w)), test_d(test_r(dt)));
            char msg[64];
            (void)snprintf(msg, sizeof(msg), "turn rate %g", w);
            ASSERT_NEAR_MSG(e.x, out.position_m[0], tol, msg);
            ASSERT_NEAR_MSG(e.y, out.position_m[1], tol, msg);
        }
    }
}

static void test_predict_long_arc_is_accurate_for_every_small_turn(void)
{
    /* A 1 m arc (v = 1, dt = 1) with turn angles w dt swept from 1e-4 to 1e-1 rad, across any
     * switch between series and closed form. The lateral offset (1 - cos(w dt)) / w is where
     * cancellation bites: evaluated as written it loses eps / (w dt)^2 relative, ~6 % in float at
     * w dt = 1e-3, i.e. ~3e-5 m here; the half-angle form 2 sin^2(w dt / 2) / w keeps it to a few
     * ulps. Bound: 32 ulps of the 1 m displacement. */
    const pose_d p = {0.0, 0.0, 0.7};
    const tvo_pose_t start = to_pose(p);
    const pose_d p_rounded = {0.0, 0.0, test_d(start.heading_rad)};
    const double tol = TEST_TOL(32, 1.0);
    double worst = 0.0, worst_w = 0.0;
    for (double w = 1e-4; w < 1e-1; w *= 1.01) {
        tvo_pose_t out;
        tvo_unicycle_predict(&start, TVO_R(1.0), test_r(w), TVO_R(1.0), &out);
        const pose_d e = arc(p_rounded, 1.0, test_d(test_r(w)), 1.0);
        const double err = hypot(test_d(out.position_m[0]) - e.x, test_d(out.position_m[1]) - e.y);
        if (err > worst) {
            worst = err;
            worst_w = w;
        }
    }
    char msg[96];
    (void)snprintf(msg, sizeof(msg), "1 m arc position error at w dt = %.4g", worst_w);
    ASSERT_LE(worst, tol, msg);
}

static void test_predict_zero_interval_is_identity(void)
{
    const tvo_pose_t start = {{TVO_R(3.25), TVO_R(-1.5)}, TVO_R(1.0)};
    tvo_pose_t out;
    tvo_unicycle_predict(&start, TVO_R(2.0), TVO_R(1.5), TVO_R(0.0), &out);
    ASSERT_NEAR(3.25, out.position_m[0], 0.0);
    ASSERT_NEAR(-1.5, out.position_m[1], 0.0);
    assert_heading(1.0, out.heading_rad, TEST_TOL(2, 1.0));
}

static void test_predict_output_may_alias_start(void)
{
    const pose_d p = {1.0, -2.0, 0.7};
    const double v = 1.5, w = 0.8, dt = 0.5;
    tvo_pose_t pose = to_pose(p);
    tvo_unicycle_predict(&pose, test_r(v), test_r(w), test_r(dt), &pose);
    assert_pose(arc(p, v, w, dt), &pose, TEST_TOL(16, 3.0));
}

static void test_predict_composes_over_split_intervals(void)
{
    /* The arc is a flow: dt = 0.3 then 0.2 lands where 0.5 does. */
    const tvo_pose_t start = {{TVO_R(0.2), TVO_R(0.1)}, TVO_R(-0.4)};
    tvo_pose_t mid, two, one;
    tvo_unicycle_predict(&start, TVO_R(1.2), TVO_R(-2.0), TVO_R(0.3), &mid);
    tvo_unicycle_predict(&mid, TVO_R(1.2), TVO_R(-2.0), TVO_R(0.2), &two);
    tvo_unicycle_predict(&start, TVO_R(1.2), TVO_R(-2.0), TVO_R(0.5), &one);
    ASSERT_NEAR(one.position_m[0], two.position_m[0], TEST_TOL(32, 1.0));
    ASSERT_NEAR(one.position_m[1], two.position_m[1], TEST_TOL(32, 1.0));
    assert_heading(test_d(one.heading_rad), two.heading_rad, TEST_TOL(32, 2.0));
}




/* ------------------------------------------------------------------------------------------------
 * Angle wrapping
 * --------------------------------------------------------------------------------------------- */

static void test_wrap_keeps_angles_inside_the_range(void)
{
    /* In-range angles come back unchanged, up to the rounding of an add/subtract of 2 pi. */
    ASSERT_NEAR(0.0, tvo_wrap_angle(TVO_R(0.0)), TEST_TOL(2, 2.0 * TEST_PI));
    ASSERT_NEAR(1.0, tvo_wrap_angle(TVO_R(1.0)), TEST_TOL(2, 2.0 * TEST_PI));
    ASSERT_NEAR(-3.0, tvo_wrap_angle(TVO_R(-3.0)), TEST_TOL(2, 2.0 * TEST_PI));
}

static void test_wrap_hand_values(void)
{
    ASSERT_NEAR(-TEST_PI / 2.0, tvo_wrap_angle(test_r(1.5 * TEST_PI)), TEST_TOL(8, 5.0));
    ASSERT_NEAR(TEST_PI / 2.0, tvo_wrap_angle(test_r(-1.5 * TEST_PI)), TEST_TOL(8, 5.0));
    ASSERT_NEAR(7.0 - 2.0 * TEST_PI, tvo_wrap_angle(TVO_R(7.0)), TEST_TOL(8, 7.0));
    ASSERT_NEAR(100.0 - 32.0 * TEST_PI, tvo_wrap_angle(TVO_R(100.0)), TEST_TOL(8, 100.0));
    ASSERT_NEAR(-100.0 + 32.0 * TEST_PI, tvo_wrap_angle(TVO_R(-100.0)), TEST_TOL(8, 100.0));
}

static void test_wrap_keeps_odd_multiples_of_pi_on_the_boundary(void)
{
    /* The range (-pi, pi] is about the true pi, which no float/double equals: the nearest float to
     * pi lies above pi (so it correctly wraps to just above -pi) and the nearest double below
     * (so it stays). Either way the result must sit on the boundary: |result| = pi to rounding. */
    const double odd[] = {-3.0, -1.0, 1.0, 3.0, 5.0};
    for (size_t i = 0; i < sizeof(odd) / sizeof(odd[0]); ++i) {
        const double got = test_d(tvo_wrap_angle(test_r(odd[i] * TEST_PI)));
        ASSERT_NEAR(TEST_PI, fabs(got), TEST_TOL(8, 16.0));
    }
}

static void test_wrap_sweep_agrees_with_remainder(void)
{
    for (int i = -300; i <= 300; ++i) {
        const tvo_real_t a = test_r(i * 0.173);
        const double got = test_d(tvo_wrap_angle(a));
        const double expected = remainder(test_d(a), 2.0 * TEST_PI);
        const double tol = TEST_TOL(8, 60.0);
        TEST_ASSERT_TRUE_MESSAGE(got > -TEST_PI - tol && got <= TEST_PI + tol, "outside (-pi, pi]");
        ASSERT_NEAR(0.0, remainder(got - expected, 2.0 * TEST_PI), tol);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_flat_map_hand_case_heading_north);
    RUN_TEST(test_flat_map_general_heading);
    RUN_TEST(test_flat_map_reconstructs_the_output_acceleration);
    RUN_TEST(test_flat_map_zero_speed_uses_floor_with_positive_sign);
    RUN_TEST(test_flat_map_small_negative_speed_uses_negative_floor);
    RUN_TEST(test_flat_map_small_positive_speed_uses_floor);
    RUN_TEST(test_flat_map_negative_speed_divides_by_it);
    RUN_TEST(test_flat_map_speed_at_floor_is_not_low);
    RUN_TEST(test_predict_arc_matches_the_textbook_closed_form);
    RUN_TEST(test_predict_negative_turn_and_reverse_speed);
    RUN_TEST(test_predict_full_circle_returns_to_start);
    RUN_TEST(test_predict_half_circle_lands_one_diameter_across);
    RUN_TEST(test_predict_straight_line_when_turn_is_zero);
    RUN_TEST(test_predict_is_continuous_through_tiny_turn_rates);
    RUN_TEST(test_predict_long_arc_is_accurate_for_every_small_turn);
    RUN_TEST(test_predict_zero_interval_is_identity);
    RUN_TEST(test_predict_output_may_alias_start);
    RUN_TEST(test_predict_composes_over_split_intervals);
    RUN_TEST(test_wrap_keeps_angles_inside_the_range);
    RUN_TEST(test_wrap_hand_values);
    RUN_TEST(test_wrap_keeps_odd_multiples_of_pi_on_the_boundary);
    RUN_TEST(test_wrap_sweep_agrees_with_remainder);
    return UNITY_END();
}
