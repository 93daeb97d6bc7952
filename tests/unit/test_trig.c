/*
 * tvo_sincos and tvo_sincos_turns against libm in double: within a few float32 ulps over the fast
 * range and beyond it (the exact reduction, at every float exponent), NaN for NaN and Inf; the
 * fixed-point phase exact at every quarter. TVO_ATAN2 (the float build's own tvo_atan2f, libm's atan2
 * in double) within 2 ulps of double atan2 over every direction at radii from 1e-30 to 1e30 and
 * over random argument bits, and C99 Annex F's values at zeros, infinities and NaN.
 */
#include "test_support.h"

#include "tvo/trig.h"
#include "internal/trig.h"

#include <float.h>
#include <string.h>

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

/* Beyond the fast range the float build reduces by the bits of 2/pi; libm's double reduction of the
 * same float is exact, so the two agree to float32 rounding at every exponent up to FLT_MAX. */
static void test_sincos_beyond_the_fast_range_at_every_exponent(void)
{
#if !TVO_USE_DOUBLE
    uint32_t state = 2463534242u;
    for (uint32_t exponent = 140u; exponent <= 254u; ++exponent) { /* 2^13 <= |x| < 2^128 */
        for (int k = 0; k < 48; ++k) {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            const uint32_t bits = (exponent << 23) | (state & 0x7FFFFFu) | (state & 0x80000000u);
            float x;
            memcpy(&x, &bits, sizeof(x));
            if (fabsf(x) > TVO_SINCOS_FAST_LIMIT_RAD) {
                assert_sincos_at((double)x);
            }
        }
    }
    assert_sincos_at((double)FLT_MAX);
    assert_sincos_at(-(double)FLT_MAX);
    assert_sincos_at((double)nextafterf(TVO_SINCOS_FAST_LIMIT_RAD, INFINITY));
#endif
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

static void test_turns_refuse_an_extra_angle_beyond_the_fast_range(void)
{
    tvo_real_t s;
    tvo_real_t c;
    tvo_sincos_turns(0x1234567812345678u, TVO_SINCOS_FAST_LIMIT_RAD, &s, &c); /* the limit itself: reduced */
    const double angle = (double)0x1234567812345678u * (2.0 * TEST_PI / 18446744073709551616.0) +
                         test_d(TVO_SINCOS_FAST_LIMIT_RAD);
    /* Known to the rounding of the phase plus the extra angle (an ulp of 8192 rad), not better. */
    ASSERT_NEAR(sin(angle), s, 8192.0 * TEST_EPS);
    ASSERT_NEAR(cos(angle), c, 8192.0 * TEST_EPS);
    const tvo_real_t beyond[3] = {TVO_SINCOS_FAST_LIMIT_RAD * TVO_R(1.0001), -TVO_SINCOS_FAST_LIMIT_RAD * TVO_R(1.0001),
                                  TEST_NAN};
    for (unsigned i = 0; i < 3u; ++i) {
        tvo_sincos_turns(0u, beyond[i], &s, &c);
        TEST_ASSERT_TRUE(isnan(s) && isnan(c));
    }
}

/* The spacing of the scalar type's numbers at |v| (v finite). */
static double scalar_ulp(tvo_real_t v)
{
#if TVO_USE_DOUBLE
    return nextafter(fabs(v), (double)INFINITY) - fabs(v);
#else
    return (double)(nextafterf(fabsf(v), INFINITY) - fabsf(v));
#endif
}

/* TVO_ATAN2(y, x) within 2 ulps of the exact angle (double atan2 of the same arguments); the error in
 * ulps of the result, so the sweeps below can say how close they came. */
static double atan2_ulps_at(tvo_real_t y, tvo_real_t x)
{
    const double exact = atan2(test_d(y), test_d(x));
    const tvo_real_t got = TVO_ATAN2(y, x);
    const double ulps = fabs(test_d(got) - exact) / scalar_ulp(test_r(exact));
    if (!(ulps <= 2.0)) {
        char msg[128];
        (void)snprintf(msg, sizeof(msg), "atan2(%a, %a) = %a, exact %a", test_d(y), test_d(x), test_d(got), exact);
        TEST_FAIL_MESSAGE(msg);
    }
    return ulps;
}

static void test_atan2_within_two_ulps_in_every_direction(void)
{
    const double radii[] = {1e-30, 1e-3, 1.0, 7.5, 1e4, 1e30};
    double worst = 0.0;
    for (size_t k = 0; k < sizeof(radii) / sizeof(radii[0]); ++k) {
        for (int i = -20000; i <= 20000; ++i) {
            const double theta = (double)i * (TEST_PI / 20000.0) + 1e-6 * (double)(i % 7);
            const double ulps = atan2_ulps_at(test_r(radii[k] * sin(theta)), test_r(radii[k] * cos(theta)));
            worst = ulps > worst ? ulps : worst;
        }
    }
#if !TVO_USE_DOUBLE
    TEST_ASSERT_TRUE(worst > 0.0); /* the sweep met rounded results, not only exact ones */
#else
    TEST_ASSERT_TRUE(worst == 0.0); /* libm's atan2 itself */
#endif
}

static void test_atan2_within_two_ulps_over_random_bits(void)
{
#if !TVO_USE_DOUBLE
    uint32_t state = 88172645u;
    for (int k = 0; k < 200000; ++k) {
        uint32_t words[2];
        for (int w = 0; w < 2; ++w) {
            state ^= state << 13;
            state ^= state >> 17;
            state ^= state << 5;
            /* exponents within 2^-40 .. 2^40 of each other's, so the quotient stays a normal float */
            words[w] = (state & 0x807FFFFFu) | ((107u + ((state >> 23) % 80u)) << 23);
        }
        float y;
        float x;
        memcpy(&y, &words[0], sizeof(y));
        memcpy(&x, &words[1], sizeof(x));
        (void)atan2_ulps_at(y, x);
    }
#else
    (void)atan2_ulps_at(TVO_R(0.3), TVO_R(-0.7)); /* libm's own: the sweep above covers it */
#endif
}

static void test_atan2_special_values(void)
{
    const tvo_real_t pi = test_r(TEST_PI);
    const tvo_real_t half_pi = test_r(TEST_PI / 2.0);
    const struct {
        tvo_real_t y, x, expected;
    } cases[] = {
        {TVO_R(0.0), TVO_R(0.0), TVO_R(0.0)},     {-TVO_R(0.0), TVO_R(0.0), -TVO_R(0.0)},
        {TVO_R(0.0), -TVO_R(0.0), pi},            {-TVO_R(0.0), -TVO_R(0.0), -pi},
        {TVO_R(0.0), -TVO_R(3.0), pi},            {-TVO_R(0.0), -TVO_R(3.0), -pi},
        {TVO_R(0.0), TVO_R(3.0), TVO_R(0.0)},     {-TVO_R(0.0), TVO_R(3.0), -TVO_R(0.0)},
        {TVO_R(2.0), TVO_R(0.0), half_pi},        {-TVO_R(2.0), -TVO_R(0.0), -half_pi},
        {TVO_R(2.0), -TEST_INF, pi},              {-TVO_R(2.0), -TEST_INF, -pi},
        {TVO_R(2.0), TEST_INF, TVO_R(0.0)},       {-TVO_R(2.0), TEST_INF, -TVO_R(0.0)},
        {TEST_INF, TVO_R(5.0), half_pi},          {-TEST_INF, -TVO_R(5.0), -half_pi},
        {TEST_INF, -TEST_INF, test_r(0.75 * TEST_PI)}, {-TEST_INF, -TEST_INF, test_r(-0.75 * TEST_PI)},
        {TEST_INF, TEST_INF, test_r(TEST_PI / 4.0)},   {-TEST_INF, TEST_INF, test_r(-TEST_PI / 4.0)},
    };
    for (size_t i = 0; i < sizeof(cases) / sizeof(cases[0]); ++i) {
        const tvo_real_t got = TVO_ATAN2(cases[i].y, cases[i].x);
        char msg[96];
        (void)snprintf(msg, sizeof(msg), "atan2(%g, %g) = %a", test_d(cases[i].y), test_d(cases[i].x), test_d(got));
        TEST_ASSERT_TRUE_MESSAGE(got == cases[i].expected && signbit(got) == signbit(cases[i].expected), msg);
    }
    TEST_ASSERT_TRUE(isnan(TVO_ATAN2(TEST_NAN, TVO_R(1.0))));
    TEST_ASSERT_TRUE(isnan(TVO_ATAN2(TVO_R(1.0), TEST_NAN)));
    TEST_ASSERT_TRUE(isnan(TVO_ATAN2(TEST_INF, TEST_NAN)));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_sincos_matches_libm_over_the_fast_range);
    RUN_TEST(test_sincos_beyond_the_fast_range_and_not_finite);
    RUN_TEST(test_sincos_beyond_the_fast_range_at_every_exponent);
    RUN_TEST(test_turns_are_exact_at_quarters_and_match_libm_between);
    RUN_TEST(test_turns_refuse_an_extra_angle_beyond_the_fast_range);
    RUN_TEST(test_atan2_within_two_ulps_in_every_direction);
    RUN_TEST(test_atan2_within_two_ulps_over_random_bits);
    RUN_TEST(test_atan2_special_values);
    return UNITY_END();
}
