/*
 * Differential test of the closed forms (tvo_term_t.gradient_hessian) against the jet path.
 *
 * Every term kind with a closed form (tracking on each target kind, distance minimum and maximum,
 * half-space, obstacle free space, formation-offset equality) is evaluated by the law twice on
 * random problems, states, times and barrier branches: once through its closed form and once with
 * the objective's jets_only switch (every gradient and Hessian from jets, the reference). The
 * gradient rows, the Hessian and the law's output must agree to a few units of rounding of their
 * own magnitude, in float32 and double, on the host and on the Cortex-M4F (tests/target).
 * And the law's path for objectives of tracking terms only (no Hessian matrix, no general solve)
 * against its general path on the same objective: the same numbers bit for bit, the same refusals.
 */
#include "test_support.h"

#include "tvo/law.h"
#include "tvo/problem.h"
#include "internal/jet.h"
#include "internal/law.h"
#include "internal/linsolve.h"
#include "internal/objective.h"

void setUp(void) {}
void tearDown(void) {}

#define TRIALS 60u
/* Closed forms and jets round differently: allow this many ulps of each row's largest entry. */
#define AGREEMENT_ULPS 512.0

static tvo_problem_t problem; /* large: static */
static uint32_t rng_state = 0x2545F491u;

static double uniform(double lo, double hi)
{
    rng_state = rng_state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (double)(rng_state >> 8) / 16777216.0;
}

/* Random target of a random kind for a robot near (cx, cy). */
static void random_target(tvo_target_t *target, double cx, double cy)
{
    const double kind = uniform(0.0, 3.0);
    if (kind < 1.0) {
        tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
        memset(coeff, 0, sizeof(coeff));
        coeff[0][0] = test_r(cx);
        coeff[1][0] = test_r(cy);
        for (int j = 1; j <= 3 && j <= TVO_POLY_MAX_DEGREE; ++j) {
            coeff[0][j] = test_r(uniform(-0.5, 0.5));
            coeff[1][j] = test_r(uniform(-0.5, 0.5));
        }
        ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(target, TEST_CONST_POLY(coeff)));
    } else if (kind < 2.0) {
        const tvo_real_t center[2] = {test_r(cx), test_r(cy)};
        ASSERT_STATUS(TVO_OK, tvo_target_init_circle(target, center, test_r(uniform(0.3, 2.0)),
                                                     test_r(uniform(-1.5, 1.5)), test_r(uniform(-3.0, 3.0))));
    } else {
        tvo_target_ellipse_t el;
        el.center_m[0] = test_r(cx);
        el.center_m[1] = test_r(cy);
        el.semi_axis_m[0] = test_r(uniform(0.3, 3.0));
        el.semi_axis_m[1] = test_r(uniform(0.3, 3.0));
        el.omega_radps = test_r(uniform(-1.5, 1.5));
        el.phase_rad = test_r(uniform(-3.0, 3.0));
        el.rotation_rad = test_r(uniform(-3.0, 3.0));
        el.rate_turns_q64 = 0u;
        ASSERT_STATUS(TVO_OK, tvo_target_init_ellipse(target, &el));
    }
}

/* Where robot r of n starts: two robots at (-1.5, 0) and (1.5, 0), more on a circle of radius 1.5. */
static void robot_place(unsigned r, unsigned n, double *x, double *y)
{
    const double angle = n == 2u ? (r == 0u ? TEST_PI : 0.0) : 2.0 * TEST_PI * (double)r / (double)n;
    *x = 1.5 * cos(angle);
    *y = 1.5 * sin(angle);
}

/* n robots, every constraint kind present, an offset equality when offsets is set. Two robots: one
 * distance bound between them; three or more (the block solve's problems, each bound's two sides one
 * term): a ring of them, and one more bound with its maximum only. */
static void random_problem(unsigned n, int offsets)
{
    tvo_problem_desc_t desc;
    ASSERT_STATUS(TVO_OK, tvo_problem_desc_default(&desc));
    desc.robot_count = (uint8_t)n;
    for (unsigned r = 0; r < n; ++r) {
        double x = 0.0;
        double y = 0.0;
        robot_place(r, n, &x, &y);
        random_target(&desc.target[r], x, y);
    }
    for (uint8_t r = 0; r < n; ++r) {
        desc.tracking_weight[r][0] = test_r(uniform(0.5, 3.0));
        desc.tracking_weight[r][1] = test_r(uniform(0.5, 3.0));
    }
    desc.barrier.c0 = test_r(uniform(0.5, 5.0));
    desc.barrier.alpha_c_per_s = test_r(uniform(0.0, 2.0));
    desc.barrier.relaxation_degree = (uint8_t)(3u + (rng_state >> 28) % 4u);
    desc.distance_count = 1u;
    desc.distance[0].robot_a = 0u;
    desc.distance[0].robot_b = 1u;
    desc.distance[0].min_m = test_r(uniform(0.5, 1.5));
    desc.distance[0].min_rate_mps = test_r(uniform(-0.05, 0.05));
    desc.distance[0].max_m = test_r(uniform(3.5, 5.0));
    desc.distance[0].max_rate_mps = test_r(uniform(-0.05, 0.05));
    if (n > 2u) {
        /* A ring: robot r to r + 1, spaced 3 sin(pi / n) apart. */
        const double spacing = 3.0 * sin(TEST_PI / (double)n);
        for (unsigned b = 0; b < n && b < TVO_MAX_DISTANCE_BOUNDS; ++b) {
            desc.distance[b].robot_a = (uint8_t)b;
            desc.distance[b].robot_b = (uint8_t)((b + 1u) % n);
            desc.distance[b].min_m = test_r(spacing * uniform(0.3, 0.7));
            desc.distance[b].min_rate_mps = test_r(uniform(-0.05, 0.05));
            desc.distance[b].max_m = test_r(spacing * uniform(1.4, 2.0));
            desc.distance[b].max_rate_mps = test_r(uniform(-0.05, 0.05));
            desc.distance_count = (uint8_t)(b + 1u);
        }
        if (desc.distance_count < TVO_MAX_DISTANCE_BOUNDS) {
            desc.distance[desc.distance_count].robot_a = 0u;
            desc.distance[desc.distance_count].robot_b = (uint8_t)(n / 2u);
            desc.distance[desc.distance_count].max_m = test_r(uniform(3.5, 5.0));
            desc.distance_count++;
        }
    }
    desc.halfspace_count = 1u;
    desc.halfspace[0].robot = 1u;
    desc.halfspace[0].normal[0] = test_r(uniform(-1.0, 1.0));
    desc.halfspace[0].normal[1] = test_r(uniform(0.5, 1.0));
    desc.halfspace[0].normal_rate[0] = test_r(uniform(-0.1, 0.1));
    desc.halfspace[0].normal_rate[1] = test_r(uniform(-0.1, 0.1));
    desc.halfspace[0].bound_m = test_r(uniform(1.0, 3.0));
    desc.halfspace[0].bound_rate_mps = test_r(uniform(-0.2, 0.2));
    desc.obstacle_count = 2u;
    desc.robot_radius_m = test_r(uniform(0.0, 0.3));
    desc.obstacle[0].center_m[0] = test_r(uniform(-1.0, 1.0));
    desc.obstacle[0].center_m[1] = test_r(uniform(2.0, 3.0));
    desc.obstacle[0].radius_m = test_r(uniform(0.2, 0.6));
    desc.obstacle[1].center_m[0] = test_r(uniform(-1.0, 1.0));
    desc.obstacle[1].center_m[1] = test_r(uniform(-3.0, -2.0));
    desc.obstacle[1].radius_m = test_r(uniform(0.2, 0.6));
    desc.offset_count = offsets ? 1u : 0u;
    if (offsets) {
        desc.offset[0].robot_a = 0u;
        desc.offset[0].robot_b = 1u;
        random_target(&desc.offset[0].offset, -3.0, 0.0);
    }
    tvo_problem_culprit_t part;
    ASSERT_STATUS(TVO_OK, tvo_problem_init(&problem, &desc, 2u, &part));
#if TVO_BLOCK_SOLVE
    TEST_ASSERT_TRUE((problem.objective.plan != NULL) == (n > 2u)); /* the block solve from three robots on */
#endif
}

/* |a - b| within AGREEMENT_ULPS of scale, with the place named. */
static void assert_agree(double reference, double closed_form, double scale, const char *what, unsigned i, unsigned j)
{
    const double tol = AGREEMENT_ULPS * TEST_EPS * (1.0 + scale);
    if (!(fabs(reference - closed_form) <= tol)) {
        static char msg[160];
        (void)snprintf(msg, sizeof(msg), "%s [%u][%u]: jets %.9g, closed form %.9g (tol %.3g)", what, i, j, reference,
                       closed_form, tol);
        TEST_FAIL_MESSAGE(msg);
    }
}

/* The law through closed forms and through jets on the same input: same status, same numbers. */
static void compare_paths(const tvo_output_derivs_t *y, const tvo_time_jet_t *t, unsigned *compared)
{
    const tvo_real_t gains[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2u, problem.objective.dim, gains);
    static tvo_objective_t by_jets;
    by_jets = problem.objective;
    by_jets.jets_only = 1u;
    static tvo_law_eval_t closed_eval;
    static tvo_law_eval_t jet_eval;
    tvo_real_t closed_out[TVO_MAX_Z_DIM];
    tvo_real_t jet_out[TVO_MAX_Z_DIM];
    const tvo_status_t st_closed = tvo_law_evaluate(&law, &problem.objective, y, t, closed_out, &closed_eval);
    const tvo_status_t st_jets = tvo_law_evaluate(&law, &by_jets, y, t, jet_out, &jet_eval);
    ASSERT_STATUS(st_jets, st_closed);
    if (st_jets != TVO_OK) {
        return; /* the same refusal (e.g. an obstacle centre under the robot) */
    }
    const unsigned m = problem.objective.dim;
    for (unsigned row = 0; row <= 2u; ++row) {
        double scale = 0.0;
        for (unsigned i = 0; i < m; ++i) {
            scale = fmax(scale, fabs(test_d(jet_eval.grad[row][i])));
        }
        for (unsigned i = 0; i < m; ++i) {
            assert_agree(test_d(jet_eval.grad[row][i]), test_d(closed_eval.grad[row][i]), scale, "gradient row", row, i);
        }
    }
    double h_scale = 0.0;
    for (unsigned i = 0; i < m; ++i) {
        for (unsigned j = 0; j < m; ++j) {
            h_scale = fmax(h_scale, fabs(test_d(jet_eval.hessian[i][j])));
        }
    }
    for (unsigned i = 0; i < m; ++i) {
        for (unsigned j = 0; j < m; ++j) {
            assert_agree(test_d(jet_eval.hessian[i][j]), test_d(closed_eval.hessian[i][j]), h_scale, "Hessian", i, j);
        }
    }
    /* The law's outputs are compared by what they solve: the closed-form output must satisfy the jet
     * path's own system (H + shift I_primal) y'' = -(r + a0 g + a1 g') to rounding of its terms
     * (backward error). Only where the Hessian's diagonal spans less than TVO_STIFF_RATIO and both
     * solves used the same shift: otherwise the stiff barrier parts were solved apart
     * (tvo_saddle_solve_split), which the plain system's residual cannot judge in this precision
     * (tests/unit/test_saddle.c checks that solve); the Hessians themselves agree above. */
    double diag_min = HUGE_VAL;
    double diag_max = 0.0;
    for (unsigned i = 0; i < problem.objective.primal_dim; ++i) {
        diag_min = fmin(diag_min, fabs(test_d(jet_eval.hessian[i][i])));
        diag_max = fmax(diag_max, fabs(test_d(jet_eval.hessian[i][i])));
    }
    /* Split apart, a stiff system never needs more regularisation than the plain one. */
    ASSERT_LE(test_d(closed_eval.regularization), test_d(jet_eval.regularization) * (1.0 + AGREEMENT_ULPS * TEST_EPS),
              "regularisation");
    const int same_shift = fabs(test_d(jet_eval.regularization) - test_d(closed_eval.regularization)) <=
                           AGREEMENT_ULPS * TEST_EPS * (1.0 + h_scale);
    if (!(diag_max < test_d(TVO_STIFF_RATIO) * diag_min) || !same_shift) {
        return;
    }
    for (unsigned i = 0; i < m; ++i) {
        const double rhs = test_d(jet_eval.grad[2][i]) + 40.0 * test_d(jet_eval.grad[0][i]) +
                           13.0 * test_d(jet_eval.grad[1][i]);
        double residual = rhs;
        double magnitude = fabs(rhs);
        for (unsigned j = 0; j < m; ++j) {
            const double term = test_d(jet_eval.hessian[i][j]) * test_d(closed_out[j]);
            residual += term;
            magnitude += fabs(term);
        }
        if (i < problem.objective.primal_dim) {
            residual += test_d(jet_eval.regularization) * test_d(closed_out[i]);
            magnitude += fabs(test_d(jet_eval.regularization) * test_d(closed_out[i]));
        }
        assert_agree(0.0, residual, magnitude, "residual of the closed-form output in the jet system", i, 0u);
    }
    (*compared)++;
}

/* Random states near the targets, at random times on both sides of the barrier's cap. */
static void run_trials(unsigned n, int offsets)
{
    unsigned compared = 0u;
    for (unsigned trial = 0; trial < TRIALS; ++trial) {
        random_problem(n, offsets);
        tvo_output_derivs_t y;
        memset(&y, 0, sizeof(y));
        y.d[0][0] = test_r(uniform(-2.5, -0.5));
        y.d[0][1] = test_r(uniform(-1.5, 1.5));
        y.d[0][2] = test_r(uniform(0.5, 2.5));
        y.d[0][3] = test_r(uniform(-1.5, 1.5));
        if (n > 2u) {
            for (unsigned r = 0; r < n; ++r) {
                double x = 0.0;
                double yy = 0.0;
                robot_place(r, n, &x, &yy);
                y.d[0][2u * r] = test_r(x + uniform(-0.5, 0.5));
                y.d[0][2u * r + 1u] = test_r(yy + uniform(-0.5, 0.5));
            }
        }
        const unsigned primal = 2u * n;
        for (unsigned i = 0; i < problem.objective.dim; ++i) {
            if (i >= primal) {
                y.d[0][i] = test_r(uniform(-1.0, 1.0)); /* multipliers */
            }
            y.d[1][i] = test_r(uniform(-1.0, 1.0));
        }
        const double t_s = uniform(0.0, 12.0);
        tvo_time_jet_t t;
        ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks((uint64_t)llround(t_s * 1e6), 1000000u, TVO_R(1.0), &t));
        /* The slack from the state itself (a violated start relaxes), or none (both branches). */
        if (trial % 2u == 0u) {
            ASSERT_STATUS(TVO_OK, tvo_problem_choose_slack(&problem, y.d[0], t.t_s));
        }
        compare_paths(&y, &t, &compared);
    }
    /* Refusals and stiff draws are allowed, but the whole comparison must have happened for many. */
    ASSERT_LE(TRIALS / 4u, compared, "trials compared in full");
}

static void test_closed_forms_match_jets_without_equalities(void)
{
    run_trials(2u, 0);
}

static void test_closed_forms_match_jets_with_an_offset_equality(void)
{
    run_trials(2u, 1);
}

/* Three robots and the build's most: the block plan's problems (a bound's two sides one term, its
 * Hessian one 2 x 2 block, the solve by the plan) against the jets' dense path. */
#if TVO_MAX_ROBOTS >= 3
static void test_block_solved_problems_match_jets(void)
{
    run_trials(3u, 0);
    run_trials(TVO_MAX_ROBOTS, 0);
    run_trials(TVO_MAX_ROBOTS, 1);
}
#endif

/* The law's pass uses the closed forms (no term left to jets) unless jets_only asks otherwise. */
static void test_every_built_in_term_has_a_closed_form(void)
{
    random_problem(2u, 1);
    tvo_jet_t z[TVO_MAX_Z_DIM];
    tvo_jet_t grad[TVO_MAX_Z_DIM];
    static tvo_hessian_t h;
    for (unsigned i = 0; i < TVO_MAX_Z_DIM; ++i) {
        tvo_jet_constant(test_r(0.3 * (double)i - 1.0), &z[i]);
    }
    tvo_time_jet_t t;
    ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks(1500000u, 1000000u, TVO_R(1.0), &t));
    uint8_t jet_terms = 99u;
    tvo_hessian_clear(&h, TVO_MAX_Z_DIM);
    ASSERT_STATUS(TVO_OK, tvo_objective_gradient_hessian(&problem.objective, z, &t, 2u, grad, &h, &jet_terms));
    TEST_ASSERT_EQUAL_UINT8(0u, jet_terms);
    problem.objective.jets_only = 1u;
    ASSERT_STATUS(TVO_OK, tvo_objective_gradient_hessian(&problem.objective, z, &t, 2u, grad, &h, &jet_terms));
    TEST_ASSERT_EQUAL_UINT8(problem.objective.term_count, jet_terms);
}

/* A term that adds nothing: appended, it sends the law down its general path with the same sums. */
static tvo_status_t nothing_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                         uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)y;
    (void)dim;
    (void)t;
    (void)order;
    (void)grad;
    return TVO_OK;
}

static tvo_status_t nothing_gradient_hessian(const void *term, const tvo_jet_t *y, uint8_t dim,
                                             const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                             tvo_hessian_t *hessian)
{
    (void)hessian;
    return nothing_gradient_jet(term, y, dim, t, order, grad);
}

/* Sentinel in the workspace matrix's off-diagonal entry: the tracking path leaves it, the general
 * path clears it, so each successful evaluation shows which path it took. */
#define PATH_SENTINEL TVO_R(7.0)

typedef struct {
    tvo_status_t status;
    tvo_real_t out[TVO_MAX_Z_DIM];
    tvo_real_t gradient[TVO_MAX_Z_DIM];
    tvo_real_t gradient_rate[TVO_MAX_Z_DIM];
    tvo_real_t regularization;
    int took_tracking_path;
} law_result_t;

static void evaluate_reporting(const tvo_law_t *law, const tvo_objective_t *objective, const tvo_output_derivs_t *y,
                               const tvo_time_jet_t *t, law_result_t *result)
{
    static tvo_law_workspace_t work;
    memset(result, 0, sizeof(*result));
    memset(&work, 0, sizeof(work));
    work.hessian.matrix[0][1] = PATH_SENTINEL;
    tvo_law_report_t report = {result->gradient, result->gradient_rate, objective->dim, TVO_R(-1.0)};
    result->status = tvo_law_evaluate_report(law, objective, y, t, result->out, &report, &work);
    result->regularization = report.regularization;
    result->took_tracking_path = work.hessian.matrix[0][1] == PATH_SENTINEL;
}

static void assert_same_bits(const law_result_t *a, const law_result_t *b, unsigned m)
{
    ASSERT_STATUS(a->status, b->status);
    TEST_ASSERT_EQUAL_MEMORY(a->out, b->out, m * sizeof(tvo_real_t));
    TEST_ASSERT_EQUAL_MEMORY(a->gradient, b->gradient, m * sizeof(tvo_real_t));
    TEST_ASSERT_EQUAL_MEMORY(a->gradient_rate, b->gradient_rate, m * sizeof(tvo_real_t));
    TEST_ASSERT_EQUAL_MEMORY(&a->regularization, &b->regularization, sizeof(tvo_real_t));
}

/* Random tracking-only objectives (1 .. TVO_MAX_ROBOTS robots, every target kind, k = 1 .. the build's
 * maximum, sometimes a second target on robot 0): the tracking path and the general path (the same
 * objective with a term that adds nothing) give the same bits; a target's refusal and a state that
 * is not finite are refused alike, outputs zeroed. */
static void test_tracking_path_matches_the_general_path_bit_for_bit(void)
{
    static tvo_target_t targets[TVO_MAX_ROBOTS + 1];
    static tvo_tracking_term_t terms[TVO_MAX_ROBOTS + 1];
    static tvo_objective_t tracking_only;
    static tvo_objective_t general;
    static const int nothing = 0;
    const tvo_term_t nothing_term = {nothing_gradient_jet, nothing_gradient_hessian, NULL, &nothing, TVO_TERM_GENERAL};
    unsigned tracking_paths = 0u;
    for (unsigned trial = 0; trial < 4u * TRIALS; ++trial) {
        const uint8_t robots = (uint8_t)(1u + trial % TVO_MAX_ROBOTS);
        const uint8_t m = (uint8_t)(2u * robots);
        const uint8_t k = (uint8_t)(1u + (trial / TVO_MAX_ROBOTS) % TVO_MAX_RELATIVE_DEGREE);
        ASSERT_STATUS(TVO_OK, tvo_objective_init(&tracking_only, m));
        const unsigned term_count = robots + (trial % 3u == 0u ? 1u : 0u);
        for (unsigned r = 0; r < term_count; ++r) {
            const unsigned robot = r < robots ? r : 0u;
            random_target(&targets[r], 2.0 * (double)robot, 0.0);
            if (trial % 17u == 5u && r == 0u) {
                ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&targets[r])); /* no sample: refused */
            }
            const tvo_real_t w[2] = {test_r(uniform(0.1, 5.0)), test_r(uniform(0.1, 5.0))};
            ASSERT_STATUS(TVO_OK, tvo_tracking_init(&terms[r], &targets[r], w, (uint8_t)(2u * robot)));
            const tvo_term_t term = {tvo_tracking_gradient_jet, tvo_tracking_gradient_hessian, NULL, &terms[r], TVO_TERM_TRACKING};
            ASSERT_STATUS(TVO_OK, tvo_objective_add(&tracking_only, &term));
        }
        TEST_ASSERT_EQUAL_UINT8(1u, tracking_only.tracking_only);
        general = tracking_only;
        ASSERT_STATUS(TVO_OK, tvo_objective_add(&general, &nothing_term));
        TEST_ASSERT_EQUAL_UINT8(0u, general.tracking_only);

        const tvo_real_t gains[3] = {TVO_R(8.0), TVO_R(12.0), TVO_R(6.0)}; /* (s + 2)^3's, Hurwitz for each k */
        tvo_law_t law;
        tvo_law_init(&law, k, m, gains);
        tvo_output_derivs_t y;
        memset(&y, 0, sizeof(y));
        for (unsigned j = 0; j < k; ++j) {
            for (unsigned i = 0; i < m; ++i) {
                y.d[j][i] = test_r(uniform(-3.0, 3.0));
            }
        }
        if (trial % 23u == 7u) {
            y.d[k - 1u][m - 1u] = TEST_NAN;
        }
        tvo_time_jet_t t;
        ASSERT_STATUS(TVO_OK, tvo_time_jet_at_ticks((uint64_t)llround(uniform(0.0, 3600.0) * 1e4), 10000u,
                                                    TVO_R(1.0), &t));
        law_result_t fast;
        law_result_t reference;
        evaluate_reporting(&law, &tracking_only, &y, &t, &fast);
        evaluate_reporting(&law, &general, &y, &t, &reference);
        assert_same_bits(&reference, &fast, m);
        if (fast.status == TVO_OK) {
            TEST_ASSERT_FALSE(reference.took_tracking_path);
            TEST_ASSERT_TRUE(fast.took_tracking_path);
            tracking_paths++;
        } else {
            const tvo_real_t zeros[TVO_MAX_Z_DIM] = {TVO_R(0.0)};
            TEST_ASSERT_EQUAL_MEMORY(zeros, fast.out, m * sizeof(tvo_real_t));
        }
    }
    ASSERT_LE(3u * TRIALS, tracking_paths, "evaluations that took the tracking path");
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_closed_forms_match_jets_without_equalities);
    RUN_TEST(test_closed_forms_match_jets_with_an_offset_equality);
#if TVO_MAX_ROBOTS >= 3
    RUN_TEST(test_block_solved_problems_match_jets);
#endif
    RUN_TEST(test_every_built_in_term_has_a_closed_form);
    RUN_TEST(test_tracking_path_matches_the_general_path_bit_for_bit);
    return UNITY_END();
}
