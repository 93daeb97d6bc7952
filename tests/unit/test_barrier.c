/*
 * The relaxed log barrier B_delta (paper, eq. "relaxed barrier") and its schedules:
 *   - tvo_barrier_derivatives against the closed form on both branches (-log sigma above delta, the
 *     degree-m_r Taylor continuation below), for m_r = 3, 4, 6;
 *   - continuity of B^(n) at sigma = delta for n <= m_r and the jump of B^(m_r+1);
 *   - tvo_barrier_weight_jet: its value is -(1/c) B'_delta(s - f) with c, s, delta of the schedule; its
 *     jet coefficients are the time derivatives of that scalar weight along f(tau), t + tau (finite
 *     differences, both branches); the cap c_max; rate 0 freezes the schedules;
 *   - the s0 rule and the parameter checks.
 */
#include "fd_support.h"

#include "tvo/barrier.h"
#include "internal/barrier.h"
#include "internal/jet.h"

void setUp(void) {}
void tearDown(void) {}

/* ------------------------------------------------------------------------------------------------
 * Closed forms, in double
 * --------------------------------------------------------------------------------------------- */

/* d^n/dsigma^n (-log sigma). */
static double log_branch(unsigned n, double sigma)
{
    if (n == 0u) {
        return -log(sigma);
    }
    double fact = 1.0; /* (n-1)! */
    for (unsigned i = 2; i < n; ++i) {
        fact *= (double)i;
    }
    return ((n % 2u) ? -1.0 : 1.0) * fact / pow(sigma, (double)n);
}

/* d^n/dsigma^n of -log delta + sum_{j=1..m} u^j / j, u = (delta - sigma)/delta, by differentiating the
 * coefficient list of the polynomial in u n times and applying du/dsigma = -1/delta n times. */
static double relaxed_branch(unsigned m, unsigned n, double sigma, double delta)
{
    double coeff[TVO_BARRIER_MAX_DEGREE + 2];
    coeff[0] = -log(delta);
    for (unsigned j = 1; j <= m; ++j) {
        coeff[j] = 1.0 / (double)j;
    }
    unsigned degree = m;
    for (unsigned d = 0; d < n; ++d) {
        if (degree == 0u) {
            return 0.0;
        }
        for (unsigned j = 0; j < degree; ++j) {
            coeff[j] = (double)(j + 1u) * coeff[j + 1u];
        }
        degree--;
    }
    const double u = (delta - sigma) / delta;
    double p = 0.0;
    for (unsigned jj = degree + 1u; jj > 0u; --jj) {
        p = p * u + coeff[jj - 1u];
    }
    return pow(-1.0 / delta, (double)n) * p;
}

static tvo_real_t real_below(tvo_real_t x)
{
#if TVO_USE_DOUBLE
    return nextafter(x, -HUGE_VAL); /* HUGE_VAL is a double: INFINITY is a float and would be promoted */
#else
    return nextafterf(x, -INFINITY);
#endif
}

/* ------------------------------------------------------------------------------------------------
 * tvo_barrier_derivatives
 * --------------------------------------------------------------------------------------------- */

static const uint8_t DEGREES[3] = {3u, 4u, 6u};

static void test_derivatives_log_branch_match_closed_form(void)
{
    const double delta = 0.05;
    const double sigmas[4] = {0.05, 0.3, 1.0, 2.5};
    for (int di = 0; di < 3; ++di) {
        const uint8_t m = DEGREES[di];
        const uint8_t order = (uint8_t)(m + 1u);
        for (int si = 0; si < 4; ++si) {
            const tvo_real_t sigma = test_r(sigmas[si]);
            tvo_real_t d[TVO_BARRIER_MAX_DEGREE + 1];
            ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(m, sigma, test_r(delta), order, d));
            for (unsigned n = 0; n <= order; ++n) {
                const double ref = log_branch(n, test_d(sigma));
                /* n multiplications and one division or log: a few ulps per step, 8 per step granted. */
                ASSERT_NEAR_MSG(ref, d[n], 8.0 * (n + 2.0) * TEST_EPS * (fabs(ref) + (n == 0u ? 1.0 : 0.0)),
                                "log branch");
            }
        }
    }
}

static void test_derivatives_relaxed_branch_match_closed_form(void)
{
    const double delta = 0.05;
    /* Just below delta, inside (0, delta), at 0 and infeasible (negative): all on the polynomial. */
    const double sigmas[5] = {0.049, 0.03, 0.0, -0.1, -1.0};
    for (int di = 0; di < 3; ++di) {
        const uint8_t m = DEGREES[di];
        const uint8_t order = (uint8_t)(m + 1u);
        for (int si = 0; si < 5; ++si) {
            const tvo_real_t sigma = test_r(sigmas[si]);
            tvo_real_t d[TVO_BARRIER_MAX_DEGREE + 1];
            ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(m, sigma, test_r(delta), order, d));
            const double delta_r = test_d(test_r(delta));
            for (unsigned n = 0; n <= order; ++n) {
                const double ref = relaxed_branch(m, n, test_d(sigma), delta_r);
                /* u >= 0 here, so every summand is positive: (m + n + 2) roundings of the sum's size. */
                ASSERT_NEAR_MSG(ref, d[n], 8.0 * (m + n + 2.0) * TEST_EPS * fabs(ref), "relaxed branch");
            }
            /* The degree-m polynomial's (m+1)-th derivative vanishes. */
            ASSERT_NEAR(0.0, d[m + 1u], 0.0);
        }
    }
}

static void test_derivatives_continuous_up_to_m_r_at_delta_and_not_beyond(void)
{
    const double deltas[3] = {0.05, 0.5, 2.0};
    for (int di = 0; di < 3; ++di) {
        const uint8_t m = DEGREES[di];
        const uint8_t order = (uint8_t)(m + 1u);
        for (int k = 0; k < 3; ++k) {
            const tvo_real_t delta = test_r(deltas[k]);
            const tvo_real_t left_sigma = real_below(delta); /* the relaxation's side, one ulp away */
            tvo_real_t right[TVO_BARRIER_MAX_DEGREE + 1], left[TVO_BARRIER_MAX_DEGREE + 1];
            ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(m, delta, delta, order, right));
            ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(m, left_sigma, delta, order, left));
            for (unsigned n = 0; n <= m; ++n) {
                /* Left and right limits agree: both equal (-1)^n (n-1)!/delta^n up to rounding and the
                 * one-ulp step (which moves B^(n) by |B^(n+1)| ulp(delta) ~ n eps |B^(n)|). */
                const double ref = log_branch(n, test_d(delta));
                const double tol = 8.0 * (m + n + 2.0) * TEST_EPS * (fabs(ref) + (n == 0u ? 1.0 : 0.0));
                ASSERT_NEAR_MSG(test_d(right[n]), left[n], tol, "left and right limits of B^(n) differ");
                ASSERT_NEAR_MSG(ref, right[n], tol, "B^(n)(delta) is not the logarithm's");
            }
            /* B^(m_r+1) jumps: 0 on the polynomial side, m_r!/delta^(m_r+1) in magnitude on the log side. */
            const double jump = log_branch(m + 1u, test_d(delta));
            ASSERT_NEAR(0.0, left[m + 1u], 0.0);
            ASSERT_NEAR_MSG(jump, right[m + 1u], 16.0 * (m + 2.0) * TEST_EPS * fabs(jump), "B^(m_r+1) on the log side");
            TEST_ASSERT_TRUE_MESSAGE(fabs(test_d(right[m + 1u]) - test_d(left[m + 1u])) > 0.99 * fabs(jump),
                                     "B^(m_r+1) must be discontinuous at delta");
        }
    }
}

static void test_derivatives_reject_bad_arguments(void)
{
    tvo_real_t d[TVO_BARRIER_MAX_DEGREE + 1];
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_derivatives(4, TVO_R(1.0), TVO_R(0.1), 2, NULL));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_derivatives(0, TVO_R(1.0), TVO_R(0.1), 2, d));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_derivatives(TVO_BARRIER_MAX_DEGREE + 1, TVO_R(1.0), TVO_R(0.1), 2, d));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_derivatives(4, TVO_R(1.0), TVO_R(0.1), TVO_BARRIER_MAX_DEGREE + 1, d));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_barrier_derivatives(4, TEST_NAN, TVO_R(0.1), 2, d));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_barrier_derivatives(4, TVO_R(1.0), TVO_R(0.0), 2, d));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_barrier_derivatives(4, TVO_R(1.0), TEST_INF, 2, d));
}

/* ------------------------------------------------------------------------------------------------
 * Barrier instance: init, schedules, s0 rule
 * --------------------------------------------------------------------------------------------- */

static tvo_barrier_config_t config(double c0, double alpha_c, double c_max, double delta0, double alpha_s,
                                   double margin, uint8_t m)
{
    tvo_barrier_config_t cfg;
    cfg.c0 = test_r(c0);
    cfg.alpha_c_per_s = test_r(alpha_c);
    cfg.c_max = test_r(c_max);
    cfg.delta0 = test_r(delta0);
    cfg.alpha_s_per_s = test_r(alpha_s);
    cfg.slack_margin = test_r(margin);
    cfg.relaxation_degree = m;
    return cfg;
}

static void test_init_checks_every_field_and_m_r_against_k(void)
{
    tvo_barrier_t b;
    tvo_barrier_config_t cfg;
    ASSERT_STATUS(TVO_OK, tvo_barrier_config_default(&cfg));
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 2));
    TEST_ASSERT_EQUAL_UINT8(1, b.initialized);
    ASSERT_NEAR(0.0, b.slack0, 0.0);

    const tvo_barrier_config_t good = config(1.0, 1.0, 100.0, 0.05, 1.0, 0.1, 3);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &good, 2)); /* m_r = k + 1 is the least allowed */
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &good, 3)); /* m_r = 3 < k + 1 = 4 */
    TEST_ASSERT_EQUAL_UINT8(0, b.initialized);
    tvo_barrier_config_t bad = good;
    bad.relaxation_degree = 2u;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad.relaxation_degree = (uint8_t)(TVO_BARRIER_MAX_DEGREE + 1);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &good, 0));
    bad = good;
    bad.c0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.c0 = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.alpha_c_per_s = TVO_R(-0.1);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.c_max = TVO_R(0.5); /* below c0 */
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.c_max = TEST_INF;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.delta0 = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.alpha_s_per_s = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    bad = good;
    bad.slack_margin = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_init(&b, &bad, 2));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_init(NULL, &good, 2));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_init(&b, NULL, 2));
}

static void test_schedules_follow_the_closed_form(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(2.0, 0.5, 1000.0, 0.25, 0.75, 0.1, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(0.4)));
    const double times[3] = {0.0, 0.5, 3.0};
    for (int i = 0; i < 3; ++i) {
        tvo_real_t c, s, delta;
        ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&b, test_r(times[i]), &c, &s, &delta));
        const double c_ref = 2.0 * exp(0.5 * times[i]);
        const double s_ref = test_d(test_r(0.5)) * exp(-0.75 * times[i]);
        /* One exp and a product or quotient each: a few ulps. */
        ASSERT_NEAR(c_ref, c, TEST_TOL(8, c_ref));
        ASSERT_NEAR(s_ref, s, TEST_TOL(8, s_ref));
        ASSERT_NEAR(0.25 / c_ref, delta, TEST_TOL(8, 0.25 / c_ref));
    }
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_barrier_schedule(&b, TEST_NAN, &c, &s, &delta));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_schedule(&b, TVO_R(0.0), NULL, &s, &delta));
    tvo_barrier_t fresh;
    memset(&fresh, 0, sizeof(fresh));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_barrier_schedule(&fresh, TVO_R(0.0), &c, &s, &delta));
}

static void test_slack_rule_zero_when_feasible_else_max_plus_margin(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(1.0, 1.0, 100.0, 0.05, 1.0, 0.125, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 2));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(-0.5)));
    ASSERT_NEAR(0.0, b.slack0, 0.0); /* strictly feasible start: no slack */
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(-1e-6)));
    ASSERT_NEAR(0.0, b.slack0, 0.0);
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(0.0)));
    ASSERT_NEAR(0.125, b.slack0, 0.0); /* on the boundary counts as infeasible (paper: max >= 0) */
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(0.375)));
    ASSERT_NEAR(0.5, b.slack0, 0.0); /* 0.375 + 0.125, exact in binary */
    /* The schedule uses it: s(1) = s0 e^{-1}. */
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&b, TVO_R(1.0), &c, &s, &delta));
    ASSERT_NEAR(0.5 * exp(-1.0), s, TEST_TOL(8, 0.5));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_barrier_choose_slack(&b, TEST_NAN));
    ASSERT_NEAR(0.5, b.slack0, 0.0); /* a rejected value changes nothing */
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_choose_slack(NULL, TVO_R(1.0)));
    tvo_barrier_t fresh;
    memset(&fresh, 0, sizeof(fresh));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_barrier_choose_slack(&fresh, TVO_R(1.0)));
}

/* ------------------------------------------------------------------------------------------------
 * tvo_barrier_weight_jet
 * --------------------------------------------------------------------------------------------- */

static tvo_time_jet_t time_jet(double t_s, double rate)
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), test_r(rate), 1000000u, (uint64_t)llround(t_s * 1e6));
    return t;
}

/* w = -(1/c) B'_delta(s - f) from the schedule and tvo_barrier_derivatives; also dw/dsigma. */
static void weight_reference(const tvo_barrier_t *b, double t_s, tvo_real_t f, double *w, double *dw, double *sigma_out,
                             double *s_out, double *delta_out)
{
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(b, test_r(t_s), &c, &s, &delta));
    const tvo_real_t sigma = s - f;
    tvo_real_t d[3];
    ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(b->cfg.relaxation_degree, sigma, delta, 2, d));
    *w = -test_d(d[1]) / test_d(c);
    *dw = -test_d(d[2]) / test_d(c);
    *sigma_out = test_d(sigma);
    *s_out = test_d(s);
    *delta_out = test_d(delta);
}

static void test_weight_value_is_minus_barrier_slope_over_c_on_both_branches(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(2.0, 0.5, 1000.0, 0.5, 0.75, 0.25, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(1.0))); /* s0 = 1.25 */
    const double times[3] = {0.0, 0.5, 2.0};
    const double fs[6] = {-3.0, -1.0, 0.5, 0.75, 1.0, 2.5};
    int seen_log = 0, seen_relaxed = 0, seen_infeasible = 0;
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 6; ++j) {
            const tvo_real_t f = test_r(fs[j]);
            double w, dw, sigma, s, delta;
            weight_reference(&b, times[i], f, &w, &dw, &sigma, &s, &delta);
            seen_log |= sigma >= delta;
            seen_relaxed |= sigma < delta && sigma > 0.0;
            seen_infeasible |= sigma < 0.0;
            tvo_jet_t fj, wj;
            tvo_jet_constant(f, &fj);
            const tvo_time_jet_t t = time_jet(times[i], 1.0);
            ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &t, 0, &wj));
            /* Both paths round sigma = s - f (error eps (|s| + |f|), times dw/dsigma), and the relaxed
             * path rounds u = 1 - c sigma / delta0 (error eps (delta + |sigma|) in sigma units); 64 ulps. */
            const double tol = 64.0 * TEST_EPS * (fabs(w) + fabs(dw) * (s + fabs(test_d(f)) + delta + fabs(sigma)));
            ASSERT_NEAR_MSG(w, wj.c[0], tol, "weight != -(1/c) B'(s - f)");
            TEST_ASSERT_TRUE_MESSAGE(wj.c[0] > TVO_R(0.0), "the weight is positive");
        }
    }
    TEST_ASSERT_TRUE_MESSAGE(seen_log && seen_relaxed && seen_infeasible, "the grid must cover every branch");
}

typedef struct {
    const tvo_barrier_t *b;
    double t_s;
    double rate;
    double f[4]; /* f(tau) = f0 + f1 tau + f2 tau^2 + f3 tau^3 */
} weight_path_t;

/* W(tau) = the order-0 weight at f(tau) and t + rate tau. */
static int weight_along(void *ctx, double tau, double *out)
{
    const weight_path_t *p = (const weight_path_t *)ctx;
    const double f = p->f[0] + tau * (p->f[1] + tau * (p->f[2] + tau * p->f[3]));
    tvo_jet_t fj, wj;
    tvo_jet_constant(test_r(f), &fj);
    const tvo_time_jet_t t = time_jet(p->t_s + p->rate * tau, p->rate);
    if (tvo_barrier_weight_jet(p->b, &fj, &t, 0, &wj) != TVO_OK) {
        return 1;
    }
    out[0] = test_d(wj.c[0]);
    return 0;
}

/* c(t) sigma(t) / delta0 - 1 at tau: >= 0 on the logarithm. */
static double branch_x(const weight_path_t *p, double tau)
{
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(p->b, test_r(p->t_s + p->rate * tau), &c, &s, &delta));
    const double f = p->f[0] + tau * (p->f[1] + tau * (p->f[2] + tau * p->f[3]));
    return test_d(c) * (test_d(s) - f) / test_d(p->b->cfg.delta0) - 1.0;
}

/* length: the tau scale on which w changes by O(w) (the FD steps are fractions of it). */
static void check_weight_jet_against_time_differences(weight_path_t *p, double length, int expect_log,
                                                      const char *what)
{
    /* The stencils (up to +-6 h = +-0.75 L for k = 3 in float32) stay on one branch. */
    const double span = 6.0 * length * fd_step_rel(3);
    for (int j = -6; j <= 6; ++j) {
        const double x = branch_x(p, span * j / 6.0);
        TEST_ASSERT_TRUE_MESSAGE(expect_log ? x >= 0.0 : x < 0.0, "stencil crosses the branch switch");
    }
    tvo_jet_t fj, wj;
    tvo_jet_constant(TVO_R(0.0), &fj);
    for (int j = 0; j <= 3; ++j) {
        fj.c[j] = test_r(p->f[j]);
    }
    const tvo_time_jet_t t = time_jet(p->t_s, p->rate);
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(p->b, &fj, &t, 3, &wj));
    double w0 = 0.0;
    TEST_ASSERT_EQUAL_INT(0, weight_along(p, 0.0, &w0));
    ASSERT_NEAR_MSG(w0, wj.c[0], TEST_TOL(64, w0), what); /* the same computation at order 0 */
    /* cond: sigma = s - f is rounded to eps (|s| + |f|) and the relaxation's u = 1 - c sigma / delta0
     * to eps (delta + |sigma|) in sigma units; w moves by |dw/dsigma| per unit of sigma. */
    double w_ref, dw, sigma, s, delta;
    weight_reference(p->b, p->t_s, test_r(p->f[0]), &w_ref, &dw, &sigma, &s, &delta);
    const double cond = 1.0 + fabs(dw) * (s + fabs(p->f[0]) + delta + fabs(sigma)) / w_ref;
    const double fact[4] = {1.0, 1.0, 2.0, 6.0};
    for (unsigned k = 1; k <= 3; ++k) {
        const double expected = test_d(wj.c[k]) * fact[k];
        FD_CHECK(weight_along, p, 1, k, length, cond, &expected, what);
    }
}

static void test_weight_jet_is_the_time_derivative_of_the_weight_on_both_branches(void)
{
    tvo_barrier_t b;
    /* At t = 1: c = 3.30, delta = 0.152, s = 1.25 e^-0.75 = 0.590. The paths have a sizeable cubic
     * term so that every derivative up to the third is far from zero (an informative comparison). */
    const tvo_barrier_config_t cfg = config(2.0, 0.5, 1000.0, 0.5, 0.75, 0.25, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(1.0)));
    /* w = 1/(c sigma) with sigma ~ 1.6 moving by ~1 per unit tau: w changes by O(w) over tau ~ 0.5. */
    weight_path_t p = {&b, 1.0, 1.0, {-1.0, 0.5, -0.25, 0.5}};
    check_weight_jet_against_time_differences(&p, 0.5, 1, "logarithm (sigma = 1.59)");
    /* u = 1 - c sigma / delta0 moves by ~0.5 per unit tau: the cubic in u changes by O(w) over 0.25. */
    weight_path_t q = {&b, 1.0, 1.0, {0.55, -0.5, 1.0, -0.5}};
    check_weight_jet_against_time_differences(&q, 0.25, 0, "relaxation, feasible (0 < sigma = 0.04 < delta)");
    weight_path_t r = {&b, 1.0, 1.0, {1.5, 0.25, 0.5, 0.5}};
    check_weight_jet_against_time_differences(&r, 0.25, 0, "relaxation, infeasible (sigma = -0.91)");
}

static void test_weight_jet_with_degree_six_relaxation(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(1.0, 1.0, 1000.0, 0.5, 0.5, 0.25, 6);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(0.25))); /* s0 = 0.5 */
    /* t = 1: c = 2.72, s = 0.303; f = 0.5: sigma = -0.197 (relaxed, infeasible), u = 2.07; the
     * degree-5 polynomial in u changes by O(w) over tau ~ 0.25. */
    weight_path_t p = {&b, 1.0, 1.0, {0.5, 0.25, -0.25, 0.5}};
    check_weight_jet_against_time_differences(&p, 0.25, 0, "m_r = 6, relaxation");
}

static void test_weight_jet_cap_makes_c_constant(void)
{
    tvo_barrier_t b;
    /* c = e^{2t} capped at 8: cap_time = ln(8)/2. s0 = 0 (feasible start), so only c moves. */
    const tvo_barrier_config_t cfg = config(1.0, 2.0, 8.0, 0.05, 1.0, 0.1, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(-1.0)));
    ASSERT_NEAR(log(8.0) / 2.0, b.cap_time_s, TEST_TOL(8, 1.0));
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&b, TVO_R(5.0), &c, &s, &delta));
    ASSERT_NEAR(8.0, c, 0.0);
    ASSERT_NEAR(0.05 / 8.0, delta, TEST_TOL(4, 0.01));
    /* Continuous at the cap: just before it c is 8 to rounding of exp. */
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&b, test_r(test_d(b.cap_time_s) * (1.0 - 1e-4)), &c, &s, &delta));
    ASSERT_NEAR(8.0 * exp(-2e-4 * test_d(b.cap_time_s)), c, TEST_TOL(64, 8.0));

    /* f = -1 constant, sigma = 1 on the logarithm: w = 1/(c sigma) = e^{-2t}/sigma before the cap. */
    tvo_jet_t fj, wj;
    tvo_jet_constant(TVO_R(-1.0), &fj);
    const tvo_time_jet_t before = time_jet(0.5, 1.0);
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &before, 3, &wj));
    const double w = exp(-1.0);
    const double coeff[4] = {w, -2.0 * w, 2.0 * w, -4.0 / 3.0 * w}; /* w (-2)^j / j! */
    for (int j = 0; j <= 3; ++j) {
        ASSERT_NEAR(coeff[j], wj.c[j], TEST_TOL(32, coeff[j]));
    }
    const tvo_time_jet_t after = time_jet(2.0, 1.0);
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &after, 3, &wj));
    ASSERT_NEAR(1.0 / 8.0, wj.c[0], TEST_TOL(4, 0.125));
    for (int j = 1; j <= 3; ++j) {
        ASSERT_NEAR(0.0, wj.c[j], 0.0); /* c constant past the cap: no time derivative at all */
    }
}

static void test_weight_jet_rate_zero_freezes_the_schedules(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(1.0, 1.0, 1000.0, 0.05, 1.0, 0.25, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&b, TVO_R(0.75))); /* s0 = 1 */
    const tvo_time_jet_t frozen = time_jet(0.5, 0.0);
    const tvo_time_jet_t moving = time_jet(0.5, 1.0);
    tvo_jet_t fj, wj, wm;
    /* f constant: frozen schedules leave nothing to move. */
    tvo_jet_constant(TVO_R(-0.5), &fj);
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &frozen, 3, &wj));
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &moving, 3, &wm));
    for (int j = 1; j <= 3; ++j) {
        ASSERT_NEAR(0.0, wj.c[j], 0.0);
    }
    TEST_ASSERT_TRUE_MESSAGE(fabs(test_d(wm.c[1])) > 0.1 * test_d(wm.c[0]), "with rate 1 the schedules do move w");
    /* f = f0 + f1 tau, schedules frozen: w = 1/(c (sigma0 - f1 tau)) = w0 sum (f1 tau / sigma0)^j. */
    tvo_jet_variable(TVO_R(-0.5), TVO_R(0.25), &fj);
    ASSERT_STATUS(TVO_OK, tvo_barrier_weight_jet(&b, &fj, &frozen, 3, &wj));
    const double c = exp(0.5), s = exp(-0.5), sigma0 = s + 0.5;
    const double w0 = 1.0 / (c * sigma0);
    for (int j = 0; j <= 3; ++j) {
        const double ref = w0 * pow(0.25 / sigma0, (double)j);
        ASSERT_NEAR(ref, wj.c[j], TEST_TOL(64, w0)); /* exp, a quotient and j products: tens of ulps */
    }
}

static void test_weight_jet_rejects_bad_arguments(void)
{
    tvo_barrier_t b;
    const tvo_barrier_config_t cfg = config(1.0, 1.0, 1000.0, 0.05, 1.0, 0.25, 4);
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&b, &cfg, 3));
    tvo_jet_t fj, wj;
    tvo_jet_constant(TVO_R(-0.5), &fj);
    const tvo_time_jet_t t = time_jet(0.5, 1.0);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_weight_jet(NULL, &fj, &t, 1, &wj));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_barrier_weight_jet(&b, NULL, &t, 1, &wj));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_barrier_weight_jet(&b, &fj, &t, TVO_JET_MAX_ORDER + 1, &wj));
    tvo_barrier_t fresh;
    memset(&fresh, 0, sizeof(fresh));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_barrier_weight_jet(&fresh, &fj, &t, 1, &wj));
    tvo_jet_constant(TEST_NAN, &fj);
    ASSERT_STATUS(TVO_ERR_NUMERIC, tvo_barrier_weight_jet(&b, &fj, &t, 1, &wj));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_derivatives_log_branch_match_closed_form);
    RUN_TEST(test_derivatives_relaxed_branch_match_closed_form);
    RUN_TEST(test_derivatives_continuous_up_to_m_r_at_delta_and_not_beyond);
    RUN_TEST(test_derivatives_reject_bad_arguments);
    RUN_TEST(test_init_checks_every_field_and_m_r_against_k);
    RUN_TEST(test_schedules_follow_the_closed_form);
    RUN_TEST(test_slack_rule_zero_when_feasible_else_max_plus_margin);
    RUN_TEST(test_weight_value_is_minus_barrier_slope_over_c_on_both_branches);
    RUN_TEST(test_weight_jet_is_the_time_derivative_of_the_weight_on_both_branches);
    RUN_TEST(test_weight_jet_with_degree_six_relaxation);
    RUN_TEST(test_weight_jet_cap_makes_c_constant);
    RUN_TEST(test_weight_jet_rate_zero_freezes_the_schedules);
    RUN_TEST(test_weight_jet_rejects_bad_arguments);
    return UNITY_END();
}
