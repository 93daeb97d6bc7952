/*
 * Jets (truncated Taylor polynomials in tau): every operation against the Taylor coefficients of a
 * known function, c[j] = f^(j)(0) / j!, derived by hand below and evaluated in double.
 */
#include "test_support.h"

#include "tvo/jet.h"
#include "internal/jet.h"

void setUp(void) {}
void tearDown(void) {}

#define N TVO_JET_MAX_ORDER

/* Coefficients of simple elementary functions are O(1): a few ulps of them. */
#define JET_TOL(expected) TEST_TOL(16, (expected))

static tvo_jet_t jet4(double c0, double c1, double c2, double c3)
{
    tvo_jet_t j;
    memset(&j, 0, sizeof(j));
    j.c[0] = test_r(c0);
    j.c[1] = test_r(c1);
    j.c[2] = test_r(c2);
    j.c[3] = test_r(c3);
    return j;
}

static void assert_jet(const double expected[N + 1], const tvo_jet_t *actual, uint8_t order)
{
    for (uint8_t j = 0; j <= order; ++j) {
        char msg[64];
        (void)snprintf(msg, sizeof(msg), "coefficient %u", (unsigned)j);
        ASSERT_NEAR_MSG(expected[j], actual->c[j], JET_TOL(expected[j]), msg);
    }
}

static void test_max_order_is_three(void)
{
    /* The k = 3 law needs coefficients 0..3; every closed form below is written for order 3. */
    TEST_ASSERT_EQUAL_INT(3, TVO_JET_MAX_ORDER);
}

static void test_constant_and_variable_zero_the_higher_coefficients(void)
{
    tvo_jet_t j = jet4(9, 9, 9, 9);
    tvo_jet_constant(TVO_R(2.5), &j);
    const double e_const[N + 1] = {2.5, 0, 0, 0};
    assert_jet(e_const, &j, N);

    j = jet4(9, 9, 9, 9);
    tvo_jet_variable(TVO_R(-1.5), TVO_R(3.0), &j);
    const double e_var[N + 1] = {-1.5, 3.0, 0, 0};
    assert_jet(e_var, &j, N);
}

static void test_add_sub_scale_axpy_are_coefficientwise(void)
{
    const tvo_jet_t a = jet4(1, 2, 3, 4);
    const tvo_jet_t b = jet4(0.5, -1, 0.25, -2);
    tvo_jet_t out;

    tvo_jet_add(&a, &b, N, &out);
    const double e_add[N + 1] = {1.5, 1, 3.25, 2};
    assert_jet(e_add, &out, N);

    tvo_jet_sub(&a, &b, N, &out);
    const double e_sub[N + 1] = {0.5, 3, 2.75, 6};
    assert_jet(e_sub, &out, N);

    tvo_jet_scale(&a, TVO_R(-3.0), N, &out);
    const double e_scale[N + 1] = {-3, -6, -9, -12};
    assert_jet(e_scale, &out, N);

    out = b;
    tvo_jet_axpy(TVO_R(2.0), &a, N, &out); /* b + 2 a */
    const double e_axpy[N + 1] = {2.5, 3, 6.25, 6};
    assert_jet(e_axpy, &out, N);
}

static void test_mul_is_the_cauchy_product(void)
{
    /* (1 + 2t + 3t^2 + 4t^3)(5 - t + t^2/2 + 2t^3):
     *   t^0: 5
     *   t^1: 1*(-1) + 2*5 = 9
     *   t^2: 1*(1/2) + 2*(-1) + 3*5 = 13.5
     *   t^3: 1*2 + 2*(1/2) + 3*(-1) + 4*5 = 20 */
    const tvo_jet_t a = jet4(1, 2, 3, 4);
    const tvo_jet_t b = jet4(5, -1, 0.5, 2);
    tvo_jet_t out;
    tvo_jet_mul(&a, &b, N, &out);
    const double e[N + 1] = {5, 9, 13.5, 20};
    assert_jet(e, &out, N);
}

static void test_div_reciprocal_of_one_plus_tau_is_alternating_series(void)
{
    /* 1 / (1 + t) = 1 - t + t^2 - t^3 + ... */
    tvo_jet_t one, den, out;
    tvo_jet_constant(TVO_R(1.0), &one);
    tvo_jet_variable(TVO_R(1.0), TVO_R(1.0), &den);
    tvo_jet_div(&one, &den, N, &out);
    const double e[N + 1] = {1, -1, 1, -1};
    assert_jet(e, &out, N);
}

static void test_div_sin_over_cos_is_tan(void)
{
    /* sin t = t - t^3/6, cos t = 1 - t^2/2, tan t = t + t^3/3. */
    const tvo_jet_t s = jet4(0, 1, 0, -1.0 / 6.0);
    const tvo_jet_t c = jet4(1, 0, -0.5, 0);
    tvo_jet_t out;
    tvo_jet_div(&s, &c, N, &out);
    const double e[N + 1] = {0, 1, 0, 1.0 / 3.0};
    assert_jet(e, &out, N);
}

static void test_exp_of_affine_matches_closed_form(void)
{
    /* exp(1 + 2t) = e * exp(2t): c_j = e 2^j / j! = e, 2e, 2e, 4e/3. */
    const double e1 = exp(1.0);
    tvo_jet_t a, out;
    tvo_jet_variable(TVO_R(1.0), TVO_R(2.0), &a);
    tvo_jet_exp(&a, N, &out);
    const double e[N + 1] = {e1, 2.0 * e1, 2.0 * e1, 4.0 * e1 / 3.0};
    assert_jet(e, &out, N);
}

static void test_exp_of_quadratic_matches_closed_form(void)
{
    /* exp(t^2) = 1 + t^2 + O(t^4): exercises the a_2 term of the recurrence. */
    const tvo_jet_t a = jet4(0, 0, 1, 0);
    tvo_jet_t out;
    tvo_jet_exp(&a, N, &out);
    const double e[N + 1] = {1, 0, 1, 0};
    assert_jet(e, &out, N);
}

static void test_log_of_two_plus_tau_matches_closed_form(void)
{
    /* log(2 + t) = log 2 + log(1 + t/2) = log 2 + t/2 - t^2/8 + t^3/24. */
    tvo_jet_t a, out;
    tvo_jet_variable(TVO_R(2.0), TVO_R(1.0), &a);
    tvo_jet_log(&a, N, &out);
    const double e[N + 1] = {log(2.0), 0.5, -0.125, 1.0 / 24.0};
    assert_jet(e, &out, N);
}

static void test_sqrt_of_four_plus_tau_matches_closed_form(void)
{
    /* sqrt(4 + t) = 2 (1 + t/4)^(1/2) = 2 (1 + t/8 - t^2/128 + t^3/1024) = 2 + t/4 - t^2/64 + t^3/512. */
    tvo_jet_t a, out;
    tvo_jet_variable(TVO_R(4.0), TVO_R(1.0), &a);
    tvo_jet_sqrt(&a, N, &out);
    const double e[N + 1] = {2, 0.25, -1.0 / 64.0, 1.0 / 512.0};
    assert_jet(e, &out, N);
}

static void test_sqrt_of_a_square_recovers_it(void)
{
    /* sqrt((1.5 - 2t + t^2/4 + 3t^3)^2) = 1.5 - 2t + t^2/4 + 3t^3 (the c0 > 0 branch). */
    const tvo_jet_t p = jet4(1.5, -2, 0.25, 3);
    tvo_jet_t sq, out;
    tvo_jet_mul(&p, &p, N, &sq);
    tvo_jet_sqrt(&sq, N, &out);
    const double e[N + 1] = {1.5, -2, 0.25, 3};
    assert_jet(e, &out, N);
}

static void test_log_inverts_exp(void)
{
    const tvo_jet_t a = jet4(0.3, -0.7, 1.1, 0.4);
    tvo_jet_t ex, out;
    tvo_jet_exp(&a, N, &ex);
    tvo_jet_log(&ex, N, &out);
    const double e[N + 1] = {0.3, -0.7, 1.1, 0.4};
    assert_jet(e, &out, N);
}

static void test_lower_orders_compute_the_same_prefix(void)
{
    /* A jet op truncated at order n must give the first n + 1 coefficients of the full result. */
    tvo_jet_t a, full, part;
    tvo_jet_variable(TVO_R(2.0), TVO_R(1.0), &a);
    for (uint8_t n = 0; n <= N; ++n) {
        tvo_jet_log(&a, N, &full);
        tvo_jet_log(&a, n, &part);
        for (uint8_t j = 0; j <= n; ++j) {
            ASSERT_NEAR(full.c[j], part.c[j], 0.0);
        }
        tvo_jet_exp(&a, N, &full);
        tvo_jet_exp(&a, n, &part);
        for (uint8_t j = 0; j <= n; ++j) {
            ASSERT_NEAR(full.c[j], part.c[j], 0.0);
        }
    }
}

/* A jet followed by guard words: an op must never write past c[TVO_JET_MAX_ORDER]. */
typedef struct {
    tvo_jet_t jet;
    tvo_real_t guard[4];
} guarded_jet_t;

static void fill_guard(guarded_jet_t *g)
{
    for (int i = 0; i < 4; ++i) {
        g->guard[i] = TVO_R(-777.0);
    }
}

static void assert_guard(const guarded_jet_t *g)
{
    for (int i = 0; i < 4; ++i) {
        ASSERT_NEAR(-777.0, g->guard[i], 0.0);
    }
}

static void test_order_above_maximum_is_clamped(void)
{
    /* order 200 behaves exactly like TVO_JET_MAX_ORDER and writes nothing past the jet. */
    const tvo_jet_t a = jet4(2, 1, 0.5, -0.25);
    const tvo_jet_t b = jet4(1, -1, 2, 0.125);
    guarded_jet_t big;
    tvo_jet_t ref;
    const uint8_t huge = 200;

    fill_guard(&big);
    tvo_jet_mul(&a, &b, huge, &big.jet);
    tvo_jet_mul(&a, &b, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    tvo_jet_div(&a, &b, huge, &big.jet);
    tvo_jet_div(&a, &b, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    tvo_jet_sqrt(&a, huge, &big.jet);
    tvo_jet_sqrt(&a, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    tvo_jet_log(&a, huge, &big.jet);
    tvo_jet_log(&a, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    tvo_jet_exp(&a, huge, &big.jet);
    tvo_jet_exp(&a, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    tvo_jet_add(&a, &b, huge, &big.jet);
    tvo_jet_add(&a, &b, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    fill_guard(&big);
    big.jet = b;
    tvo_jet_axpy(TVO_R(0.5), &a, huge, &big.jet);
    ref = b;
    tvo_jet_axpy(TVO_R(0.5), &a, N, &ref);
    TEST_ASSERT_EQUAL_MEMORY(&ref, &big.jet, sizeof(ref));
    assert_guard(&big);

    /* is_finite with a huge order reads only c[0..N]: the guard beyond is not a coefficient. */
    big.guard[0] = TEST_NAN;
    TEST_ASSERT_EQUAL_INT(1, tvo_jet_is_finite(&big.jet, huge));
}

static void test_mul_output_may_alias_either_input(void)
{
    /* a := a * a for a = 1 + t: 1 + 2t + t^2. */
    tvo_jet_t a;
    tvo_jet_variable(TVO_R(1.0), TVO_R(1.0), &a);
    tvo_jet_mul(&a, &a, N, &a);
    const double e_sq[N + 1] = {1, 2, 1, 0};
    assert_jet(e_sq, &a, N);

    /* b := a * b with a = 1 + 2t + 3t^2 + 4t^3, b = 5 - t + t^2/2 + 2t^3 (see the Cauchy test). */
    const tvo_jet_t a2 = jet4(1, 2, 3, 4);
    tvo_jet_t b = jet4(5, -1, 0.5, 2);
    tvo_jet_mul(&a2, &b, N, &b);
    const double e[N + 1] = {5, 9, 13.5, 20};
    assert_jet(e, &b, N);
}

static void test_div_output_may_alias_either_input(void)
{
    /* tan = sin / cos, written over the numerator, then over the denominator. */
    tvo_jet_t s = jet4(0, 1, 0, -1.0 / 6.0);
    tvo_jet_t c = jet4(1, 0, -0.5, 0);
    const double e[N + 1] = {0, 1, 0, 1.0 / 3.0};
    tvo_jet_div(&s, &c, N, &s);
    assert_jet(e, &s, N);

    tvo_jet_t s2 = jet4(0, 1, 0, -1.0 / 6.0);
    tvo_jet_div(&s2, &c, N, &c);
    assert_jet(e, &c, N);
}

static void test_unary_ops_may_write_over_their_input(void)
{
    tvo_jet_t a;
    tvo_jet_variable(TVO_R(4.0), TVO_R(1.0), &a);
    tvo_jet_sqrt(&a, N, &a);
    const double e_sqrt[N + 1] = {2, 0.25, -1.0 / 64.0, 1.0 / 512.0};
    assert_jet(e_sqrt, &a, N);

    tvo_jet_variable(TVO_R(2.0), TVO_R(1.0), &a);
    tvo_jet_log(&a, N, &a);
    const double e_log[N + 1] = {log(2.0), 0.5, -0.125, 1.0 / 24.0};
    assert_jet(e_log, &a, N);

    tvo_jet_variable(TVO_R(1.0), TVO_R(2.0), &a);
    tvo_jet_exp(&a, N, &a);
    const double e1 = exp(1.0);
    const double e_exp[N + 1] = {e1, 2.0 * e1, 2.0 * e1, 4.0 * e1 / 3.0};
    assert_jet(e_exp, &a, N);
}

static void test_add_sub_may_write_over_an_input(void)
{
    tvo_jet_t a = jet4(1, 2, 3, 4);
    const tvo_jet_t b = jet4(0.5, -1, 0.25, -2);
    tvo_jet_add(&a, &b, N, &a);
    const double e_add[N + 1] = {1.5, 1, 3.25, 2};
    assert_jet(e_add, &a, N);

    tvo_jet_t c = jet4(0.5, -1, 0.25, -2);
    const tvo_jet_t d = jet4(1, 2, 3, 4);
    tvo_jet_sub(&d, &c, N, &c);
    const double e_sub[N + 1] = {0.5, 3, 2.75, 6};
    assert_jet(e_sub, &c, N);
}

static void test_is_finite_checks_only_up_to_order(void)
{
    tvo_jet_t a = jet4(1, 2, 3, 4);
    TEST_ASSERT_EQUAL_INT(1, tvo_jet_is_finite(&a, N));
    a.c[2] = TEST_NAN;
    TEST_ASSERT_EQUAL_INT(1, tvo_jet_is_finite(&a, 1));
    TEST_ASSERT_EQUAL_INT(0, tvo_jet_is_finite(&a, 2));
    a.c[2] = TVO_R(3.0);
    a.c[3] = TEST_INF;
    TEST_ASSERT_EQUAL_INT(1, tvo_jet_is_finite(&a, 2));
    TEST_ASSERT_EQUAL_INT(0, tvo_jet_is_finite(&a, N));
    a.c[3] = (-TEST_INF);
    TEST_ASSERT_EQUAL_INT(0, tvo_jet_is_finite(&a, N));
    a.c[3] = TVO_R(4.0);
    a.c[0] = TEST_NAN;
    TEST_ASSERT_EQUAL_INT(0, tvo_jet_is_finite(&a, 0));
}

static void test_chain_gives_second_derivative_of_a_composite(void)
{
    /* f(t) = sqrt(1 + t^2) / (2 + t) at t = 0.5, computed on the jet t = 0.5 + tau:
     * f(tau) Taylor coefficients equal f^(j)(0.5) / j!. Reference by hand:
     *   g = sqrt(1 + t^2): g' = t/g, g'' = 1/g^3.
     *   q = g / (2 + t): q' = g'/(2+t) - g/(2+t)^2,
     *                    q'' = g''/(2+t) - 2 g'/(2+t)^2 + 2 g/(2+t)^3. */
    const double t = 0.5;
    const double g = sqrt(1.0 + t * t);
    const double g1 = t / g;
    const double g2 = 1.0 / (g * g * g);
    const double d = 2.0 + t;
    const double q = g / d;
    const double q1 = g1 / d - g / (d * d);
    const double q2 = g2 / d - 2.0 * g1 / (d * d) + 2.0 * g / (d * d * d);

    tvo_jet_t x, x2, one, num, den, out;
    tvo_jet_variable(TVO_R(0.5), TVO_R(1.0), &x);
    tvo_jet_mul(&x, &x, N, &x2);
    tvo_jet_constant(TVO_R(1.0), &one);
    tvo_jet_add(&one, &x2, N, &num);
    tvo_jet_sqrt(&num, N, &num);
    tvo_jet_constant(TVO_R(2.0), &den);
    tvo_jet_add(&den, &x, N, &den);
    tvo_jet_div(&num, &den, N, &out);
    ASSERT_NEAR(q, out.c[0], JET_TOL(q));
    ASSERT_NEAR(q1, out.c[1], JET_TOL(q1));
    ASSERT_NEAR(q2 / 2.0, out.c[2], JET_TOL(q2));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_max_order_is_three);
    RUN_TEST(test_constant_and_variable_zero_the_higher_coefficients);
    RUN_TEST(test_add_sub_scale_axpy_are_coefficientwise);
    RUN_TEST(test_mul_is_the_cauchy_product);
    RUN_TEST(test_div_reciprocal_of_one_plus_tau_is_alternating_series);
    RUN_TEST(test_div_sin_over_cos_is_tan);
    RUN_TEST(test_exp_of_affine_matches_closed_form);
    RUN_TEST(test_exp_of_quadratic_matches_closed_form);
    RUN_TEST(test_log_of_two_plus_tau_matches_closed_form);
    RUN_TEST(test_sqrt_of_four_plus_tau_matches_closed_form);
    RUN_TEST(test_sqrt_of_a_square_recovers_it);
    RUN_TEST(test_log_inverts_exp);
    RUN_TEST(test_lower_orders_compute_the_same_prefix);
    RUN_TEST(test_order_above_maximum_is_clamped);
    RUN_TEST(test_mul_output_may_alias_either_input);
    RUN_TEST(test_div_output_may_alias_either_input);
    RUN_TEST(test_unary_ops_may_write_over_their_input);
    RUN_TEST(test_add_sub_may_write_over_an_input);
    RUN_TEST(test_is_finite_checks_only_up_to_order);
    RUN_TEST(test_chain_gives_second_derivative_of_a_composite);
    return UNITY_END();
}
