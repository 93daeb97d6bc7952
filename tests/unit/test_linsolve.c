/*
 * Cholesky solve of A x = b for SPD A: against a known solution (b built as A x_true in double),
 * and rejection of matrices without a Cholesky factor.
 */
#include "test_support.h"

#include "tvo/linsolve.h"
#include "internal/linsolve.h"

void setUp(void) {}
void tearDown(void) {}

typedef tvo_real_t mat_t[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];

static void mat_fill(mat_t a, double v)
{
    for (int i = 0; i < TVO_MAX_Z_DIM; ++i) {
        for (int j = 0; j < TVO_MAX_Z_DIM; ++j) {
            a[i][j] = test_r(v);
        }
    }
}

static void test_solves_3x3_known_solution(void)
{
    /* A = [4 1 2; 1 5 3; 2 3 6] (minors 4, 19, 70 > 0), x = (1, -2, 3):
     * b = (4 - 2 + 6, 1 - 10 + 9, 2 - 6 + 18) = (8, 0, 14). */
    mat_t a;
    mat_fill(a, 0.0);
    const double A[3][3] = {{4, 1, 2}, {1, 5, 3}, {2, 3, 6}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a[i][j] = test_r(A[i][j]);
        }
    }
    const tvo_real_t b[3] = {TVO_R(8.0), TVO_R(0.0), TVO_R(14.0)};
    tvo_real_t x[3] = {TVO_R(-9.0), TVO_R(-9.0), TVO_R(-9.0)};
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 3, b, x));
    ASSERT_NEAR(1.0, x[0], TEST_TOL(32, 3.0));
    ASSERT_NEAR(-2.0, x[1], TEST_TOL(32, 3.0));
    ASSERT_NEAR(3.0, x[2], TEST_TOL(32, 3.0));
}

static void test_reads_only_the_lower_triangle(void)
{
    /* Same system with NaN above the diagonal: the strictly upper part must never be read. */
    mat_t a;
    mat_fill(a, (double)NAN);
    const double A[3][3] = {{4, 1, 2}, {1, 5, 3}, {2, 3, 6}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j <= i; ++j) {
            a[i][j] = test_r(A[i][j]);
        }
    }
    const tvo_real_t b[3] = {TVO_R(8.0), TVO_R(0.0), TVO_R(14.0)};
    tvo_real_t x[3];
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 3, b, x));
    ASSERT_NEAR(1.0, x[0], TEST_TOL(32, 3.0));
    ASSERT_NEAR(-2.0, x[1], TEST_TOL(32, 3.0));
    ASSERT_NEAR(3.0, x[2], TEST_TOL(32, 3.0));
}

static void test_overwrites_a_with_its_cholesky_factor(void)
{
    /* A = [4 2; 2 5] = L L^T with L = [2 0; 1 2]. */
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(4.0);
    a[1][0] = TVO_R(2.0);
    a[0][1] = TVO_R(2.0);
    a[1][1] = TVO_R(5.0);
    const tvo_real_t b[2] = {TVO_R(2.0), TVO_R(1.0)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 2, b, x));
    ASSERT_NEAR(2.0, a[0][0], TEST_TOL(4, 2.0));
    ASSERT_NEAR(1.0, a[1][0], TEST_TOL(4, 2.0));
    ASSERT_NEAR(2.0, a[1][1], TEST_TOL(4, 2.0));
    /* x = A^{-1} b = (1/16)[5 -2; -2 4](2, 1) = (8/16, 0) */
    ASSERT_NEAR(0.5, x[0], TEST_TOL(8, 1.0));
    ASSERT_NEAR(0.0, x[1], TEST_TOL(8, 1.0));
}

static void test_solves_8x8_known_solution(void)
{
    /* A = 8 I + Lehmer(min(i,j)/max(i,j)) (SPD, condition number < 10), x_true_i = (-1)^i (i + 1) / 3. */
    enum { n = TVO_MAX_Z_DIM };
    double A[n][n], xt[n], bd[n];
    mat_t a;
    tvo_real_t b[n], x[n];
    for (int i = 0; i < n; ++i) {
        xt[i] = ((i % 2) ? -1.0 : 1.0) * (i + 1) / 3.0;
        for (int j = 0; j < n; ++j) {
            const double lo = (i < j ? i : j) + 1.0, hi = (i < j ? j : i) + 1.0;
            A[i][j] = test_d(test_r(lo / hi + (i == j ? 8.0 : 0.0))); /* exactly what the solver sees */
            a[i][j] = test_r(A[i][j]);
        }
    }
    for (int i = 0; i < n; ++i) {
        bd[i] = 0.0;
        for (int j = 0; j < n; ++j) {
            bd[i] += A[i][j] * xt[j];
        }
        b[i] = test_r(bd[i]);
    }
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, n, b, x));
    for (int i = 0; i < n; ++i) {
        /* Backward-stable solve: error ~ cond * eps * |x| (cond < 10, |x| <= 3, b rounded too). */
        ASSERT_NEAR(xt[i], x[i], TEST_TOL(200, 3.0));
    }
}

static void test_solution_may_alias_right_hand_side(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    const double A[3][3] = {{4, 1, 2}, {1, 5, 3}, {2, 3, 6}};
    for (int i = 0; i < 3; ++i) {
        for (int j = 0; j < 3; ++j) {
            a[i][j] = test_r(A[i][j]);
        }
    }
    tvo_real_t bx[3] = {TVO_R(8.0), TVO_R(0.0), TVO_R(14.0)};
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 3, bx, bx));
    ASSERT_NEAR(1.0, bx[0], TEST_TOL(32, 3.0));
    ASSERT_NEAR(-2.0, bx[1], TEST_TOL(32, 3.0));
    ASSERT_NEAR(3.0, bx[2], TEST_TOL(32, 3.0));
}

static void test_one_by_one(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(4.0);
    const tvo_real_t b[1] = {TVO_R(2.0)};
    tvo_real_t x[1];
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 1, b, x));
    ASSERT_NEAR(0.5, x[0], TEST_TOL(2, 1.0));
}

static void test_scale_does_not_change_the_verdict(void)
{
    /* A tiny but well-conditioned SPD matrix (1e-20 I) must solve: the pivot test is relative. */
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1e-20);
    a[1][1] = TVO_R(2e-20);
    const tvo_real_t b[2] = {TVO_R(1e-20), TVO_R(1e-20)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_OK, tvo_cholesky_solve(a, 2, b, x));
    ASSERT_NEAR(1.0, x[0], TEST_TOL(8, 1.0));
    ASSERT_NEAR(0.5, x[1], TEST_TOL(8, 1.0));
}

static void test_rejects_indefinite_matrix(void)
{
    /* [1 2; 2 1] has eigenvalues 3 and -1. */
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1.0);
    a[1][0] = TVO_R(2.0);
    a[0][1] = TVO_R(2.0);
    a[1][1] = TVO_R(1.0);
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, 2, b, x));
}

static void test_rejects_negative_definite_matrix(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(-1.0);
    a[1][1] = TVO_R(-2.0);
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, 2, b, x));
}

static void test_rejects_singular_matrix(void)
{
    /* [1 1; 1 1]: the second pivot is exactly 0. */
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1.0);
    a[1][0] = TVO_R(1.0);
    a[0][1] = TVO_R(1.0);
    a[1][1] = TVO_R(1.0);
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, 2, b, x));
}

static void test_rejects_numerically_singular_matrix(void)
{
    /* [1 1; 1 1 + eps]: rank one to working precision. Dividing by the rounding-noise pivot
     * would return garbage of size 1/eps; the relative pivot test must refuse instead. */
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1.0);
    a[1][0] = TVO_R(1.0);
    a[0][1] = TVO_R(1.0);
    a[1][1] = test_r(1.0 + TEST_EPS);
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(2.0)};
    tvo_real_t x[2];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, 2, b, x));
}

static void test_rejects_zero_matrix(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    const tvo_real_t b[3] = {TVO_R(1.0), TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[3];
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, 3, b, x));
}

static void test_rejects_singular_block_inside_8x8(void)
{
    /* Identity except a rank-deficient 2x2 block in the last rows: the last pivot is 0. */
    mat_t a;
    mat_fill(a, 0.0);
    for (int i = 0; i < TVO_MAX_Z_DIM; ++i) {
        a[i][i] = TVO_R(1.0);
    }
    a[7][6] = TVO_R(1.0);
    a[6][7] = TVO_R(1.0);
    tvo_real_t b[TVO_MAX_Z_DIM], x[TVO_MAX_Z_DIM];
    for (int i = 0; i < TVO_MAX_Z_DIM; ++i) {
        b[i] = TVO_R(1.0);
    }
    ASSERT_STATUS(TVO_ERR_NOT_POSITIVE_DEFINITE, tvo_cholesky_solve(a, TVO_MAX_Z_DIM, b, x));
}

static void test_rejects_non_finite_matrix(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1.0);
    a[1][1] = TVO_R(1.0);
    a[1][0] = TEST_NAN;
    const tvo_real_t b[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_real_t x[2];
    TEST_ASSERT_TRUE(tvo_cholesky_solve(a, 2, b, x) != TVO_OK);
}

static void test_rejects_dimension_zero_and_above_maximum(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    for (int i = 0; i < TVO_MAX_Z_DIM; ++i) {
        a[i][i] = TVO_R(1.0);
    }
    tvo_real_t b[TVO_MAX_Z_DIM + 1] = {TVO_R(0.0)};
    tvo_real_t x[TVO_MAX_Z_DIM + 1];
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_cholesky_solve(a, 0, b, x));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_cholesky_solve(a, (uint8_t)(TVO_MAX_Z_DIM + 1), b, x));
}

static void test_rejects_null(void)
{
    mat_t a;
    mat_fill(a, 0.0);
    a[0][0] = TVO_R(1.0);
    const tvo_real_t b[1] = {TVO_R(1.0)};
    tvo_real_t x[1];
    ASSERT_STATUS(TVO_ERR_NULL, tvo_cholesky_solve(NULL, 1, b, x));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_cholesky_solve(a, 1, NULL, x));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_cholesky_solve(a, 1, b, NULL));
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_solves_3x3_known_solution);
    RUN_TEST(test_reads_only_the_lower_triangle);
    RUN_TEST(test_overwrites_a_with_its_cholesky_factor);
    RUN_TEST(test_solves_8x8_known_solution);
    RUN_TEST(test_solution_may_alias_right_hand_side);
    RUN_TEST(test_one_by_one);
    RUN_TEST(test_scale_does_not_change_the_verdict);
    RUN_TEST(test_rejects_indefinite_matrix);
    RUN_TEST(test_rejects_negative_definite_matrix);
    RUN_TEST(test_rejects_singular_matrix);
    RUN_TEST(test_rejects_numerically_singular_matrix);
    RUN_TEST(test_rejects_zero_matrix);
    RUN_TEST(test_rejects_singular_block_inside_8x8);
    RUN_TEST(test_rejects_non_finite_matrix);
    RUN_TEST(test_rejects_dimension_zero_and_above_maximum);
    RUN_TEST(test_rejects_null);
    return UNITY_END();
}
