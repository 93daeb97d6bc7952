/*
 * tvo_sincos and tvo_sincos_turns against libm in double: within a few float32 ulps over the fast
 * range, libm's answer beyond it, NaN for NaN and Inf; the fixed-point phase exact at every quarter.
 */
#include "test_support.h"

#include "tvo/trig.h"

void setUp(void) {}
void tearDown(void) {}

/* Absolute error allowed: sin and cos are at most 1, a few ulps of 1 plus the argument's rounding. */
#define TRIG_TOL (4.0 * TEST_EPS)

static void assert_sincos_at(double angle)
{
    const tvo_real_t x = test_r(angle);
    tvo_real_t s;
    tvo_real_t c;
    tvo_sincos(x, &s, &c);
    char msg[64];
    (void)snprintf(msg, sizeof(msg), "sin at %.9g", test_d(x));
    ASSERT_NEAR_MSG(sin(test_d(x)), s, TRIG_TOL, msg);
    (void)snprintf(msg, sizeof(msg), "cos at %.9g", test_d(x));
    ASSERT_NEAR_MSG(cos(test_d(x)), c, TRIG_TOL, msg);
}

static void test_sincos_matches_libm_over_the_fast_range(void)
{
    for (int i = -20000; i <= 20000; ++i) {
        assert_sincos_at((double)i * 1e-3 * TEST_PI); /* every quadrant boundary region, |x| <= 20 pi */
    }
    for (int i = 0; i <= 2000; ++i) {
        assert_sincos_at(8000.0 + (double)i * 0.0971); /* near the fast limit */
    }
}

static void test_sincos_beyond_the_fast_range_and_not_finite(void)
{
    assert_sincos_at(1e5);
    assert_sincos_at(-3.0e6);
    tvo_real_t s;
    tvo_real_t c;
    tvo_sincos(TEST_NAN, &s, &c);
    TEST_ASSERT_TRUE(isnan(s) && isnan(c));
    tvo_sincos(TEST_INF, &s, &c);
    TEST_ASSERT_TRUE(isnan(s) && isnan(c));
}

static void test_turns_are_exact_at_quarters_and_match_libm_between(void)
{
    tvo_real_t s;
    tvo_real_t c;
    tvo_sincos_turns(0x4000000000000000u, TVO_R(0.0), &s, &c); /* a quarter turn */
    ASSERT_NEAR(1.0, s, TRIG_TOL);
    ASSERT_NEAR(0.0, c, TRIG_TOL);
    tvo_sincos_turns(0xC000000000000000u, TVO_R(0.0), &s, &c); /* three quarters */
    ASSERT_NEAR(-1.0, s, TRIG_TOL);
    ASSERT_NEAR(0.0, c, TRIG_TOL);
    for (uint32_t i = 0; i < 4096u; ++i) {
        const uint64_t turns = (uint64_t)i * 0x0010001000100011u;
        const double extra = ((double)(i % 7u) - 3.0) * 0.25;
        const double angle = (double)turns * (2.0 * TEST_PI / 18446744073709551616.0) + test_d(test_r(extra));
        tvo_sincos_turns(turns, test_r(extra), &s, &c);
        ASSERT_NEAR(sin(angle), s, 2.0 * TRIG_TOL);
        ASSERT_NEAR(cos(angle), c, 2.0 * TRIG_TOL);
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sincos_matches_libm_over_the_fast_range);
    RUN_TEST(test_sincos_beyond_the_fast_range_and_not_finite);
    RUN_TEST(test_turns_are_exact_at_quarters_and_match_libm_between);
    return UNITY_END();
}
