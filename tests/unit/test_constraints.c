/*
 * Inequality-constraint terms (tvo/constraints.h) against finite differences of the term itself, at
 * points on both barrier branches (feasible with sigma > delta; feasible or on the boundary inside the
 * relaxation; infeasible):
 *   (a) Hessian columns: order-1 jets in a unit direction with time frozen (rate 0) vs central
 *       differences in y of the order-0 gradient;
 *   (b) trajectory jets of order 2 and 3 (rate 1) vs differences in time of the order-0 gradient along
 *       y(tau) = y + y' tau + y'' tau^2 / 2, t + tau;
 *   (c) the order-0 gradient vs differences in y of the scalar potential (1/c) B_delta(s - f), from
 *       tvo_barrier_derivatives[0] and the term's own constraint value.
 * Distance bounds (minimum and maximum, time-varying bound), half-spaces (time-varying a(t), b(t)) and
 * the local free space among disks. The free-space term freezes the robot's own position y_c at the
 * jet's constant coefficient (header): its references hold y_c fixed, built from the core's barrier
 * and the term's constraint value, and a test shows what the freezing omits.
 */
#include "fd_support.h"

#include "tvo/constraints.h"
#include "internal/barrier.h"
#include "internal/constraints.h"
#include "internal/jet.h"

void setUp(void) {}
void tearDown(void) {}

/* Schedules at T0 = 0.5 with c0 = 1, alpha_c = 0.5, delta0 = 2, alpha_s = 1:
 * c = 1.284, delta = 1.558, s = s0 e^-0.5. A large delta0 gives a wide relaxation band (and a smooth
 * relaxation polynomial) to put points in with room for the stencils. */
#define T0 0.5

static tvo_barrier_t barrier;

/* Barrier with s0 chosen from max_value by the s0 rule (m_r = 4, so k = 3 jets are smooth). */
static void make_barrier(double max_value)
{
    tvo_barrier_config_t cfg;
    cfg.c0 = TVO_R(1.0);
    cfg.alpha_c_per_s = TVO_R(0.5);
    cfg.c_max = TVO_R(1000.0);
    cfg.delta0 = TVO_R(2.0);
    cfg.alpha_s_per_s = TVO_R(1.0);
    cfg.slack_margin = TVO_R(0.25);
    cfg.relaxation_degree = 4u;
    ASSERT_STATUS(TVO_OK, tvo_barrier_init(&barrier, &cfg, 3));
    ASSERT_STATUS(TVO_OK, tvo_barrier_choose_slack(&barrier, test_r(max_value)));
}

static tvo_time_jet_t time_jet(double t_s, double rate)
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), test_r(rate), 1000000u, (uint64_t)llround(t_s * 1e6));
    return t;
}

typedef struct {
    double c, s, delta;
} schedule_t;

static schedule_t schedule_at(double t_s)
{
    tvo_real_t c, s, delta;
    ASSERT_STATUS(TVO_OK, tvo_barrier_schedule(&barrier, test_r(t_s), &c, &s, &delta));
    const schedule_t out = {test_d(c), test_d(s), test_d(delta)};
    return out;
}

/* ------------------------------------------------------------------------------------------------
 * A term, a point and a path; its constraint value f(y, t) for branch checks and potentials.
 * --------------------------------------------------------------------------------------------- */

#define MODE_DIRECTION 0 /* y + tau e_col, time frozen */
#define MODE_TRAJECTORY 1 /* y + y' tau + y'' tau^2 / 2, t + tau */

typedef struct term_case term_case_t;
/* f(y, t) of the (single) constraint, as the core computes it (the branch and the potential use it). */
typedef double (*constraint_value_fn)(const term_case_t *tc, const double *y, double t_s);

struct term_case {
    tvo_gradient_jet_fn gradient;
    const void *term;
    constraint_value_fn value;
    uint8_t dim;
    uint8_t active[4];       /* the z indices the term touches */
    uint8_t active_count;
    double f_scale;          /* sum of the magnitudes f is computed from (its rounding scale) */
    double y[FD_MAX_DIM], v[FD_MAX_DIM], a[FD_MAX_DIM];
    /* free space: reference gradient with y_c frozen (NULL: the term's own order-0 gradient) */
    int (*frozen_gradient)(const term_case_t *tc, const double *y, double t_s, const double *y_c, double *g);
    int mode;
    unsigned col;
    const char *name;
};

static void point_on_path(const term_case_t *tc, int mode, unsigned col, double tau, double *y, double *t_s)
{
    for (unsigned i = 0; i < tc->dim; ++i) {
        y[i] = (mode == MODE_DIRECTION) ? tc->y[i] + (i == col ? tau : 0.0)
                                        : tc->y[i] + tc->v[i] * tau + 0.5 * tc->a[i] * tau * tau;
    }
    *t_s = (mode == MODE_DIRECTION) ? T0 : T0 + tau;
}

/* The term's order-0 gradient at (y, t). */
static int term_gradient(const term_case_t *tc, const double *y, double t_s, double *g)
{
    tvo_jet_t z[FD_MAX_DIM], grad[FD_MAX_DIM];
    for (unsigned i = 0; i < tc->dim; ++i) {
        tvo_jet_constant(test_r(y[i]), &z[i]);
        tvo_jet_constant(TVO_R(0.0), &grad[i]);
    }
    const tvo_time_jet_t t = time_jet(t_s, 1.0);
    if (tc->gradient(tc->term, z, tc->dim, &t, 0, grad) != TVO_OK) {
        return 1;
    }
    for (unsigned i = 0; i < tc->dim; ++i) {
        g[i] = test_d(grad[i].c[0]);
    }
    return 0;
}

/* G(tau): the order-0 gradient along the case's path (y_c frozen at the path's start if the case
 * has a frozen reference). */
static int gradient_along(void *ctx, double tau, double *out)
{
    const term_case_t *tc = (const term_case_t *)ctx;
    double y[FD_MAX_DIM], t_s;
    point_on_path(tc, tc->mode, tc->col, tau, y, &t_s);
    if (tc->frozen_gradient != NULL) {
        return tc->frozen_gradient(tc, y, t_s, tc->y, out);
    }
    return term_gradient(tc, y, t_s, out);
}

/* Phi(tau) = (1/c) B_delta(s - f) along e_col (time frozen), from the core's barrier and f. */
static int potential_along(void *ctx, double tau, double *out)
{
    const term_case_t *tc = (const term_case_t *)ctx;
    double y[FD_MAX_DIM], t_s;
    point_on_path(tc, MODE_DIRECTION, tc->col, tau, y, &t_s);
    const schedule_t sch = schedule_at(t_s);
    const double f = tc->value(tc, y, t_s);
    tvo_real_t b[1];
    if (tvo_barrier_derivatives(barrier.cfg.relaxation_degree, test_r(sch.s) - test_r(f), test_r(sch.delta), 0, b) !=
        TVO_OK) {
        return 1;
    }
    out[0] = test_d(b[0]) / sch.c;
    return 0;
}

/* x = sigma - delta at tau along a path: the branch (>= 0: logarithm). */
static double branch_at(const term_case_t *tc, int mode, unsigned col, double tau)
{
    double y[FD_MAX_DIM], t_s;
    point_on_path(tc, mode, col, tau, y, &t_s);
    const schedule_t sch = schedule_at(t_s);
    return sch.s - tc->value(tc, y, t_s) - sch.delta;
}

/* w and dw/dsigma at the case's point, from tvo_barrier_derivatives. */
static void weight_at_point(const term_case_t *tc, double *sigma, double *w, double *dw, schedule_t *sch)
{
    *sch = schedule_at(T0);
    const double f = tc->value(tc, tc->y, T0);
    tvo_real_t d[3];
    ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(barrier.cfg.relaxation_degree, test_r(sch->s) - test_r(f),
                                                  test_r(sch->delta), 2, d));
    *sigma = sch->s - f;
    *w = -test_d(d[1]) / sch->c;
    *dw = -test_d(d[2]) / sch->c;
}

/* Roundoff amplification of an order-0 gradient: sigma = s - f is good to eps (s + f_scale) and the
 * relaxation's u to eps (delta + |sigma|); w moves by |dw/dsigma| per unit sigma. */
static double gradient_cond(const term_case_t *tc)
{
    double sigma, w, dw;
    schedule_t sch;
    weight_at_point(tc, &sigma, &w, &dw, &sch);
    return 1.0 + fabs(dw) * (sch.s + tc->f_scale + sch.delta + fabs(sigma)) / w;
}

/* Every stencil point (up to +-6 h of the widest stencil) is on the branch of the point itself. */
static void assert_one_branch(const term_case_t *tc, int mode, unsigned col, double length, unsigned k)
{
    const double span = 6.0 * length * fd_step_rel(k);
    const int log_branch = branch_at(tc, mode, col, 0.0) >= 0.0;
    for (int j = -12; j <= 12; ++j) {
        const double x = branch_at(tc, mode, col, span * j / 12.0);
        if ((x >= 0.0) != log_branch) {
            static char msg[200];
            (void)snprintf(msg, sizeof(msg), "%s: stencil crosses the branch switch (mode %d, col %u)", tc->name, mode,
                           col);
            TEST_FAIL_MESSAGE(msg);
        }
    }
}

/* (a) Hessian column col: order-1 jet along e_col, rate 0, vs differences of the order-0 gradient. */
static void check_hessian_columns(term_case_t *tc, double length)
{
    const double cond = gradient_cond(tc);
    for (unsigned ci = 0; ci < tc->active_count; ++ci) {
        const unsigned col = tc->active[ci];
        assert_one_branch(tc, MODE_DIRECTION, col, length, 1);
        tvo_jet_t z[FD_MAX_DIM], grad[FD_MAX_DIM];
        for (unsigned i = 0; i < tc->dim; ++i) {
            tvo_jet_constant(test_r(tc->y[i]), &z[i]);
            tvo_jet_constant(TVO_R(0.0), &grad[i]);
        }
        z[col].c[1] = TVO_R(1.0);
        const tvo_time_jet_t t = time_jet(T0, 0.0);
        ASSERT_STATUS(TVO_OK, tc->gradient(tc->term, z, tc->dim, &t, 1, grad));
        double column[FD_MAX_DIM];
        for (unsigned i = 0; i < tc->dim; ++i) {
            column[i] = test_d(grad[i].c[1]);
        }
        tc->mode = MODE_DIRECTION;
        tc->col = col;
        static char what[160];
        (void)snprintf(what, sizeof(what), "%s: Hessian column %u", tc->name, col);
        FD_CHECK(gradient_along, tc, tc->dim, 1, length, cond, column, what);
    }
}

/* (b) Trajectory jet of the given order (rate 1): coefficient j times j! vs the j-th time difference. */
static void check_trajectory_jet(term_case_t *tc, uint8_t order, double length)
{
    const double cond = gradient_cond(tc);
    assert_one_branch(tc, MODE_TRAJECTORY, 0, length, order);
    tvo_jet_t z[FD_MAX_DIM], grad[FD_MAX_DIM];
    for (unsigned i = 0; i < tc->dim; ++i) {
        tvo_jet_constant(TVO_R(0.0), &z[i]);
        z[i].c[0] = test_r(tc->y[i]);
        z[i].c[1] = test_r(tc->v[i]);
        z[i].c[2] = test_r(0.5 * tc->a[i]);
        tvo_jet_constant(TVO_R(0.0), &grad[i]);
    }
    const tvo_time_jet_t t = time_jet(T0, 1.0);
    ASSERT_STATUS(TVO_OK, tc->gradient(tc->term, z, tc->dim, &t, order, grad));
    tc->mode = MODE_TRAJECTORY;
    const double fact[4] = {1.0, 1.0, 2.0, 6.0};
    for (unsigned k = 1; k <= order; ++k) {
        double expected[FD_MAX_DIM];
        for (unsigned i = 0; i < tc->dim; ++i) {
            expected[i] = test_d(grad[i].c[k]) * fact[k];
        }
        static char what[160];
        (void)snprintf(what, sizeof(what), "%s: order-%u trajectory jet", tc->name, (unsigned)order);
        FD_CHECK(gradient_along, tc, tc->dim, k, length, cond, expected, what);
    }
}

/* (c) The order-0 gradient is the derivative of the potential (1/c) B_delta(s - f). */
static void check_gradient_is_potential_slope(term_case_t *tc, double length)
{
    double g[FD_MAX_DIM];
    TEST_ASSERT_EQUAL_INT(0, term_gradient(tc, tc->y, T0, g));
    double sigma, w, dw;
    schedule_t sch;
    weight_at_point(tc, &sigma, &w, &dw, &sch);
    /* Each potential value: B (a log or a short sum, a few ulps of |B| + 1) over c, plus the rounding
     * of sigma (eps (s + f_scale + delta + |sigma|)) times its slope w. */
    double bd[1];
    const tvo_real_t sigma_r = test_r(sigma);
    tvo_real_t b0[1];
    ASSERT_STATUS(TVO_OK, tvo_barrier_derivatives(barrier.cfg.relaxation_degree, sigma_r, test_r(sch.delta), 0, b0));
    bd[0] = test_d(b0[0]);
    const double noise =
        FD_ULPS * TEST_EPS * ((fabs(bd[0]) + 1.0) / sch.c + w * (sch.s + tc->f_scale + sch.delta + fabs(sigma)));
    for (unsigned ci = 0; ci < tc->active_count; ++ci) {
        const unsigned col = tc->active[ci];
        assert_one_branch(tc, MODE_DIRECTION, col, length, 1);
        tc->col = col;
        static char what[160];
        (void)snprintf(what, sizeof(what), "%s: gradient entry %u vs potential", tc->name, col);
        FD_CHECK_NOISE(potential_along, tc, 1, 1, length, noise, &g[col], what);
    }
    /* Entries the term does not touch stay exactly zero. */
    for (unsigned i = 0; i < tc->dim; ++i) {
        int touched = 0;
        for (unsigned ci = 0; ci < tc->active_count; ++ci) {
            touched |= tc->active[ci] == i;
        }
        if (!touched) {
            ASSERT_NEAR(0.0, g[i], 0.0);
        }
    }
}

/* The paths carry |y''| ~ 1 so that the second and third time derivatives are large (informative). */
static void check_all(term_case_t *tc, double length)
{
    check_hessian_columns(tc, length);
    check_trajectory_jet(tc, 2, length);
    check_trajectory_jet(tc, 3, length);
    check_gradient_is_potential_slope(tc, length);
}

/* ------------------------------------------------------------------------------------------------
 * Distance bounds
 * --------------------------------------------------------------------------------------------- */

static double distance_value(const term_case_t *tc, const double *y, double t_s)
{
    tvo_real_t yr[FD_MAX_DIM], f;
    for (unsigned i = 0; i < tc->dim; ++i) {
        yr[i] = test_r(y[i]);
    }
    ASSERT_STATUS(TVO_OK, tvo_distance_constraint_max(tc->term, yr, tc->dim, test_r(t_s), &f));
    return test_d(f);
}

static void distance_case(term_case_t *tc, const tvo_distance_term_t *term, const double y[4], const char *name)
{
    static const double v[4] = {0.5, -0.25, -0.25, 0.5};
    static const double a[4] = {-1.0, 1.0, 0.75, -0.5};
    memset(tc, 0, sizeof(*tc));
    tc->gradient = tvo_distance_gradient_jet;
    tc->term = term;
    tc->value = distance_value;
    tc->dim = 4;
    tc->active_count = 4;
    for (uint8_t i = 0; i < 4; ++i) {
        tc->active[i] = i;
        tc->y[i] = y[i];
        tc->v[i] = v[i];
        tc->a[i] = a[i];
    }
    const double dx = y[0] - y[2], dy = y[1] - y[3];
    const double d = test_d(term->bound_m) + test_d(term->bound_rate_mps) * T0;
    tc->f_scale = dx * dx + dy * dy + d * d;
    tc->name = name;
}

static void test_distance_max_derivatives_match_differences_on_both_branches(void)
{
    make_barrier(0.75); /* s0 = 1, s(T0) = 0.607 */
    tvo_distance_term_t term;
    /* d(t) = 1.5 + 0.25 t: d(T0) = 1.625; sigma = s - |D|^2 + d^2 = 3.247 - |D|^2. */
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&term, &barrier, TVO_DISTANCE_MAX, 0, 1, TVO_R(1.5), TVO_R(0.25)));
    term_case_t tc;
    const double feasible[4] = {0.25, -0.125, -0.25, 0.25}; /* |D|^2 = 0.391: sigma = 2.86 > delta */
    const double boundary[4] = {1.0, 0.5, -0.5, -0.5};      /* |D|^2 = 3.25: sigma = 0.00 (relaxed) */
    const double infeasible[4] = {1.25, 0.5, -0.75, -0.375}; /* |D|^2 = 4.77: sigma = -1.52 */
    /* Length scales: the distance over which w changes by O(w) (sigma / |grad sigma| on the logarithm,
     * the relaxation polynomial's scale (delta0/c)/|grad sigma| ~ 0.2 below it). */
    distance_case(&tc, &term, feasible, "max distance, feasible");
    check_all(&tc, 0.25);
    distance_case(&tc, &term, boundary, "max distance, on the boundary (relaxed)");
    check_all(&tc, 0.125);
    distance_case(&tc, &term, infeasible, "max distance, infeasible");
    check_all(&tc, 0.125);
}

static void test_distance_min_derivatives_match_differences_on_both_branches(void)
{
    make_barrier(0.75);
    tvo_distance_term_t term;
    /* d(t) = 1 + 0.25 t: d(T0) = 1.125; sigma = s - d^2 + |D|^2 = |D|^2 - 0.659. */
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&term, &barrier, TVO_DISTANCE_MIN, 0, 1, TVO_R(1.0), TVO_R(0.25)));
    term_case_t tc;
    const double feasible[4] = {1.0, 0.5, -0.75, -0.25};    /* |D|^2 = 3.63: sigma = 2.97 */
    const double relaxed[4] = {0.5, 0.25, -0.25, -0.125};   /* |D|^2 = 0.703: sigma = 0.044 */
    const double infeasible[4] = {0.25, 0.0, 0.0, -0.125};  /* |D|^2 = 0.078: sigma = -0.58 */
    distance_case(&tc, &term, feasible, "min distance, feasible");
    check_all(&tc, 0.25);
    distance_case(&tc, &term, relaxed, "min distance, relaxed");
    check_all(&tc, 0.25);
    distance_case(&tc, &term, infeasible, "min distance, infeasible");
    check_all(&tc, 0.125);
}

static void test_distance_constraint_value_and_errors(void)
{
    make_barrier(-1.0);
    tvo_distance_term_t mn, mx;
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&mn, &barrier, TVO_DISTANCE_MIN, 1, 0, TVO_R(1.0), TVO_R(0.5)));
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&mx, &barrier, TVO_DISTANCE_MAX, 1, 0, TVO_R(3.0), TVO_R(-0.5)));
    const tvo_real_t y[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(1.5), TVO_R(2.0)}; /* |D| = 2.5 */
    tvo_real_t f;
    ASSERT_STATUS(TVO_OK, tvo_distance_constraint_max(&mn, y, 4, TVO_R(2.0), &f));
    ASSERT_NEAR(4.0 - 6.25, f, TEST_TOL(8, 6.25)); /* d_min(2) = 2 */
    ASSERT_STATUS(TVO_OK, tvo_distance_constraint_max(&mx, y, 4, TVO_R(2.0), &f));
    ASSERT_NEAR(6.25 - 4.0, f, TEST_TOL(8, 6.25)); /* d_max(2) = 2 */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_distance_constraint_max(&mn, y, 2, TVO_R(0.0), &f));

    tvo_distance_term_t t;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_distance_term_init(&t, &barrier, TVO_DISTANCE_MIN, 1, 1, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_distance_term_init(&t, &barrier, TVO_DISTANCE_MIN, 0, 1, TVO_R(0.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_DIMENSION,
                  tvo_distance_term_init(&t, &barrier, TVO_DISTANCE_MIN, 0, TVO_MAX_ROBOTS, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_distance_term_init(&t, &barrier, TVO_DISTANCE_MAX, 0, 1, TEST_NAN, TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_distance_term_init(&t, &barrier, TVO_DISTANCE_MAX, 0, 1, TVO_R(1.0), TEST_INF));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_distance_term_init(&t, NULL, TVO_DISTANCE_MAX, 0, 1, TVO_R(1.0), TVO_R(0.0)));

    /* A bound schedule that has run through zero is refused at evaluation; so is a short z. */
    tvo_jet_t z[4], g[4];
    for (int i = 0; i < 4; ++i) {
        tvo_jet_constant(y[i], &z[i]);
        tvo_jet_constant(TVO_R(0.0), &g[i]);
    }
    const tvo_time_jet_t late = time_jet(7.0, 1.0); /* d_max(7) = 3 - 3.5 < 0 */
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_distance_gradient_jet(&mx, z, 4, &late, 1, g));
    const tvo_time_jet_t now = time_jet(0.0, 1.0);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_distance_gradient_jet(&mx, z, 2, &now, 1, g));
}

/* ------------------------------------------------------------------------------------------------
 * Half-spaces
 * --------------------------------------------------------------------------------------------- */

static double halfspace_value(const term_case_t *tc, const double *y, double t_s)
{
    tvo_real_t yr[FD_MAX_DIM], f;
    for (unsigned i = 0; i < tc->dim; ++i) {
        yr[i] = test_r(y[i]);
    }
    ASSERT_STATUS(TVO_OK, tvo_halfspace_constraint_max(tc->term, yr, tc->dim, test_r(t_s), &f));
    return test_d(f);
}

static void halfspace_case(term_case_t *tc, const tvo_halfspace_term_t *term, const double yr[2], const char *name)
{
    memset(tc, 0, sizeof(*tc));
    tc->gradient = tvo_halfspace_gradient_jet;
    tc->term = term;
    tc->value = halfspace_value;
    tc->dim = 4;
    tc->active_count = 2;
    tc->active[0] = 2;
    tc->active[1] = 3;
    /* Robot 0 is a bystander (its entries must stay zero); robot 1 is constrained. */
    const double y[4] = {-3.0, 2.0, yr[0], yr[1]};
    const double v[4] = {1.0, 1.0, 0.5, -0.5};
    const double a[4] = {0.0, 0.0, -1.0, 1.0};
    for (int i = 0; i < 4; ++i) {
        tc->y[i] = y[i];
        tc->v[i] = v[i];
        tc->a[i] = a[i];
    }
    const double ax = test_d(term->normal[0]) + test_d(term->normal_rate[0]) * T0;
    const double ay = test_d(term->normal[1]) + test_d(term->normal_rate[1]) * T0;
    tc->f_scale = fabs(ax * yr[0]) + fabs(ay * yr[1]) + fabs(test_d(term->bound_m) + test_d(term->bound_rate_mps) * T0);
    tc->name = name;
}

static void test_halfspace_derivatives_match_differences_on_both_branches(void)
{
    make_barrier(0.75);
    tvo_halfspace_term_t term;
    /* a(t) = (1, 0.5) + (0.25, -0.5) t, b(t) = 1 + 0.5 t: at T0 a = (1.125, 0.25), b = 1.25;
     * sigma = s - a^T y + b = 1.857 - a^T y. */
    const tvo_real_t a0[2] = {TVO_R(1.0), TVO_R(0.5)};
    const tvo_real_t a1[2] = {TVO_R(0.25), TVO_R(-0.5)};
    ASSERT_STATUS(TVO_OK, tvo_halfspace_term_init(&term, &barrier, 1, a0, a1, TVO_R(1.0), TVO_R(0.5)));
    term_case_t tc;
    const double feasible[2] = {-1.0, 0.5};   /* sigma = 2.86 */
    const double relaxed[2] = {1.25, 0.75};   /* sigma = 0.26 */
    const double infeasible[2] = {2.5, 1.0};  /* sigma = -1.21 */
    halfspace_case(&tc, &term, feasible, "half-space, feasible");
    check_all(&tc, 0.5);
    halfspace_case(&tc, &term, relaxed, "half-space, relaxed");
    check_all(&tc, 0.25);
    halfspace_case(&tc, &term, infeasible, "half-space, infeasible");
    check_all(&tc, 0.25);
}

static void test_halfspace_constraint_value_and_errors(void)
{
    make_barrier(-1.0);
    tvo_halfspace_term_t term;
    const tvo_real_t a0[2] = {TVO_R(1.0), TVO_R(0.5)};
    const tvo_real_t a1[2] = {TVO_R(0.25), TVO_R(-0.5)};
    ASSERT_STATUS(TVO_OK, tvo_halfspace_term_init(&term, &barrier, 1, a0, a1, TVO_R(1.0), TVO_R(0.5)));
    const tvo_real_t y[4] = {TVO_R(9.0), TVO_R(9.0), TVO_R(2.0), TVO_R(-1.0)};
    tvo_real_t f;
    ASSERT_STATUS(TVO_OK, tvo_halfspace_constraint_max(&term, y, 4, TVO_R(2.0), &f));
    /* a(2) = (1.5, -0.5), b(2) = 2: f = 3 + 0.5 - 2 = 1.5 */
    ASSERT_NEAR(1.5, f, TEST_TOL(8, 4.0));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_halfspace_constraint_max(&term, y, 2, TVO_R(0.0), &f));

    tvo_halfspace_term_t t;
    const tvo_real_t zero[2] = {TVO_R(0.0), TVO_R(0.0)};
    const tvo_real_t nan2[2] = {TEST_NAN, TVO_R(1.0)};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_halfspace_term_init(&t, &barrier, 0, zero, a1, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_halfspace_term_init(&t, &barrier, 0, nan2, a1, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_halfspace_term_init(&t, &barrier, 0, a0, a1, TEST_INF, TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_halfspace_term_init(&t, &barrier, TVO_MAX_ROBOTS, a0, a1, TVO_R(1.0), TVO_R(0.0)));
    /* A zero normal rate is fine (a constant plane); a0 = 0 with a1 != 0 is not. */
    ASSERT_STATUS(TVO_OK, tvo_halfspace_term_init(&t, &barrier, 0, a0, zero, TVO_R(1.0), TVO_R(0.0)));
}

/* ------------------------------------------------------------------------------------------------
 * Local free space
 * --------------------------------------------------------------------------------------------- */

#define FS_ROBOT_RADIUS 0.25

/* A single-obstacle term per obstacle of the case, so that the constraint value of each is known. */
static tvo_free_space_term_t fs_single[TVO_MAX_OBSTACLES];
static tvo_free_space_term_t fs_all;
static tvo_disk_t fs_obstacle[TVO_MAX_OBSTACLES];
static uint8_t fs_count;

static void free_space_setup(const tvo_disk_t *obstacles, uint8_t count)
{
    fs_count = count;
    for (uint8_t i = 0; i < count; ++i) {
        fs_obstacle[i] = obstacles[i];
        ASSERT_STATUS(TVO_OK,
                      tvo_free_space_term_init(&fs_single[i], &barrier, 0, test_r(FS_ROBOT_RADIUS), &obstacles[i], 1, NULL));
    }
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&fs_all, &barrier, 0, test_r(FS_ROBOT_RADIUS), obstacles, count, NULL));
}

/* f_i(y; y_c) = a_i(y_c)^T (y - y_c) + f_i(y_c; y_c): the half-plane of obstacle i for a robot at y_c
 * (a_i = o_i - y_c, header), evaluated at y; f_i(y_c; y_c) is the term's own constraint value. */
static double free_space_plane_value(uint8_t i, const double *y, const double *y_c)
{
    const tvo_real_t yc[2] = {test_r(y_c[0]), test_r(y_c[1])};
    tvo_real_t f_c;
    ASSERT_STATUS(TVO_OK, tvo_free_space_constraint_max(&fs_single[i], yc, 2, TVO_R(0.0), &f_c));
    const double ax = test_d(fs_obstacle[i].center_m[0]) - test_d(yc[0]);
    const double ay = test_d(fs_obstacle[i].center_m[1]) - test_d(yc[1]);
    return ax * (y[0] - test_d(yc[0])) + ay * (y[1] - test_d(yc[1])) + test_d(f_c);
}

/* grad with y_c frozen: sum_i w(s - f_i(y; y_c)) a_i(y_c), w = -(1/c) B'_delta from the core. */
static int free_space_frozen_gradient(const term_case_t *tc, const double *y, double t_s, const double *y_c, double *g)
{
    (void)tc;
    const schedule_t sch = schedule_at(t_s);
    g[0] = 0.0;
    g[1] = 0.0;
    for (uint8_t i = 0; i < fs_count; ++i) {
        const double f = free_space_plane_value(i, y, y_c);
        tvo_real_t d[2];
        if (tvo_barrier_derivatives(barrier.cfg.relaxation_degree, test_r(sch.s) - test_r(f), test_r(sch.delta), 1, d) !=
            TVO_OK) {
            return 1;
        }
        const double w = -test_d(d[1]) / sch.c;
        g[0] += w * (test_d(fs_obstacle[i].center_m[0]) - test_d(test_r(y_c[0])));
        g[1] += w * (test_d(fs_obstacle[i].center_m[1]) - test_d(test_r(y_c[1])));
    }
    return 0;
}

/* The case's single constraint value with y_c frozen at the case's point (obstacle 0). */
static double free_space_value(const term_case_t *tc, const double *y, double t_s)
{
    (void)t_s;
    return free_space_plane_value(0, y, tc->y);
}

static void free_space_case(term_case_t *tc, const double y_c[2], const char *name)
{
    memset(tc, 0, sizeof(*tc));
    tc->gradient = tvo_free_space_gradient_jet;
    tc->term = &fs_all;
    tc->value = free_space_value;
    tc->frozen_gradient = free_space_frozen_gradient;
    tc->dim = 2;
    tc->active_count = 2;
    tc->active[0] = 0;
    tc->active[1] = 1;
    const double v[2] = {0.5, 0.25};
    const double a[2] = {-1.0, 1.0};
    for (int i = 0; i < 2; ++i) {
        tc->y[i] = y_c[i];
        tc->v[i] = v[i];
        tc->a[i] = a[i];
    }
    const double dx = test_d(fs_obstacle[0].center_m[0]) - y_c[0], dy = test_d(fs_obstacle[0].center_m[1]) - y_c[1];
    tc->f_scale = dx * dx + dy * dy + FS_ROBOT_RADIUS * FS_ROBOT_RADIUS +
                  test_d(fs_obstacle[0].radius_m) * test_d(fs_obstacle[0].radius_m) + FS_ROBOT_RADIUS * sqrt(dx * dx + dy * dy);
    tc->name = name;
}

static void test_free_space_frozen_reference_is_the_terms_gradient(void)
{
    /* The reference assembled from the core's barrier and the term's constraint value equals the
     * term's own order-0 gradient at y = y_c (so the differences below are of the term itself). */
    make_barrier(-1.0); /* s0 = 0 */
    const tvo_disk_t obs[2] = {{{TVO_R(2.0), TVO_R(0.5)}, TVO_R(0.5)}, {{TVO_R(-1.5), TVO_R(1.0)}, TVO_R(0.75)}};
    free_space_setup(obs, 2);
    const double points[3][2] = {{0.0, -1.0}, {1.0, -0.25}, {-0.5, 0.5}};
    for (int p = 0; p < 3; ++p) {
        term_case_t tc;
        free_space_case(&tc, points[p], "free space");
        double g_ref[2], g[2];
        TEST_ASSERT_EQUAL_INT(0, free_space_frozen_gradient(&tc, points[p], T0, points[p], g_ref));
        TEST_ASSERT_EQUAL_INT(0, term_gradient(&tc, points[p], T0, g));
        const double scale = fabs(g_ref[0]) + fabs(g_ref[1]);
        for (int i = 0; i < 2; ++i) {
            /* Two routes to the same w a: tens of ulps of the weight's condition. */
            ASSERT_NEAR(g_ref[i], g[i], FD_ULPS * TEST_EPS * gradient_cond(&tc) * scale);
        }
    }
}

static void test_free_space_derivatives_match_frozen_differences_on_both_branches(void)
{
    make_barrier(-1.0); /* s0 = 0: sigma = -f */
    const tvo_disk_t one[1] = {{{TVO_R(2.0), TVO_R(0.5)}, TVO_R(0.5)}};
    free_space_setup(one, 1);
    term_case_t tc;
    /* f(y_c; y_c) = -((d - r)^2 - r_o^2) / 2 with d = |o - y_c|. */
    const double far[2] = {-0.5, -1.5};         /* d = 3.2: sigma = 4.23 (logarithm) */
    const double near[2] = {1.0, -0.25};        /* d = 1.25: sigma = 0.375 < delta (relaxed, feasible) */
    const double colliding[2] = {1.625, 0.1875}; /* d = 0.49 < r + r_o: sigma = -0.097 (infeasible) */
    /* Frozen planes: f is linear in y with slope |a| = d, so w = 1/(c sigma) changes by O(w) over sigma/d. */
    free_space_case(&tc, far, "free space, far");
    check_all(&tc, 1.0);
    free_space_case(&tc, near, "free space, near (relaxed)");
    check_all(&tc, 0.25);
    free_space_case(&tc, colliding, "free space, colliding");
    check_all(&tc, 0.5);

    /* Two obstacles: the term sums both planes (both on the logarithm here). */
    const tvo_disk_t two[2] = {{{TVO_R(2.0), TVO_R(0.5)}, TVO_R(0.5)}, {{TVO_R(-1.5), TVO_R(1.0)}, TVO_R(0.75)}};
    free_space_setup(two, 2);
    free_space_case(&tc, far, "free space, two obstacles");
    tc.active_count = 2;
    /* (c) uses obstacle 0's value only, so skip it here; (a) and (b) compare the summed gradient. */
    check_hessian_columns(&tc, 0.5);
    check_trajectory_jet(&tc, 2, 0.5);
    check_trajectory_jet(&tc, 3, 0.5);
}

static void test_free_space_time_jet_omits_the_motion_of_the_planes(void)
{
    /*
     * The header: y_c is frozen at the jet's constant coefficient, so the first time coefficient is
     * d/dt grad(y(t); y_c) with y_c fixed, and omits (d grad / d y_c) y'. Shown on both branches:
     *   - it matches the time difference of the frozen-y_c gradient;
     *   - the time difference of the term's order-0 gradient (planes re-derived at y(t)) differs from it
     *     by the omitted term, computed by differences in y_c;
     *   - and that difference is far above the tolerances (the omission is real, not rounding).
     */
    make_barrier(-1.0);
    const tvo_disk_t one[1] = {{{TVO_R(2.0), TVO_R(0.5)}, TVO_R(0.5)}};
    free_space_setup(one, 1);
    const double points[2][2] = {{0.0, -1.0}, {1.0, -0.25}};
    const double lengths[2] = {0.5, 0.125};
    for (int p = 0; p < 2; ++p) {
        term_case_t tc;
        free_space_case(&tc, points[p], p == 0 ? "far" : "near (relaxed)");
        const double length = lengths[p];
        assert_one_branch(&tc, MODE_TRAJECTORY, 0, length, 1);
        /* The jet's first coefficient. */
        tvo_jet_t z[2], grad[2];
        for (int i = 0; i < 2; ++i) {
            tvo_jet_variable(test_r(tc.y[i]), test_r(tc.v[i]), &z[i]);
            tvo_jet_constant(TVO_R(0.0), &grad[i]);
        }
        const tvo_time_jet_t t = time_jet(T0, 1.0);
        ASSERT_STATUS(TVO_OK, tvo_free_space_gradient_jet(&fs_all, z, 2, &t, 1, grad));
        const double jet1[2] = {test_d(grad[0].c[1]), test_d(grad[1].c[1])};
        const double cond = gradient_cond(&tc);

        /* 1. y_c held fixed: matches. */
        tc.mode = MODE_TRAJECTORY;
        FD_CHECK(gradient_along, &tc, 2, 1, length, cond, jet1, "jet vs d/dt with y_c fixed");

        /* 2. The omitted term (d grad / d y_c) y' by central differences in y_c (y, t fixed). */
        const double h = length * fd_step_rel(1);
        double omitted[2] = {0.0, 0.0};
        static const double w1[5] = {1.0, -8.0, 0.0, 8.0, -1.0};
        for (int j = -2; j <= 2; ++j) {
            const double yc[2] = {tc.y[0] + tc.v[0] * j * h, tc.y[1] + tc.v[1] * j * h};
            double g[2];
            TEST_ASSERT_EQUAL_INT(0, free_space_frozen_gradient(&tc, tc.y, T0, yc, g));
            omitted[0] += w1[j + 2] * g[0] / (12.0 * h);
            omitted[1] += w1[j + 2] * g[1] / (12.0 * h);
        }
        /* 3. The total derivative (planes moving with the robot) = jet + omitted term. */
        tc.frozen_gradient = NULL;
        const double total[2] = {jet1[0] + omitted[0], jet1[1] + omitted[1]};
        /* The omitted term carries its own difference error: 1.5 FD_ULPS eps cond |g| / h. */
        double g0[2];
        TEST_ASSERT_EQUAL_INT(0, term_gradient(&tc, tc.y, T0, g0));
        const double omitted_tol = 1.5 * FD_ULPS * TEST_EPS * cond * (fabs(g0[0]) + fabs(g0[1])) / h;
        fd_check_line(gradient_along, &tc, 2, 1, length, cond, omitted_tol * h, total,
                      "d/dt with the planes moving = jet + (d grad/d y_c) y'", __LINE__);
        const double size = fabs(omitted[0]) + fabs(omitted[1]);
        const double jet_size = fabs(jet1[0]) + fabs(jet1[1]);
        ASSERT_LE(0.05 * jet_size, size, "the omitted term is a sizeable part of the rate, not rounding");
        ASSERT_LE(100.0 * omitted_tol, size, "the omitted term is far above its own error");
    }
}

static void test_free_space_constraint_at_robot_is_closed_form_and_negative_when_clear(void)
{
    make_barrier(-1.0);
    const tvo_disk_t obs[1] = {{{TVO_R(1.0), TVO_R(-2.0)}, TVO_R(0.5)}};
    free_space_setup(obs, 1);
    /* Robot radius 0.25 < r_o: sweep the centre distance d along a diagonal ray from the obstacle. */
    for (int k = 1; k <= 40; ++k) {
        const double d = 0.05 * k; /* 0.05 .. 2.0; contact at r + r_o = 0.75 */
        const tvo_real_t y[2] = {test_r(1.0 + d * 0.6), test_r(-2.0 + d * 0.8)};
        const double dd = hypot(test_d(y[0]) - 1.0, test_d(y[1]) + 2.0);
        tvo_real_t f;
        ASSERT_STATUS(TVO_OK, tvo_free_space_constraint_max(&fs_all, y, 2, TVO_R(0.0), &f));
        const double ref = -((dd - FS_ROBOT_RADIUS) * (dd - FS_ROBOT_RADIUS) - 0.25) / 2.0;
        /* f is a difference of terms of size d^2: a few dozen ulps of that. */
        ASSERT_NEAR(ref, f, TEST_TOL(32, dd * dd + 1.0));
        const double clearance = test_d(tvo_disk_clearance(&obs[0], test_r(FS_ROBOT_RADIUS), y));
        ASSERT_NEAR(dd - 0.75, clearance, TEST_TOL(8, dd));
        if (fabs(clearance) > 1e-3) {
            TEST_ASSERT_TRUE_MESSAGE((f < TVO_R(0.0)) == (clearance > 0.0), "f(y_c; y_c) < 0 iff the robot clears");
        }
    }
    /* With several obstacles the value is the worst plane. */
    const tvo_disk_t two[2] = {{{TVO_R(2.0), TVO_R(0.0)}, TVO_R(0.5)}, {{TVO_R(-2.0), TVO_R(0.0)}, TVO_R(0.5)}};
    free_space_setup(two, 2);
    const tvo_real_t y[2] = {TVO_R(1.0), TVO_R(0.0)}; /* d = 1 and 3 */
    tvo_real_t f;
    ASSERT_STATUS(TVO_OK, tvo_free_space_constraint_max(&fs_all, y, 2, TVO_R(0.0), &f));
    ASSERT_NEAR(-((0.75 * 0.75) - 0.25) / 2.0, f, TEST_TOL(16, 4.0));
}

static void test_free_space_constraint_is_nonnegative_when_the_robot_covers_a_small_obstacle(void)
{
    /* The header: f(y_c; y_c) "is negative exactly when the robot clears obstacle i". A robot larger than
     * the obstacle whose disk contains it (d < r - r_o) is in collision, yet (d - r)^2 > r_o^2 there. */
    make_barrier(-1.0);
    const tvo_disk_t post[1] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(0.05)}};
    tvo_free_space_term_t big;
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&big, &barrier, 0, TVO_R(0.3), post, 1, NULL));
    const tvo_real_t y[2] = {TVO_R(0.1), TVO_R(0.0)}; /* the 5 cm post is 10 cm from the 30 cm robot's centre */
    const double clearance = test_d(tvo_disk_clearance(&post[0], TVO_R(0.3), y));
    ASSERT_LE(clearance, -0.2, "the robot covers the post");
    tvo_real_t f;
    ASSERT_STATUS(TVO_OK, tvo_free_space_constraint_max(&big, y, 2, TVO_R(0.0), &f));
    ASSERT_LE(0.0, f, "a colliding robot must not read as strictly feasible (s0 rule would pick s0 = 0)");
}

static void test_free_space_init_rejects_bad_obstacles(void)
{
    make_barrier(-1.0);
    tvo_free_space_term_t t;
    const tvo_disk_t ok[2] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(1.0)}, {{TVO_R(2.5), TVO_R(0.0)}, TVO_R(1.0)}};
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&t, &barrier, 1, TVO_R(0.2), ok, 2, NULL));
    TEST_ASSERT_EQUAL_UINT8(2, t.offset);
    const tvo_disk_t overlapping[2] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(1.0)}, {{TVO_R(1.5), TVO_R(0.0)}, TVO_R(1.0)}};
    int16_t bad_obstacle = 99;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), overlapping, 2, &bad_obstacle));
    TEST_ASSERT_EQUAL_INT16(1, bad_obstacle); /* the later of the pair */
    const tvo_disk_t touching[2] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(1.0)}, {{TVO_R(2.0), TVO_R(0.0)}, TVO_R(1.0)}};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), touching, 2, NULL));
    const tvo_disk_t nested[2] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(2.0)}, {{TVO_R(0.5), TVO_R(0.0)}, TVO_R(0.5)}};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), nested, 2, NULL));
    const tvo_disk_t zero_radius[1] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(0.0)}};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), zero_radius, 1, NULL));
    const tvo_disk_t negative_radius[1] = {{{TVO_R(0.0), TVO_R(0.0)}, TVO_R(-1.0)}};
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), negative_radius, 1, NULL));
    const tvo_disk_t nan_centre[1] = {{{TEST_NAN, TVO_R(0.0)}, TVO_R(1.0)}};
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), nan_centre, 1, NULL));
    const tvo_disk_t nan_radius[1] = {{{TVO_R(0.0), TVO_R(0.0)}, TEST_NAN}};
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), nan_radius, 1, NULL));
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_free_space_term_init(&t, &barrier, 0, TEST_NAN, ok, 2, &bad_obstacle));
    TEST_ASSERT_EQUAL_INT16(-1, bad_obstacle); /* the robot's radius: no disk to blame */
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(-0.1), ok, 2, NULL));
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.0), ok, 2, NULL)); /* a point robot */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), ok, 0, NULL));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), ok, TVO_MAX_OBSTACLES + 1, NULL));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_free_space_term_init(&t, &barrier, TVO_MAX_ROBOTS, TVO_R(0.2), ok, 2, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), NULL, 1, NULL));
    /* The robot's centre on an obstacle's centre has no separating plane: an error, not a NaN. */
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&t, &barrier, 0, TVO_R(0.2), ok, 2, NULL));
    tvo_jet_t z[2], g[2];
    tvo_jet_constant(TVO_R(0.0), &z[0]);
    tvo_jet_constant(TVO_R(0.0), &z[1]);
    tvo_jet_constant(TVO_R(0.0), &g[0]);
    tvo_jet_constant(TVO_R(0.0), &g[1]);
    const tvo_time_jet_t now = time_jet(0.0, 1.0);
    TEST_ASSERT_TRUE(tvo_free_space_gradient_jet(&t, z, 2, &now, 1, g) != TVO_OK);
}

/* ------------------------------------------------------------------------------------------------
 * Every kind's entries validate alike (written once in constraints.c): the same codes for the same
 * misuse, and nothing written by a refused call.
 * --------------------------------------------------------------------------------------------- */

/* z: constant jets at y; g: zero. */
static void constant_jets(const tvo_real_t y[4], tvo_jet_t z[4], tvo_jet_t g[4])
{
    for (int i = 0; i < 4; ++i) {
        tvo_jet_constant(y[i], &z[i]);
        tvo_jet_constant(TVO_R(0.0), &g[i]);
    }
}

typedef struct {
    const char *name;
    tvo_gradient_jet_fn gradient_jet;
    tvo_gradient_hessian_fn gradient_hessian;
    tvo_constraint_max_fn constraint_max;
    const void *term;
} term_entries_t;

/* Robot 1's terms: their outputs are z[2], z[3], so a dimension of 2 is short by one robot. */
static void assert_entries_validate(const term_entries_t *kind)
{
    static tvo_hessian_t hessian; /* never reached: every call below is refused first */
    const tvo_time_jet_t now = time_jet(0.0, 1.0);
    const tvo_real_t y[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(1.5), TVO_R(2.0)};
    tvo_jet_t z[4], g[4];
    constant_jets(y, z, g);
    TEST_MESSAGE(kind->name);
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_jet(NULL, z, 4, &now, 1, g));
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_jet(kind->term, NULL, 4, &now, 1, g));
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_jet(kind->term, z, 4, NULL, 1, g));
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_jet(kind->term, z, 4, &now, 1, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_hessian(kind->term, z, 4, &now, 1, g, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, kind->gradient_hessian(NULL, z, 4, &now, 1, g, &hessian));
    ASSERT_STATUS(TVO_ERR_DIMENSION, kind->gradient_jet(kind->term, z, 2, &now, 1, g));
    ASSERT_STATUS(TVO_ERR_DIMENSION, kind->gradient_hessian(kind->term, z, 2, &now, 1, g, &hessian));
    for (int i = 0; i < 4; ++i) {
        for (int k = 0; k <= TVO_JET_MAX_ORDER; ++k) {
            TEST_ASSERT_TRUE(g[i].c[k] == TVO_R(0.0));
        }
    }
    const tvo_real_t untouched = TVO_R(-123.0);
    tvo_real_t f = untouched;
    ASSERT_STATUS(TVO_ERR_NULL, kind->constraint_max(NULL, y, 4, TVO_R(0.0), &f));
    ASSERT_STATUS(TVO_ERR_NULL, kind->constraint_max(kind->term, NULL, 4, TVO_R(0.0), &f));
    ASSERT_STATUS(TVO_ERR_NULL, kind->constraint_max(kind->term, y, 4, TVO_R(0.0), NULL));
    ASSERT_STATUS(TVO_ERR_DIMENSION, kind->constraint_max(kind->term, y, 2, TVO_R(0.0), &f));
    TEST_ASSERT_TRUE(f == untouched);
    ASSERT_STATUS(TVO_OK, kind->constraint_max(kind->term, y, 4, TVO_R(0.0), &f));
    TEST_ASSERT_TRUE(f != untouched);
}

static void test_every_kind_refuses_misuse_alike(void)
{
    make_barrier(-1.0);
    static tvo_distance_term_t distance[2]; /* a bound's minimum then its maximum: also a pair */
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&distance[0], &barrier, TVO_DISTANCE_MIN, 1, 0, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&distance[1], &barrier, TVO_DISTANCE_MAX, 1, 0, TVO_R(3.0), TVO_R(0.0)));
    tvo_halfspace_term_t halfspace;
    const tvo_real_t normal[2] = {TVO_R(1.0), TVO_R(0.0)};
    const tvo_real_t normal_rate[2] = {TVO_R(0.0), TVO_R(0.0)};
    ASSERT_STATUS(TVO_OK, tvo_halfspace_term_init(&halfspace, &barrier, 1, normal, normal_rate, TVO_R(5.0), TVO_R(0.0)));
    static tvo_free_space_term_t free_space;
    const tvo_disk_t disks[1] = {{{TVO_R(4.0), TVO_R(4.0)}, TVO_R(1.0)}};
    ASSERT_STATUS(TVO_OK, tvo_free_space_term_init(&free_space, &barrier, 1, TVO_R(0.2), disks, 1, NULL));
    const term_entries_t kinds[] = {
        {"distance", tvo_distance_gradient_jet, tvo_distance_gradient_hessian, tvo_distance_constraint_max, &distance[0]},
#if TVO_BLOCK_SOLVE
        {"distance pair", tvo_distance_pair_gradient_jet, tvo_distance_pair_gradient_hessian,
         tvo_distance_pair_constraint_max, distance},
#endif
        {"halfspace", tvo_halfspace_gradient_jet, tvo_halfspace_gradient_hessian, tvo_halfspace_constraint_max, &halfspace},
        {"free space", tvo_free_space_gradient_jet, tvo_free_space_gradient_hessian, tvo_free_space_constraint_max,
         &free_space},
    };
    for (size_t i = 0; i < sizeof(kinds) / sizeof(kinds[0]); ++i) {
        assert_entries_validate(&kinds[i]);
    }
}

#if TVO_BLOCK_SOLVE
/* A pair's two sides must be one pair of robots (all three entries), and its order within the jets. */
static void test_distance_pair_refuses_two_pairs_and_a_long_order(void)
{
    make_barrier(-1.0);
    static tvo_distance_term_t pair[2];
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&pair[0], &barrier, TVO_DISTANCE_MIN, 1, 0, TVO_R(1.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&pair[1], &barrier, TVO_DISTANCE_MAX, 0, 1, TVO_R(3.0), TVO_R(0.0)));
    static tvo_hessian_t hessian;
    const tvo_time_jet_t now = time_jet(0.0, 1.0);
    const tvo_real_t y[4] = {TVO_R(0.0), TVO_R(0.0), TVO_R(1.5), TVO_R(2.0)};
    tvo_jet_t z[4], g[4];
    constant_jets(y, z, g);
    tvo_real_t f = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_distance_pair_gradient_jet(pair, z, 4, &now, 1, g));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_distance_pair_gradient_hessian(pair, z, 4, &now, 1, g, &hessian));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_distance_pair_constraint_max(pair, y, 4, TVO_R(0.0), &f));
    ASSERT_STATUS(TVO_OK, tvo_distance_term_init(&pair[1], &barrier, TVO_DISTANCE_MAX, 1, 0, TVO_R(3.0), TVO_R(0.0)));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_distance_pair_gradient_jet(pair, z, 4, &now, TVO_JET_MAX_ORDER + 1u, g));
    ASSERT_STATUS(TVO_OK, tvo_distance_pair_gradient_jet(pair, z, 4, &now, 1, g));
    /* The larger side's value: here the maximum's, 6.25 - 9 > 1 - 6.25 (|D|^2 = 6.25). */
    ASSERT_STATUS(TVO_OK, tvo_distance_pair_constraint_max(pair, y, 4, TVO_R(0.0), &f));
    ASSERT_NEAR(6.25 - 9.0, f, TEST_TOL(8, 9.0));
}
#endif

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_distance_max_derivatives_match_differences_on_both_branches);
    RUN_TEST(test_distance_min_derivatives_match_differences_on_both_branches);
    RUN_TEST(test_distance_constraint_value_and_errors);
    RUN_TEST(test_halfspace_derivatives_match_differences_on_both_branches);
    RUN_TEST(test_halfspace_constraint_value_and_errors);
    RUN_TEST(test_free_space_frozen_reference_is_the_terms_gradient);
    RUN_TEST(test_free_space_derivatives_match_frozen_differences_on_both_branches);
    RUN_TEST(test_free_space_time_jet_omits_the_motion_of_the_planes);
    RUN_TEST(test_free_space_constraint_at_robot_is_closed_form_and_negative_when_clear);
    RUN_TEST(test_free_space_constraint_is_nonnegative_when_the_robot_covers_a_small_obstacle);
    RUN_TEST(test_free_space_init_rejects_bad_obstacles);
    RUN_TEST(test_every_kind_refuses_misuse_alike);
#if TVO_BLOCK_SOLVE
    RUN_TEST(test_distance_pair_refuses_two_pairs_and_a_long_order);
#endif
    return UNITY_END();
}
