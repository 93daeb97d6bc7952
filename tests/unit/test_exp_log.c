/*
 * tvo_expf and tvo_logf (src/exp_log.c): the float nearest the exact value over a dense sweep of
 * every binade they compute in, against double exp and log rounded once to float (skipping the rare
 * argument whose double value lies too near a float midpoint for that reference to decide); the
 * special values, the overflow and underflow thresholds, subnormal results and arguments; the
 * integer path that soft-float targets run alone gives the same bits as the whole function.
 * The exhaustive measurement against glibc is tools/agree --accuracy.
 */
#include "test_support.h"

#include "internal/exp_log.h"
#include "internal/real_bits.h"

#include <float.h>

void setUp(void) {}
void tearDown(void) {}

/* The double value rounded to float, and whether that is certainly the exact value's rounding: the
 * double is within an ulp (2^-52) of exact, so it decides unless it lies within 2^-50 of a midpoint. */
static int rounded_reference(double exact, float *out)
{
    const float r = (float)exact;
    *out = r;
    if (r == 0.0f || isinf(r)) {
        return 1;
    }
    const double up = (double)nextafterf(r, INFINITY);
    const double down = (double)nextafterf(r, -INFINITY);
    const double to_midpoint = fmin(fabs(exact - ((double)(r) + up) / 2.0), fabs(exact - ((double)(r) + down) / 2.0));
    return to_midpoint > ldexp(fabs(exact), -50);
}

/* Every decidable argument must give the reference's bits; too many undecided ones would mean the
 * sweep checked little. */
#define MAX_UNDECIDED 8u

static void assert_bits(float expected, float actual, const char *what, float x)
{
    if (float_bits(expected) != float_bits(actual)) {
        char msg[128];
        (void)snprintf(msg, sizeof(msg), "%s(%a) = %a, the nearest float is %a", what, (double)(x), (double)(actual),
                       (double)(expected));
        TEST_FAIL_MESSAGE(msg);
    }
}

/* 4096 significands per binade, spread over all 23 bits (a stride plus a scrambled low part). */
static uint32_t sweep_significand(uint32_t i)
{
    return (i * 2048u + ((i * 2654435761u) >> 21)) & 0x7FFFFFu;
}

static void test_expf_rounds_correctly_over_every_binade_it_computes(void)
{
    unsigned undecided = 0u;
    unsigned checked = 0u;
    for (uint32_t biased = 101u; biased <= 133u; ++biased) { /* |x| in [2^-26, 2^7): beyond, 1, 0 or inf */
        for (uint32_t i = 0; i < 4096u; ++i) {
            for (uint32_t sign = 0u; sign <= 1u; ++sign) {
                const float x = float_from_bits((sign << 31) | (biased << 23) | sweep_significand(i));
                float expected;
                if (!rounded_reference(exp((double)(x)), &expected)) {
                    ++undecided;
                    continue;
                }
                assert_bits(expected, tvo_expf(x), "tvo_expf", x);
                ++checked;
            }
        }
    }
    TEST_ASSERT_TRUE(undecided <= MAX_UNDECIDED);
    TEST_ASSERT_EQUAL_UINT32(33u * 4096u * 2u - undecided, checked);
}

static void test_expf_special_values_and_thresholds(void)
{
    TEST_ASSERT_EQUAL_HEX32(float_bits(1.0f), float_bits(tvo_expf(0.0f)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(1.0f), float_bits(tvo_expf(-0.0f)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(INFINITY), float_bits(tvo_expf(INFINITY)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(0.0f), float_bits(tvo_expf(-INFINITY)));
    TEST_ASSERT_TRUE(isnan(tvo_expf(NAN)));
    TEST_ASSERT_EQUAL_HEX32(0x7FC12345u, float_bits(tvo_expf(float_from_bits(0x7F812345u)))); /* a NaN quieted, its payload kept */
    /* Arguments near 0, where exp lies within 2^-48 of a midpoint and the double reference cannot
     * decide: exp(x) = 1 + x + x^2/2 + ..., so 2^-24 rounds up (2^-49 above the midpoint 1 + 2^-24),
     * -2^-25 to 1 (2^-51 above 1 - 2^-25), its neighbour down (2^-48 below it). */
    const struct {
        float x;
        float expected;
    } near_zero[] = {{FLT_TRUE_MIN, 1.0f},      {-FLT_TRUE_MIN, 1.0f},           {FLT_MIN, 1.0f},
                     {0x1p-26f, 1.0f},          {-0x1p-26f, 1.0f},               {0x1p-25f, 1.0f},
                     {0x1.fffffep-25f, 1.0f},   {0x1p-24f, 0x1.000002p+0f},      {-0x1p-25f, 1.0f},
                     {-0x1.000002p-25f, 0x1.fffffep-1f}, {-0x1p-24f, 0x1.fffffep-1f}};
    for (size_t i = 0; i < sizeof(near_zero) / sizeof(near_zero[0]); ++i) {
        assert_bits(near_zero[i].expected, tvo_expf(near_zero[i].x), "tvo_expf", near_zero[i].x);
    }
    /* The overflow threshold (the largest x with a finite exp, the next one), the subnormal range's
     * start, results near the smallest subnormal and the zero threshold. */
    const float thresholds[] = {0x1.62e42ep+6f,  0x1.62e43p+6f,  89.0f,           103.9f,          -0x1.5d589ep+6f,
                                -0x1.5d58ap+6f,  -87.5f,         -100.0f,         -0x1.9d1da0p+6f, -0x1.9fe368p+6f,
                                -0x1.9fe36ap+6f, -0x1.9fe36cp+6f, -103.97f,       -104.0f,         -110.0f};
    for (size_t i = 0; i < sizeof(thresholds) / sizeof(thresholds[0]); ++i) {
        float expected;
        TEST_ASSERT_TRUE(rounded_reference(exp((double)(thresholds[i])), &expected));
        assert_bits(expected, tvo_expf(thresholds[i]), "tvo_expf", thresholds[i]);
    }
    TEST_ASSERT_TRUE(isfinite(tvo_expf(0x1.62e42ep+6f)));
    TEST_ASSERT_TRUE(isinf(tvo_expf(0x1.62e43p+6f)));
    TEST_ASSERT_EQUAL_HEX32(1u, float_bits(tvo_expf(-0x1.9fe368p+6f))); /* the smallest subnormal */
    TEST_ASSERT_EQUAL_HEX32(0u, float_bits(tvo_expf(-0x1.9fe36ap+6f))); /* below half of it */
}

/* Soft-float targets run the integer path alone: over its domain it gives the whole function's bits. */
static void test_expf_integer_path_gives_the_same_bits(void)
{
    for (uint32_t biased = 101u; biased <= 133u; ++biased) {
        for (uint32_t i = 0; i < 2048u; ++i) {
            for (uint32_t sign = 0u; sign <= 1u; ++sign) {
                const float x = float_from_bits((sign << 31) | (biased << 23) | sweep_significand(2u * i + 1u));
                if (fabsf(x) < 104.0f) {
                    assert_bits(tvo_expf(x), tvo_expf_integer(x), "tvo_expf_integer", x);
                }
            }
        }
    }
}

static void test_logf_rounds_correctly_over_every_binade(void)
{
    unsigned undecided = 0u;
    for (uint32_t biased = 0u; biased <= 254u; ++biased) { /* the subnormals, then every normal binade */
        for (uint32_t i = 0; i < 1024u; ++i) {
            const uint32_t significand = sweep_significand(4u * i + (biased & 3u));
            if (biased == 0u && significand == 0u) {
                continue;
            }
            const float x = float_from_bits((biased << 23) | significand);
            float expected;
            if (!rounded_reference(log((double)(x)), &expected)) {
                ++undecided;
                continue;
            }
            assert_bits(expected, tvo_logf(x), "tvo_logf", x);
        }
    }
    TEST_ASSERT_TRUE(undecided <= MAX_UNDECIDED);
}

/* Near 1 the result is small and must keep its relative precision: every float within 2^-10 of 1. */
static void test_logf_rounds_correctly_near_one(void)
{
    unsigned undecided = 0u;
    for (uint32_t step = 1u; step <= 16384u; ++step) {
        const float xs[2] = {float_from_bits(0x3F800000u + step), float_from_bits(0x3F800000u - step)};
        for (unsigned k = 0; k < 2u; ++k) {
            float expected;
            if (!rounded_reference(log((double)(xs[k])), &expected)) {
                ++undecided;
                continue;
            }
            assert_bits(expected, tvo_logf(xs[k]), "tvo_logf", xs[k]);
        }
    }
    TEST_ASSERT_TRUE(undecided <= MAX_UNDECIDED);
}

static void test_logf_special_values(void)
{
    TEST_ASSERT_EQUAL_HEX32(0u, float_bits(tvo_logf(1.0f))); /* +0 */
    TEST_ASSERT_EQUAL_HEX32(float_bits(-INFINITY), float_bits(tvo_logf(0.0f)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(-INFINITY), float_bits(tvo_logf(-0.0f)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(INFINITY), float_bits(tvo_logf(INFINITY)));
    TEST_ASSERT_TRUE(isnan(tvo_logf(-1.0f)));
    TEST_ASSERT_TRUE(isnan(tvo_logf(-FLT_TRUE_MIN)));
    TEST_ASSERT_TRUE(isnan(tvo_logf(-INFINITY)));
    TEST_ASSERT_TRUE(isnan(tvo_logf(NAN)));
    TEST_ASSERT_EQUAL_HEX32(0x7FC12345u, float_bits(tvo_logf(float_from_bits(0x7F812345u))));
    const float edges[] = {FLT_TRUE_MIN, 0x1.8p-149f, FLT_MIN, FLT_MAX, 2.0f, 0.5f, 0x1p-126f, 0x1p127f,
                           0x1.fffffep-1f, 0x1.000002p+0f, 10000.0f, 0.1f};
    for (size_t i = 0; i < sizeof(edges) / sizeof(edges[0]); ++i) {
        float expected;
        TEST_ASSERT_TRUE(rounded_reference(log((double)(edges[i])), &expected));
        assert_bits(expected, tvo_logf(edges[i]), "tvo_logf", edges[i]);
    }
}

/* The core's scalar functions: its own in float32, libm's in double. */
static void test_the_cores_exp_and_log_are_these(void)
{
    const tvo_real_t x = TVO_R(2.5);
#if TVO_USE_DOUBLE
    TEST_ASSERT_TRUE(TVO_EXP(x) == exp(x) && TVO_LOG(x) == log(x));
#else
    TEST_ASSERT_EQUAL_HEX32(float_bits(tvo_expf(x)), float_bits(TVO_EXP(x)));
    TEST_ASSERT_EQUAL_HEX32(float_bits(tvo_logf(x)), float_bits(TVO_LOG(x)));
#endif
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_expf_rounds_correctly_over_every_binade_it_computes);
    RUN_TEST(test_expf_special_values_and_thresholds);
    RUN_TEST(test_expf_integer_path_gives_the_same_bits);
    RUN_TEST(test_logf_rounds_correctly_over_every_binade);
    RUN_TEST(test_logf_rounds_correctly_near_one);
    RUN_TEST(test_logf_special_values);
    RUN_TEST(test_the_cores_exp_and_log_are_these);
    return UNITY_END();
}
