/*
 * Formation-offset equality y_a - y_b = d(t) through multipliers (tvo/equality.h) and the law on
 * z = (y, nu): reservation and rejections; the term's jets; one tvo_law_evaluate (k = 2) whose z''
 * makes the gradient dynamics g'' + k_d g' + k_p g = 0 hold on every row, in particular the dual rows,
 * where g = r = y_a - y_b - d(t) (so r'' + k_d r' + k_p r = 0); and the Hessian is the KKT matrix.
 */
#include "test_support.h"

#include "tvo/equality.h"
#include "tvo/law.h"
#include "internal/equality.h"
#include "internal/jet.h"
#include "internal/law.h"

void setUp(void) {}
void tearDown(void) {}

static tvo_time_jet_t time_at(double t_s)
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), TVO_R(1.0), 1000000u, (uint64_t)llround(t_s * 1e6));
    return t;
}

/* p(t) = c0 + c1 t + c2 t^2 + c3 t^3 per axis, and its derivatives (by hand). */
typedef struct {
    double c[2][4];
} cubic_t;

static void cubic_target(tvo_target_t *target, const cubic_t *p)
{
    tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
    memset(coeff, 0, sizeof(coeff));
    for (int a = 0; a < 2; ++a) {
        for (int j = 0; j < 4; ++j) {
            coeff[a][j] = test_r(p->c[a][j]);
        }
    }
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(target, TEST_CONST_POLY(coeff)));
}

static double cubic_deriv(const cubic_t *p, int axis, int order, double t)
{
    const double *c = p->c[axis];
    switch (order) {
    case 0: return c[0] + t * (c[1] + t * (c[2] + t * c[3]));
    case 1: return c[1] + t * (2.0 * c[2] + 3.0 * t * c[3]);
    case 2: return 2.0 * c[2] + 6.0 * t * c[3];
    default: return 6.0 * c[3];
    }
}

static const cubic_t YD_A = {{{0.5, 0.3, -0.2, 0.05}, {-1.0, 0.1, 0.4, -0.02}}};
static const cubic_t YD_B = {{{-1.0, 0.2, 0.1, 0.0}, {0.5, -0.3, 0.0, 0.01}}};
static const cubic_t OFFSET = {{{1.0, 0.2, 0.1, 0.0}, {-0.5, 0.3, 0.0, -0.05}}};
static const double W[2][2] = {{2.0, 0.5}, {1.0, 1.5}};

typedef struct {
    tvo_target_t target[2];
    tvo_tracking_term_t track[2];
    tvo_target_t offset;
    tvo_offset_equality_term_t eq;
    tvo_objective_t objective;
} formation_t;

static void formation(formation_t *f)
{
    cubic_target(&f->target[0], &YD_A);
    cubic_target(&f->target[1], &YD_B);
    cubic_target(&f->offset, &OFFSET);
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&f->objective, 4));
    for (uint8_t r = 0; r < 2; ++r) {
        const tvo_real_t w[2] = {test_r(W[r][0]), test_r(W[r][1])};
        ASSERT_STATUS(TVO_OK, tvo_tracking_init(&f->track[r], &f->target[r], w, (uint8_t)(2u * r)));
        ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&f->objective, tvo_tracking_gradient_jet, &f->track[r]));
    }
    ASSERT_STATUS(TVO_OK, tvo_offset_equality_add(&f->eq, &f->objective, &f->offset, 0, 1));
}

static void test_add_reserves_two_multipliers(void)
{
    formation_t f;
    formation(&f);
    TEST_ASSERT_EQUAL_UINT8(4, f.objective.primal_dim);
    TEST_ASSERT_EQUAL_UINT8(2, f.objective.dual_dim);
    TEST_ASSERT_EQUAL_UINT8(6, f.objective.dim);
    TEST_ASSERT_EQUAL_UINT8(3, f.objective.term_count);
    TEST_ASSERT_EQUAL_UINT8(4, f.eq.multiplier_index);
    TEST_ASSERT_EQUAL_UINT8(0, f.eq.offset_a);
    TEST_ASSERT_EQUAL_UINT8(2, f.eq.offset_b);
}

static void test_add_rejects_same_robot_range_and_capacity(void)
{
    tvo_target_t d;
    cubic_target(&d, &OFFSET);
    tvo_objective_t obj;
    tvo_offset_equality_term_t eq[3];
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 4));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_offset_equality_add(&eq[0], &obj, &d, 1, 1));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_offset_equality_add(&eq[0], &obj, &d, 0, 2)); /* robot 2 of 2 */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_offset_equality_add(&eq[0], &obj, &d, TVO_MAX_ROBOTS, 0));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_offset_equality_add(&eq[0], &obj, NULL, 0, 1));
    TEST_ASSERT_EQUAL_UINT8(4, obj.dim); /* nothing reserved by the failures */
    TEST_ASSERT_EQUAL_UINT8(0, obj.term_count);
    ASSERT_STATUS(TVO_OK, tvo_offset_equality_add(&eq[0], &obj, &d, 0, 1));
    /* Two robots: four multipliers would not be fewer than the four outputs. */
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_offset_equality_add(&eq[1], &obj, &d, 1, 0));
    TEST_ASSERT_EQUAL_UINT8(6, obj.dim);

    /* Four robots: TVO_MAX_EQUALITIES (4) multipliers fit, a third offset does not. */
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 8));
    ASSERT_STATUS(TVO_OK, tvo_offset_equality_add(&eq[0], &obj, &d, 0, 1));
    ASSERT_STATUS(TVO_OK, tvo_offset_equality_add(&eq[1], &obj, &d, 2, 3));
    TEST_ASSERT_EQUAL_UINT8(10, eq[1].multiplier_index);
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_offset_equality_add(&eq[2], &obj, &d, 1, 2));
    TEST_ASSERT_EQUAL_UINT8(12, obj.dim);
    TEST_ASSERT_EQUAL_UINT8(4, obj.dual_dim);

    /* A full term table: the multipliers are given back. */
    tvo_tracking_term_t track;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&track, &d, w, 0));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 4));
    for (int i = 0; i < TVO_MAX_TERMS; ++i) {
        ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, tvo_tracking_gradient_jet, &track));
    }
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_offset_equality_add(&eq[0], &obj, &d, 0, 1));
    TEST_ASSERT_EQUAL_UINT8(4, obj.dim);
    TEST_ASSERT_EQUAL_UINT8(0, obj.dual_dim);
    /* The same with tracking terms alone (tvo_tracking_add): nor does the general path stay linked. */
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 4));
    for (int i = 0; i < TVO_MAX_TERMS; ++i) {
        ASSERT_STATUS(TVO_OK, tvo_tracking_add(&obj, &track));
    }
    ASSERT_STATUS(TVO_ERR_CAPACITY, tvo_offset_equality_add(&eq[0], &obj, &d, 0, 1));
    TEST_ASSERT_EQUAL_UINT8(0, obj.dual_dim);
    TEST_ASSERT_NULL(obj.general_path);
}

static void test_gradient_jet_is_the_lagrangian_gradient(void)
{
    /* grad_ya += nu, grad_yb -= nu, grad_nu = y_a - y_b - d(t): exact for jets of any order. */
    formation_t f;
    formation(&f);
    const double y[6] = {1.0, -0.5, 0.25, 0.75, 0.5, -2.0};
    const double v[6] = {0.5, 0.25, -0.5, 1.0, 0.125, 0.25};
    tvo_jet_t z[6], g[6];
    for (int i = 0; i < 6; ++i) {
        tvo_jet_variable(test_r(y[i]), test_r(v[i]), &z[i]);
        tvo_jet_constant(TVO_R(0.0), &g[i]);
    }
    const double t = 0.75;
    const tvo_time_jet_t tj = time_at(t);
    ASSERT_STATUS(TVO_OK, tvo_offset_equality_gradient_jet(&f.eq, z, 6, &tj, 3, g));
    for (int axis = 0; axis < 2; ++axis) {
        ASSERT_NEAR(y[4 + axis], g[axis].c[0], 0.0);
        ASSERT_NEAR(v[4 + axis], g[axis].c[1], 0.0);
        ASSERT_NEAR(-y[4 + axis], g[2 + axis].c[0], 0.0);
        ASSERT_NEAR(-v[4 + axis], g[2 + axis].c[1], 0.0);
        const double r0 = y[axis] - y[2 + axis] - cubic_deriv(&OFFSET, axis, 0, t);
        const double r1 = v[axis] - v[2 + axis] - cubic_deriv(&OFFSET, axis, 1, t);
        const double r2 = -cubic_deriv(&OFFSET, axis, 2, t) / 2.0;
        const double r3 = -cubic_deriv(&OFFSET, axis, 3, t) / 6.0;
        /* A polynomial target evaluated in tvo_real_t: a few ulps of its terms (all <= 2). */
        ASSERT_NEAR(r0, g[4 + axis].c[0], TEST_TOL(16, 2.0));
        ASSERT_NEAR(r1, g[4 + axis].c[1], TEST_TOL(16, 2.0));
        ASSERT_NEAR(r2, g[4 + axis].c[2], TEST_TOL(16, 2.0));
        ASSERT_NEAR(r3, g[4 + axis].c[3], TEST_TOL(16, 2.0));
    }
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_offset_equality_gradient_jet(&f.eq, z, 5, &tj, 1, g));
}

static void test_law_imposes_gradient_dynamics_on_the_dual_block(void)
{
    formation_t f;
    formation(&f);
    const double kp = 40.0, kd = 13.0, t = 0.6;
    const tvo_real_t gain[2] = {test_r(kp), test_r(kd)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 6, gain);
    /* y_a - y_b differs from d(t) (residual ~ 1), the multipliers and their rates are nonzero. */
    const double z[6] = {0.5, -0.25, -1.0, 0.75, 0.5, -1.5};
    const double zd[6] = {0.25, 1.0, -0.5, 0.5, 0.25, -0.125};
    tvo_output_derivs_t y;
    memset(&y, 0, sizeof(y));
    for (int i = 0; i < 6; ++i) {
        y.d[0][i] = test_r(z[i]);
        y.d[1][i] = test_r(zd[i]);
    }
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t zdd[6];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &f.objective, &y, &tj, zdd, &ev));
    ASSERT_NEAR(0.0, ev.regularization, 0.0);
    const double te = test_d(tj.t_s);
    /* The KKT matrix [W C^T; C 0] has condition ~10 and the right-hand side is ~kp |g| ~ 100: a few
     * hundred ulps of 100 bound the rounding of z'' and of these combinations. */
    const double tol = TEST_TOL(256, 100.0);
    for (int axis = 0; axis < 2; ++axis) {
        /* Dual row: r = y_a - y_b - d. */
        const double r = z[axis] - z[2 + axis] - cubic_deriv(&OFFSET, axis, 0, te);
        const double r1 = zd[axis] - zd[2 + axis] - cubic_deriv(&OFFSET, axis, 1, te);
        const double r2 = test_d(zdd[axis]) - test_d(zdd[2 + axis]) - cubic_deriv(&OFFSET, axis, 2, te);
        ASSERT_NEAR_MSG(0.0, r2 + kd * r1 + kp * r, tol, "r'' + kd r' + kp r");
        /* Primal rows: g_a = W_a (y_a - yd_a) + nu, g_b = W_b (y_b - yd_b) - nu. */
        const cubic_t *yd[2] = {&YD_A, &YD_B};
        for (int rb = 0; rb < 2; ++rb) {
            const int i = 2 * rb + axis;
            const double sign = rb == 0 ? 1.0 : -1.0;
            const double w = W[rb][axis];
            const double g0 = w * (z[i] - cubic_deriv(yd[rb], axis, 0, te)) + sign * z[4 + axis];
            const double g1 = w * (zd[i] - cubic_deriv(yd[rb], axis, 1, te)) + sign * zd[4 + axis];
            const double g2 = w * (test_d(zdd[i]) - cubic_deriv(yd[rb], axis, 2, te)) + sign * test_d(zdd[4 + axis]);
            ASSERT_NEAR_MSG(0.0, g2 + kd * g1 + kp * g0, tol, "primal gradient dynamics");
            ASSERT_NEAR(g0, ev.grad[0][i], TEST_TOL(16, 4.0));
            ASSERT_NEAR(g1, ev.grad[1][i], TEST_TOL(16, 4.0));
        }
        ASSERT_NEAR(r, ev.grad[0][4 + axis], TEST_TOL(16, 4.0));
        ASSERT_NEAR(r1, ev.grad[1][4 + axis], TEST_TOL(16, 4.0));
    }
    /* The Hessian is the KKT matrix: W on the primal block, +-I coupling, zero dual block (exact: the
     * terms are linear or quadratic, so the jets carry exact unit and weight coefficients). */
    double kkt[6][6];
    memset(kkt, 0, sizeof(kkt));
    kkt[0][0] = W[0][0];
    kkt[1][1] = W[0][1];
    kkt[2][2] = W[1][0];
    kkt[3][3] = W[1][1];
    for (int axis = 0; axis < 2; ++axis) {
        kkt[4 + axis][axis] = kkt[axis][4 + axis] = 1.0;
        kkt[4 + axis][2 + axis] = kkt[2 + axis][4 + axis] = -1.0;
    }
    for (int i = 0; i < 6; ++i) {
        for (int j = 0; j < 6; ++j) {
            ASSERT_NEAR(kkt[i][j], ev.hessian[i][j], 0.0);
        }
    }
}

static void test_law_keeps_a_satisfied_constraint_satisfied(void)
{
    /* At r = r' = 0 the dual rows demand r'' = 0: y_a'' - y_b'' = d'' exactly (to rounding). */
    formation_t f;
    formation(&f);
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 6, gain);
    const double t = 0.0;
    const double d0[2] = {cubic_deriv(&OFFSET, 0, 0, t), cubic_deriv(&OFFSET, 1, 0, t)};
    const double d1[2] = {cubic_deriv(&OFFSET, 0, 1, t), cubic_deriv(&OFFSET, 1, 1, t)};
    const double z[6] = {d0[0] + 0.25, d0[1] - 0.5, 0.25, -0.5, 0.0, 0.0};
    const double zd[6] = {d1[0] + 0.5, d1[1] + 0.5, 0.5, 0.5, 0.0, 0.0};
    tvo_output_derivs_t y;
    memset(&y, 0, sizeof(y));
    for (int i = 0; i < 6; ++i) {
        y.d[0][i] = test_r(z[i]);
        y.d[1][i] = test_r(zd[i]);
    }
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t zdd[6];
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &f.objective, &y, &tj, zdd, NULL));
    for (int axis = 0; axis < 2; ++axis) {
        ASSERT_NEAR(cubic_deriv(&OFFSET, axis, 2, t), test_d(zdd[axis]) - test_d(zdd[2 + axis]), TEST_TOL(256, 100.0));
    }
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_add_reserves_two_multipliers);
    RUN_TEST(test_add_rejects_same_robot_range_and_capacity);
    RUN_TEST(test_gradient_jet_is_the_lagrangian_gradient);
    RUN_TEST(test_law_imposes_gradient_dynamics_on_the_dual_block);
    RUN_TEST(test_law_keeps_a_satisfied_constraint_satisfied);
    return UNITY_END();
}
