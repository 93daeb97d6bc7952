/*
 * tvo_saddle_solve: [P C^T; C D] x = b by Cholesky of P and the Schur complement of the duals.
 * Against a hand-computed KKT solution; x aliasing b; dependent equality rows; an indefinite P
 * regularised by the ladder (shift reported, the result solves the shifted system); the Gershgorin
 * fallback when the ladder (up to 1e2 s) does not suffice; non-finite input; a diagonal P solved
 * without a factor.
 */
#include "test_support.h"

#include "tvo/linsolve.h"
#include "internal/jet.h"
#include "internal/linsolve.h"

void setUp(void) {}
void tearDown(void) {}

typedef tvo_real_t mat_t[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];

static void load(mat_t a, double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM], const double *values, int n)
{
    for (int i = 0; i < TVO_MAX_Z_DIM; ++i) {
        for (int j = 0; j < TVO_MAX_Z_DIM; ++j) {
            a[i][j] = TVO_R(0.0);
            copy[i][j] = 0.0;
        }
    }
    for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
            a[i][j] = test_r(values[i * n + j]);
            copy[i][j] = test_d(a[i][j]);
        }
    }
}

/* max_i |((A + shift I_primal) x - b)_i| and the scale sum |A||x| + |b| it is measured against. */
static double residual(double a[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM], int primal, int n, double shift, const tvo_real_t *x,
                       const double *b, double *scale)
{
    double worst = 0.0;
    *scale = 0.0;
    for (int i = 0; i < n; ++i) {
        double r = -b[i], s = fabs(b[i]);
        for (int j = 0; j < n; ++j) {
            const double aij = a[i][j] + ((i == j && i < primal) ? shift : 0.0);
            r += aij * test_d(x[j]);
            s += fabs(aij * test_d(x[j]));
        }
        if (fabs(r) > worst) {
            worst = fabs(r);
        }
        if (s > *scale) {
            *scale = s;
        }
    }
    return worst;
}

static void test_hand_computed_kkt_solution(void)
{
    /* [4 1 1; 1 3 1; 1 1 0] x = (1, 2, 3): x1 + x2 = 3, 3 x1 - 2 x2 = -1 (rows 1 - 2 without nu), so
     * x = (1, 2) and nu = 1 - 4 - 2 = -5. */
    const double A[9] = {4, 1, 1, 1, 3, 1, 1, 1, 0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 3);
    const tvo_real_t b[3] = {TVO_R(1.0), TVO_R(2.0), TVO_R(3.0)};
    tvo_real_t x[3] = {TVO_R(9.0), TVO_R(9.0), TVO_R(9.0)};
    tvo_real_t shift = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 1, b, x, &shift));
    ASSERT_NEAR(0.0, shift, 0.0); /* P is positive definite: no shift */
    /* KKT matrix condition ~ 10, |x| <= 5: a few dozen ulps of 5. */
    ASSERT_NEAR(1.0, x[0], TEST_TOL(64, 5.0));
    ASSERT_NEAR(2.0, x[1], TEST_TOL(64, 5.0));
    ASSERT_NEAR(-5.0, x[2], TEST_TOL(64, 5.0));
}

static void test_diagonal_primal_block_is_solved_directly_or_regularised(void)
{
    /* A diagonal P without equalities (tracking alone) is solved entry by entry, x aliasing b. */
    const double A[9] = {2.0, 0.0, 0.0, 0.0, 0.5, 0.0, 0.0, 0.0, 4.0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 3);
    tvo_real_t x[3] = {TVO_R(1.0), TVO_R(-3.0), TVO_R(2.0)};
    tvo_real_t shift = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 3, 0, x, x, &shift));
    ASSERT_NEAR(0.0, shift, 0.0);
    ASSERT_ULPS(0.5, x[0], 1);
    ASSERT_ULPS(-6.0, x[1], 1);
    ASSERT_ULPS(0.5, x[2], 1);
    /* A zero or negative diagonal entry is not positive definite: the ladder's shift, as for any P. */
    const double B[4] = {2.0, 0.0, 0.0, -1.0};
    load(a, copy, B, 2);
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 0, b, x, &shift));
    TEST_ASSERT_TRUE(shift > TVO_R(1.0)); /* the smallest ladder step above |-1| */
    double scale = 0.0;
    const double b_d[2] = {1.0, 1.0};
    ASSERT_LE(residual(copy, 2, 2, test_d(shift), x, b_d, &scale), TEST_TOL(64, scale), "shifted residual");
    /* Non-finite entries anywhere still name themselves. */
    load(a, copy, A, 3);
    a[1][1] = TEST_INF;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve(a, 3, 0, x, x, &shift));
    load(a, copy, A, 3);
    a[0][2] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve(a, 3, 0, x, x, &shift));
}

static void test_formation_kkt_with_two_equalities_solves_the_system(void)
{
    /* Two robots, P = diag(2, 1, 0.5, 3) + coupling, C = [I -I] (y_a - y_b = d): a 6x6 KKT system. */
    const double A[36] = {
        2.0, 0.25, 0.0, 0.0, 1.0, 0.0,   /* */
        0.25, 1.0, 0.0, 0.125, 0.0, 1.0, /* */
        0.0, 0.0, 0.5, 0.0, -1.0, 0.0,   /* */
        0.0, 0.125, 0.0, 3.0, 0.0, -1.0, /* */
        1.0, 0.0, -1.0, 0.0, 0.0, 0.0,   /* */
        0.0, 1.0, 0.0, -1.0, 0.0, 0.0,
    };
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 6);
    const double bd[6] = {1.0, -2.0, 0.5, 0.25, 1.5, -0.75};
    tvo_real_t b[6];
    for (int i = 0; i < 6; ++i) {
        b[i] = test_r(bd[i]);
    }
    tvo_real_t x[6];
    tvo_real_t shift = TVO_R(-1.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 4, 2, b, x, &shift));
    ASSERT_NEAR(0.0, shift, 0.0);
    double scale = 0.0;
    const double r = residual(copy, 4, 6, 0.0, x, bd, &scale);
    /* Backward-stable elimination: residual ~ n eps |A||x| (n = 6, Schur step included): 64 ulps. */
    ASSERT_LE(r, 64.0 * TEST_EPS * scale, "KKT residual");
    /* The equalities hold: x_a - x_b = d. */
    ASSERT_NEAR(1.5, test_d(x[0]) - test_d(x[2]), 64.0 * TEST_EPS * scale);
    ASSERT_NEAR(-0.75, test_d(x[1]) - test_d(x[3]), 64.0 * TEST_EPS * scale);
}

static void test_solution_may_alias_the_right_hand_side(void)
{
    const double A[9] = {4, 1, 1, 1, 3, 1, 1, 1, 0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 3);
    tvo_real_t bx[3] = {TVO_R(1.0), TVO_R(2.0), TVO_R(3.0)};
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 1, bx, bx, NULL));
    ASSERT_NEAR(1.0, bx[0], TEST_TOL(64, 5.0));
    ASSERT_NEAR(2.0, bx[1], TEST_TOL(64, 5.0));
    ASSERT_NEAR(-5.0, bx[2], TEST_TOL(64, 5.0));
}

static void test_dependent_equalities_are_rejected(void)
{
    /* C rows (1, -1, 0, 0) and (2, -2, 0, 0): the Schur complement C P^-1 C^T is singular. */
    const double A[36] = {
        1, 0, 0, 0, 1, 2,  /* */
        0, 1, 0, 0, -1, -2, /* */
        0, 0, 1, 0, 0, 0,  /* */
        0, 0, 0, 1, 0, 0,  /* */
        1, -1, 0, 0, 0, 0, /* */
        2, -2, 0, 0, 0, 0,
    };
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 6);
    const tvo_real_t b[6] = {TVO_R(1.0), TVO_R(1.0), TVO_R(1.0), TVO_R(1.0), TVO_R(1.0), TVO_R(2.0)};
    tvo_real_t x[6];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_saddle_solve(a, 4, 2, b, x, NULL));
    /* Zero rows (an equality on nothing) too. */
    const double Z[9] = {1, 0, 0, 0, 1, 0, 0, 0, 0};
    load(a, copy, Z, 3);
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_saddle_solve(a, 2, 1, b, x, NULL));
}

static void test_indefinite_primal_block_is_regularised_by_the_ladder(void)
{
    /* P = diag(1, -0.5): scale s = 1, the ladder 1e-6 .. 1e-1 leaves -0.5 + mu < 0, mu = 1 works. */
    const double A[4] = {1, 0, 0, -0.5};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 2);
    const double bd[2] = {1.0, 1.0};
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[2];
    tvo_real_t shift = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 0, b, x, &shift));
    ASSERT_NEAR(1.0, shift, TEST_TOL(16, 1.0)); /* 1e-6 times 10^6 in tvo_real_t: a few ulps */
    double scale = 0.0;
    const double res = residual(copy, 2, 2, test_d(shift), x, bd, &scale);
    ASSERT_LE(res, 16.0 * TEST_EPS * scale, "(P + mu I) x = b");
    ASSERT_NEAR(0.5, x[0], TEST_TOL(16, 2.0));
    ASSERT_NEAR(2.0, x[1], TEST_TOL(16, 2.0));
}

static void test_indefinite_primal_block_with_equality_solves_the_shifted_kkt_system(void)
{
    /* P = [1 2; 2 1] (eigenvalues 3, -1), C = (1, 0). mu = 1 leaves P + I singular; mu = 10 works. */
    const double A[9] = {1, 2, 1, 2, 1, 0, 1, 0, 0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 3);
    const double bd[3] = {1.0, -1.0, 0.5};
    const tvo_real_t b[3] = {TVO_R(1.0), TVO_R(-1.0), TVO_R(0.5)};
    tvo_real_t x[3];
    tvo_real_t shift = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 1, b, x, &shift));
    ASSERT_NEAR(10.0, shift, TEST_TOL(32, 10.0));
    double scale = 0.0;
    const double res = residual(copy, 2, 3, test_d(shift), x, bd, &scale);
    ASSERT_LE(res, 64.0 * TEST_EPS * scale, "shifted KKT residual");
    ASSERT_NEAR(0.5, x[0], TEST_TOL(64, 2.0)); /* the equality row is not shifted: x0 = b_dual */
}

static void test_gershgorin_fallback_when_the_ladder_is_not_enough(void)
{
    /* P = M [0 1 1; 1 0 1; 1 1 0], M = 1000: eigenvalues 2M, -M, -M; s = max(1, max |P_ii|) = 1, so the
     * ladder's largest shift 1e2 s leaves -900. Gershgorin: mu = 2M + 1e-6 s, P + mu I has eigenvalues
     * 4M, M, M. */
    const double M = 1000.0;
    const double A[9] = {0, M, M, M, 0, M, M, M, 0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 3);
    const double bd[3] = {1.0, 2.0, -1.0};
    const tvo_real_t b[3] = {TVO_R(1.0), TVO_R(2.0), TVO_R(-1.0)};
    tvo_real_t x[3];
    tvo_real_t shift = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 3, 0, b, x, &shift));
    ASSERT_LE(100.0, shift, "beyond the ladder");
    /* The Gershgorin shift 2M plus the documented margin 1e-6 s + 128 n eps (s + shift), s = 1, n = 3. */
    const double expected_shift = 2.0 * M + 1e-6 + 128.0 * TEST_EPS * 3.0 * (1.0 + 2.0 * M);
    ASSERT_NEAR(expected_shift, shift, TEST_TOL(8, 2.0 * M));
    double scale = 0.0;
    const double res = residual(copy, 3, 3, test_d(shift), x, bd, &scale);
    ASSERT_LE(res, 32.0 * TEST_EPS * scale, "(P + mu I) x = b");
}

static void test_gershgorin_fallback_when_the_bound_is_tight(void)
{
    /* P = [1 M; M 1], M = 1000: eigenvalues 1 + M and 1 - M = -999 < -1e2 s (s = 1): the ladder fails.
     * The header: the Gershgorin shift "provably" makes P positive definite. Here the bound is tight:
     * mu = (M - 1) + 1e-6 s leaves P + mu I = [M + 1e-6, M; M, M + 1e-6], eigenvalue 2e-6 (exactly PD). */
    const double M = 1000.0;
    const double A[4] = {1, M, M, 1};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    load(a, copy, A, 2);
    const double bd[2] = {1.0, -1.0};
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(-1.0)};
    tvo_real_t x[2];
    tvo_real_t shift = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(a, 2, 0, b, x, &shift));
    ASSERT_LE(100.0, shift, "beyond the ladder");
    double scale = 0.0;
    const double res = residual(copy, 2, 2, test_d(shift), x, bd, &scale);
    ASSERT_LE(res, 1e-3 * scale, "(P + mu I) x = b");
}

static void test_non_finite_input_and_bad_sizes_are_rejected(void)
{
    const double A[9] = {4, 1, 1, 1, 3, 1, 1, 1, 0};
    mat_t a;
    double copy[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];
    tvo_real_t b[3] = {TVO_R(1.0), TVO_R(2.0), TVO_R(3.0)};
    tvo_real_t x[3];
    tvo_real_t shift = TVO_R(-1.0);
    load(a, copy, A, 3);
    a[0][1] = TEST_NAN; /* off the diagonal, upper triangle */
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve(a, 2, 1, b, x, &shift));
    ASSERT_NEAR(0.0, shift, 0.0);
    load(a, copy, A, 3);
    a[2][0] = TEST_INF; /* in C */
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve(a, 2, 1, b, x, NULL));
    load(a, copy, A, 3);
    b[2] = TEST_NAN;
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_saddle_solve(a, 2, 1, b, x, NULL));
    b[2] = TVO_R(3.0);
    load(a, copy, A, 3);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_saddle_solve(a, 0, 1, b, x, NULL));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_saddle_solve(a, TVO_MAX_Z_DIM, 1, b, x, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_saddle_solve(NULL, 2, 1, b, x, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_saddle_solve(a, 2, 1, NULL, x, NULL));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_saddle_solve(a, 2, 1, b, NULL, NULL));
}

/* ---- stiff parts solved apart (tvo_saddle_solve_split) ---- */

/* Two robots' relative coordinates, v_x = (1, 0, -1, 0) and v_y = (0, 1, 0, -1), stiff by `weight`. */
static void pair_parts(tvo_hessian_t *h, double weight_x, double weight_y)
{
    tvo_hessian_clear(h, 4u);
    for (unsigned i = 0; i < 4u; ++i) {
        h->matrix[i][i] = TVO_R(1.0);
    }
    const double weights[2] = {weight_x, weight_y};
    for (unsigned k = 0; k < 2u; ++k) {
        tvo_rank_one_t part;
        memset(&part, 0, sizeof(part));
        part.weight = test_r(weights[k]);
        part.count = 2u;
        part.index[0] = (uint8_t)k;
        part.index[1] = (uint8_t)(2u + k);
        part.value[0] = TVO_R(1.0);
        part.value[1] = TVO_R(-1.0);
        tvo_hessian_add_part(h, &part, NULL, 0u);
    }
}

/* (I + w_x v_x v_x^T + w_y v_y v_y^T) x = b + g_x v_x + g_y v_y, exactly: along v the factor is 1 + 2 w. */
static void pair_expected(const double b[4], double wx, double wy, double gx, double gy, double x[4])
{
    const double w[2] = {wx, wy};
    const double g[2] = {gx, gy};
    for (unsigned k = 0; k < 2u; ++k) {
        const double common = 0.5 * (b[k] + b[2u + k]);
        const double relative = 0.5 * (b[k] - b[2u + k]) + g[k];
        const double along = relative / (1.0 + 2.0 * w[k]);
        x[k] = common + along;
        x[2u + k] = common - along;
    }
}

static void test_stiff_parts_keep_the_soft_directions_in_float32(void)
{
    /* The infeasible-start case: relative directions 1e7 stiffer, their right-hand side 1e9. */
    static tvo_hessian_t h;
    pair_parts(&h, 4.0e7, 3.0e3);
    const double b[4] = {0.75, -1.5, 0.25, 2.0};
    const double gamma_d[2] = {1.3e9, -2.0e5};
    const tvo_real_t bb[4] = {test_r(b[0]), test_r(b[1]), test_r(b[2]), test_r(b[3])};
    const tvo_real_t gamma[2] = {test_r(gamma_d[0]), test_r(gamma_d[1])};
    tvo_real_t x[4];
    tvo_real_t shift = TVO_R(-1.0);
    tvo_hessian_settle(&h, 4u, 0u, NULL, 0u);
    TEST_ASSERT_EQUAL_UINT8(2u, h.rank_one_count); /* both dominate the unit matrix by > 1e3 */
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&h, 4u, 0u, bb, gamma, x, &shift));
    ASSERT_NEAR(0.0, shift, 0.0);
    double expected[4];
    pair_expected(b, 4.0e7, 3.0e3, gamma_d[0], gamma_d[1], expected);
    for (unsigned i = 0; i < 4u; ++i) {
        /* Every component to its own size: the common (soft) ones included, which adding the stiff
         * right-hand side into b would have lost entirely (ulp(1.3e9) = 128 in float32). */
        ASSERT_NEAR(expected[i], x[i], TEST_TOL(64, expected[i]));
    }
}

static void test_parts_that_are_not_stiff_join_the_matrix(void)
{
    static tvo_hessian_t h;
    pair_parts(&h, 10.0, 20.0);
    tvo_jet_t grad[4];
    for (unsigned i = 0; i < 4u; ++i) {
        tvo_jet_constant(TVO_R(0.0), &grad[i]);
    }
    h.rank_one[0].gradient.c[0] = TVO_R(3.0);
    tvo_hessian_settle(&h, 4u, 0u, grad, 2u);
    TEST_ASSERT_EQUAL_UINT8(0u, h.rank_one_count);
    ASSERT_NEAR(11.0, h.matrix[0][0], 0.0);
    ASSERT_NEAR(-10.0, h.matrix[0][2], 0.0);
    ASSERT_NEAR(21.0, h.matrix[3][3], 0.0);
    ASSERT_NEAR(3.0, grad[0].c[0], 0.0); /* the folded part's gradient, 3 v_x */
    ASSERT_NEAR(-3.0, grad[2].c[0], 0.0);
}

static void test_split_falls_back_to_the_sum_when_the_rest_is_indefinite(void)
{
    /* The rest alone is indefinite (-1 on the common x direction): the parts are added in and the
     * sum regularised, exactly as tvo_saddle_solve does with the sum. */
    static tvo_hessian_t h;
    pair_parts(&h, 1.0e5, 1.0e5);
    h.matrix[0][0] = TVO_R(-1.0);
    static tvo_matrix_t sum;
    for (unsigned i = 0; i < 4u; ++i) {
        for (unsigned j = 0; j < 4u; ++j) {
            sum[i][j] = h.matrix[i][j];
        }
    }
    for (unsigned k = 0; k < 2u; ++k) {
        sum[k][k] += TVO_R(1.0e5);
        sum[k + 2u][k + 2u] += TVO_R(1.0e5);
        sum[k][k + 2u] -= TVO_R(1.0e5);
        sum[k + 2u][k] -= TVO_R(1.0e5);
    }
    const tvo_real_t b[4] = {TVO_R(1.0), TVO_R(2.0), TVO_R(3.0), TVO_R(4.0)};
    const tvo_real_t gamma[2] = {TVO_R(0.0), TVO_R(0.0)};
    tvo_real_t x_split[4];
    tvo_real_t x_sum[4];
    tvo_real_t shift_split = TVO_R(0.0);
    tvo_real_t shift_sum = TVO_R(0.0);
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve_split(&h, 4u, 0u, b, gamma, x_split, &shift_split));
    ASSERT_STATUS(TVO_OK, tvo_saddle_solve(sum, 4u, 0u, b, x_sum, &shift_sum));
    TEST_ASSERT_TRUE(shift_split > TVO_R(0.0));
    ASSERT_NEAR(shift_sum, shift_split, 0.0);
    for (unsigned i = 0; i < 4u; ++i) {
        ASSERT_NEAR(x_sum[i], x_split[i], TEST_TOL(16, x_sum[i]));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_hand_computed_kkt_solution);
    RUN_TEST(test_diagonal_primal_block_is_solved_directly_or_regularised);
    RUN_TEST(test_formation_kkt_with_two_equalities_solves_the_system);
    RUN_TEST(test_solution_may_alias_the_right_hand_side);
    RUN_TEST(test_dependent_equalities_are_rejected);
    RUN_TEST(test_indefinite_primal_block_is_regularised_by_the_ladder);
    RUN_TEST(test_indefinite_primal_block_with_equality_solves_the_shifted_kkt_system);
    RUN_TEST(test_gershgorin_fallback_when_the_ladder_is_not_enough);
    RUN_TEST(test_gershgorin_fallback_when_the_bound_is_tight);
    RUN_TEST(test_non_finite_input_and_bad_sizes_are_rejected);
    RUN_TEST(test_stiff_parts_keep_the_soft_directions_in_float32);
    RUN_TEST(test_parts_that_are_not_stiff_join_the_matrix);
    RUN_TEST(test_split_falls_back_to_the_sum_when_the_rest_is_indefinite);
    return UNITY_END();
}
