/*
 * The TV-O law y^(k) = -H^{-1} [ sum_{i<k} a_i grad^(i) + r ] (paper, Theorem "TVO-based control").
 *
 * Tracking objective f0 = 1/2 (y - yd(t))^T W (y - yd(t)), W diagonal:
 *   g = W e (e = y - yd),  g' = W e',  g'' = W e'',  H = W,
 *   r = the y^(k)-free part of g^(k) = -W yd^(k),
 * so the law collapses to the paper's chain testbed (eq. "chain_testbed"):
 *   k = 1:  y'   = yd'   - a0 e
 *   k = 2:  y''  = yd''  - kp e - kd e'
 *   k = 3:  y''' = yd''' - a0 e - a1 e' - a2 e''
 * A non-quadratic custom term (below) checks the general Newton form with a state-dependent
 * Hessian and a time-dependent gradient.
 */
#include "test_support.h"

#include "tvo/law.h"
#include "internal/jet.h"
#include "internal/law.h"

void setUp(void) {}
void tearDown(void) {}

/* Law outputs are O(kp |e|) ~ 50 here: a few dozen ulps of that. */
#define LAW_TOL TEST_TOL(64, 60.0)

/* ------------------------------------------------------------------------------------------------
 * Tracking fixture: yd(t) = (0.5 + 0.3t - 0.2t^2 + 0.05t^3,  -1 + 0.1t + 0.4t^2 - 0.02t^3)
 *   yd'   = (0.3 - 0.4t + 0.15t^2,  0.1 + 0.8t - 0.06t^2)
 *   yd''  = (-0.4 + 0.3t,           0.8 - 0.12t)
 *   yd''' = (0.3,                   -0.12)
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    tvo_target_t target;
    tvo_tracking_term_t term;
    tvo_objective_t objective;
} tracking_fx_t;

static const double W0 = 2.0, W1 = 0.5;

static void tracking_fixture(tracking_fx_t *fx)
{
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    c[0][0] = TVO_R(0.5);
    c[0][1] = TVO_R(0.3);
    c[0][2] = TVO_R(-0.2);
    c[0][3] = TVO_R(0.05);
    c[1][0] = TVO_R(-1.0);
    c[1][1] = TVO_R(0.1);
    c[1][2] = TVO_R(0.4);
    c[1][3] = TVO_R(-0.02);
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(&fx->target, TEST_CONST_POLY(c)));
    const tvo_real_t w[2] = {test_r(W0), test_r(W1)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&fx->term, &fx->target, w, 0));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&fx->objective, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&fx->objective, tvo_tracking_gradient_jet, &fx->term));
}

/* yd^(j)(t), j = 0..3, by hand (see above). */
static void yd_at(double t, double yd[4][2])
{
    yd[0][0] = 0.5 + 0.3 * t - 0.2 * t * t + 0.05 * t * t * t;
    yd[0][1] = -1.0 + 0.1 * t + 0.4 * t * t - 0.02 * t * t * t;
    yd[1][0] = 0.3 - 0.4 * t + 0.15 * t * t;
    yd[1][1] = 0.1 + 0.8 * t - 0.06 * t * t;
    yd[2][0] = -0.4 + 0.3 * t;
    yd[2][1] = 0.8 - 0.12 * t;
    yd[3][0] = 0.3;
    yd[3][1] = -0.12;
}

static tvo_time_jet_t time_at(double t_s)
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), TVO_R(1.0), 1000u, (uint64_t)llround(t_s * 1000.0));
    return t;
}

/* State y^(0..2) used throughout: y = (1, -0.5), y' = (0.3, 0.8), y'' = (-0.2, 0.1). */
static const double Y[3][2] = {{1.0, -0.5}, {0.3, 0.8}, {-0.2, 0.1}};

static tvo_output_derivs_t state(uint8_t k)
{
    tvo_output_derivs_t y;
    memset(&y, 0, sizeof(y));
    for (uint8_t j = 0; j < k; ++j) {
        y.d[j][0] = test_r(Y[j][0]);
        y.d[j][1] = test_r(Y[j][1]);
    }
    return y;
}

static void assert_tracking_eval(const tvo_law_eval_t *ev, uint8_t k, double t)
{
    double yd[4][2];
    yd_at(t, yd);
    const double w[2] = {W0, W1};
    for (uint8_t i = 0; i < 2; ++i) {
        for (uint8_t j = 0; j < k; ++j) {
            /* grad^(j) = W e^(j) */
            ASSERT_NEAR(w[i] * (Y[j][i] - yd[j][i]), ev->grad[j][i], LAW_TOL);
        }
        /* r = -W yd^(k) */
        ASSERT_NEAR(-w[i] * yd[k][i], ev->grad[k][i], LAW_TOL);
    }
    ASSERT_NEAR(W0, ev->hessian[0][0], TEST_TOL(8, 2.0));
    ASSERT_NEAR(0.0, ev->hessian[0][1], TEST_TOL(8, 2.0));
    ASSERT_NEAR(0.0, ev->hessian[1][0], TEST_TOL(8, 2.0));
    ASSERT_NEAR(W1, ev->hessian[1][1], TEST_TOL(8, 2.0));
}

static void test_k2_tracking_law_is_the_pd_chain(void)
{
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const double kp = 40.0, kd = 13.0, t = 0.7;
    const tvo_real_t gain[2] = {test_r(kp), test_r(kd)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t ydd[2] = {TVO_R(-99.0), TVO_R(-99.0)};
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &fx.objective, &y, &tj, ydd, &ev));
    double yd[4][2];
    yd_at(test_d(tj.t_s), yd);
    for (int i = 0; i < 2; ++i) {
        const double e = Y[0][i] - yd[0][i], de = Y[1][i] - yd[1][i];
        ASSERT_NEAR(yd[2][i] - kp * e - kd * de, ydd[i], LAW_TOL);
    }
    assert_tracking_eval(&ev, 2, test_d(tj.t_s));
}

static void test_k2_hand_value_at_t0(void)
{
    /* t = 0: yd = (0.5, -1), yd' = (0.3, 0.1), yd'' = (-0.4, 0.8); e = (0.5, 0.5), e' = (0, 0.7).
     * kp = 40, kd = 13: y'' = (-0.4 - 20 - 0, 0.8 - 20 - 9.1) = (-20.4, -28.3). W drops out. */
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(0.0);
    tvo_real_t ydd[2];
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &fx.objective, &y, &tj, ydd, NULL));
    ASSERT_NEAR(-20.4, ydd[0], LAW_TOL);
    ASSERT_NEAR(-28.3, ydd[1], LAW_TOL);
}

static void test_k1_tracking_law_is_gradient_flow_with_feedforward(void)
{
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const double a0 = 3.0, t = 1.1;
    const tvo_real_t gain[1] = {test_r(a0)};
    tvo_law_t law;
    tvo_law_init(&law, 1, 2, gain);
    const tvo_output_derivs_t y = state(1);
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t yd1[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &fx.objective, &y, &tj, yd1, &ev));
    double yd[4][2];
    yd_at(test_d(tj.t_s), yd);
    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(yd[1][i] - a0 * (Y[0][i] - yd[0][i]), yd1[i], LAW_TOL);
    }
    assert_tracking_eval(&ev, 1, test_d(tj.t_s));
}

static void test_k3_tracking_law_is_the_third_order_chain(void)
{
    /* Poles at -1.6 as in the paper's practical study: (s + 1.6)^3 = s^3 + 4.8 s^2 + 7.68 s + 4.096. */
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const double a0 = 4.096, a1 = 7.68, a2 = 4.8, t = 0.4;
    const tvo_real_t gain[3] = {test_r(a0), test_r(a1), test_r(a2)};
    tvo_law_t law;
    tvo_law_init(&law, 3, 2, gain);
    const tvo_output_derivs_t y = state(3);
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t y3[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &fx.objective, &y, &tj, y3, &ev));
    double yd[4][2];
    yd_at(test_d(tj.t_s), yd);
    for (int i = 0; i < 2; ++i) {
        const double e = Y[0][i] - yd[0][i], de = Y[1][i] - yd[1][i], dde = Y[2][i] - yd[2][i];
        ASSERT_NEAR(yd[3][i] - a0 * e - a1 * de - a2 * dde, y3[i], LAW_TOL);
    }
    assert_tracking_eval(&ev, 3, test_d(tj.t_s));
}

static void test_k2_two_robots_are_decoupled(void)
{
    /* dim 4: robot 0 tracks the polynomial (offset 0), robot 1 a circle (offset 2) with W = I.
     * Circle c = (2, 1), r = 0.5, w = 1.5, phase 0: yd = c + r(cos wt, sin wt),
     * yd' = r w (-sin, cos), yd'' = -r w^2 (cos, sin). */
    tracking_fx_t fx;
    tracking_fixture(&fx);
    tvo_target_t circle;
    const tvo_real_t centre[2] = {TVO_R(2.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_target_init_circle(&circle, centre, TVO_R(0.5), TVO_R(1.5), TVO_R(0.0)));
    tvo_tracking_term_t term1;
    const tvo_real_t w1[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term1, &circle, w1, 2));
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 4));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, tvo_tracking_gradient_jet, &fx.term));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, tvo_tracking_gradient_jet, &term1));

    const double kp = 40.0, kd = 13.0, t = 0.9;
    const tvo_real_t gain[2] = {test_r(kp), test_r(kd)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 4, gain);
    tvo_output_derivs_t y;
    memset(&y, 0, sizeof(y));
    const double y1[2][2] = {{2.2, 1.3}, {-0.4, 0.6}}; /* robot 1: position, velocity */
    for (int i = 0; i < 2; ++i) {
        y.d[0][i] = test_r(Y[0][i]);
        y.d[1][i] = test_r(Y[1][i]);
        y.d[0][2 + i] = test_r(y1[0][i]);
        y.d[1][2 + i] = test_r(y1[1][i]);
    }
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t ydd[4];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &y, &tj, ydd, &ev));
    const double tt = test_d(tj.t_s);
    double yd[4][2];
    yd_at(tt, yd);
    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(yd[2][i] - kp * (Y[0][i] - yd[0][i]) - kd * (Y[1][i] - yd[1][i]), ydd[i], LAW_TOL);
    }
    const double ph = 1.5 * tt, r = 0.5, w = 1.5;
    const double c_pos[2] = {2.0 + r * cos(ph), 1.0 + r * sin(ph)};
    const double c_vel[2] = {-r * w * sin(ph), r * w * cos(ph)};
    const double c_acc[2] = {-r * w * w * cos(ph), -r * w * w * sin(ph)};
    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(c_acc[i] - kp * (y1[0][i] - c_pos[i]) - kd * (y1[1][i] - c_vel[i]), ydd[2 + i], LAW_TOL);
    }
    /* Block-diagonal Hessian diag(W0, W1, 1, 1). */
    const double hd[4] = {W0, W1, 1.0, 1.0};
    for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
            ASSERT_NEAR(i == j ? hd[i] : 0.0, ev.hessian[i][j], TEST_TOL(8, 2.0));
        }
    }
}

/* ------------------------------------------------------------------------------------------------
 * A non-quadratic custom term, written here against the objective interface:
 *   f(y, t) = 1/4 |y|^4 - (t^2 / 2) b.y
 *   g   = |y|^2 y - (t^2/2) b
 *   H   = |y|^2 I + 2 y y^T                                  (PD for y != 0; time-free)
 *   g'  = H y' - t b
 *   r   = (d/dt H) y' + d/dt(-t b)  with y'' = 0
 *       = [2 (y.y') I + 2 (y' y^T + y y'^T)] y' - b  =  4 (y.y') y' + 2 |y'|^2 y - b
 *   y'' = -H^{-1} (r + kp g + kd g')
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    tvo_real_t b[2];
} quartic_term_t;

static tvo_status_t quartic_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim,
                                         const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    const quartic_term_t *q = (const quartic_term_t *)term;
    if (dim != 2u) {
        return TVO_ERR_DIMENSION;
    }
    tvo_jet_t s, sq, tj, t2, prod;
    tvo_jet_mul(&y[0], &y[0], order, &s);
    tvo_jet_mul(&y[1], &y[1], order, &sq);
    tvo_jet_add(&s, &sq, order, &s);          /* |y(tau)|^2 */
    tvo_jet_variable(t->t_s, t->rate, &tj);   /* t(tau) = t + rate tau */
    tvo_jet_mul(&tj, &tj, order, &t2);        /* t(tau)^2 */
    for (uint8_t i = 0; i < 2u; ++i) {
        tvo_jet_mul(&s, &y[i], order, &prod);
        tvo_jet_add(&grad[i], &prod, order, &grad[i]);
        tvo_jet_axpy(TVO_R(-0.5) * q->b[i], &t2, order, &grad[i]);
    }
    return TVO_OK;
}

static void test_k2_custom_quartic_term_matches_hand_newton_step(void)
{
    quartic_term_t q = {{TVO_R(1.0), TVO_R(-2.0)}};
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, quartic_gradient_jet, &q));
    const double kp = 40.0, kd = 13.0;
    const tvo_real_t gain[2] = {test_r(kp), test_r(kd)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);

    const double y[2] = {0.6, -0.8}, v[2] = {0.5, 0.25}, b[2] = {1.0, -2.0}, t = 1.2;
    tvo_output_derivs_t yy;
    memset(&yy, 0, sizeof(yy));
    for (int i = 0; i < 2; ++i) {
        yy.d[0][i] = test_r(y[i]);
        yy.d[1][i] = test_r(v[i]);
    }
    const tvo_time_jet_t tj = time_at(t);
    tvo_real_t ydd[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &yy, &tj, ydd, &ev));

    const double tt = test_d(tj.t_s);
    const double n2 = y[0] * y[0] + y[1] * y[1];
    const double yv = y[0] * v[0] + y[1] * v[1];
    const double v2 = v[0] * v[0] + v[1] * v[1];
    const double H[2][2] = {{n2 + 2 * y[0] * y[0], 2 * y[0] * y[1]}, {2 * y[0] * y[1], n2 + 2 * y[1] * y[1]}};
    double g[2], gd[2], r[2], rhs[2];
    for (int i = 0; i < 2; ++i) {
        g[i] = n2 * y[i] - 0.5 * tt * tt * b[i];
        gd[i] = H[i][0] * v[0] + H[i][1] * v[1] - tt * b[i];
        r[i] = 4.0 * yv * v[i] + 2.0 * v2 * y[i] - b[i];
        rhs[i] = r[i] + kp * g[i] + kd * gd[i];
    }
    const double det = H[0][0] * H[1][1] - H[0][1] * H[1][0];
    const double e0 = -(H[1][1] * rhs[0] - H[0][1] * rhs[1]) / det;
    const double e1 = -(-H[1][0] * rhs[0] + H[0][0] * rhs[1]) / det;

    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(g[i], ev.grad[0][i], LAW_TOL);
        ASSERT_NEAR(gd[i], ev.grad[1][i], LAW_TOL);
        ASSERT_NEAR(r[i], ev.grad[2][i], LAW_TOL);
        for (int j = 0; j < 2; ++j) {
            /* Hessian columns are taken with time frozen (rate 0): no -t b leaks into H. */
            ASSERT_NEAR(H[i][j], ev.hessian[i][j], TEST_TOL(16, 4.0));
        }
    }
    ASSERT_NEAR(e0, ydd[0], LAW_TOL);
    ASSERT_NEAR(e1, ydd[1], LAW_TOL);
}

static void test_k2_custom_term_closed_loop_identity(void)
{
    /* Whatever the term, the law must make grad'' = -kp grad - kd grad' hold at the evaluation
     * point: H y'' + r = -kp g - kd g'. Check the residual with the computed y'' and eval fields. */
    quartic_term_t q = {{TVO_R(-0.3), TVO_R(0.7)}};
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, quartic_gradient_jet, &q));
    const tvo_real_t gain[2] = {TVO_R(9.0), TVO_R(6.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    tvo_output_derivs_t yy;
    memset(&yy, 0, sizeof(yy));
    yy.d[0][0] = TVO_R(1.5);
    yy.d[0][1] = TVO_R(0.2);
    yy.d[1][0] = TVO_R(-0.4);
    yy.d[1][1] = TVO_R(1.1);
    const tvo_time_jet_t tj = time_at(0.3);
    tvo_real_t ydd[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &yy, &tj, ydd, &ev));
    for (int i = 0; i < 2; ++i) {
        const double lhs = test_d(ev.hessian[i][0]) * test_d(ydd[0]) + test_d(ev.hessian[i][1]) * test_d(ydd[1]) +
                           test_d(ev.grad[2][i]);
        const double rhs = -9.0 * test_d(ev.grad[0][i]) - 6.0 * test_d(ev.grad[1][i]);
        ASSERT_NEAR(rhs, lhs, LAW_TOL);
    }
}

/* f = 1/2 (y1^2 - y2^2): H = diag(1, -1), indefinite. */
static tvo_status_t saddle_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                        uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)dim;
    (void)t;
    tvo_jet_add(&grad[0], &y[0], order, &grad[0]);
    tvo_jet_sub(&grad[1], &y[1], order, &grad[1]);
    return TVO_OK;
}

/* f = 1/2 |y|^2: H = I. */
static tvo_status_t identity_gradient_jet_for_regularization(const void *term, const tvo_jet_t *y, uint8_t dim,
                                                             const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)dim;
    (void)t;
    tvo_jet_add(&grad[0], &y[0], order, &grad[0]);
    tvo_jet_add(&grad[1], &y[1], order, &grad[1]);
    return TVO_OK;
}

/* f = 1/2 y1^2: H = diag(1, 0), singular. */
static tvo_status_t trough_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                        uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)dim;
    (void)t;
    tvo_jet_add(&grad[0], &y[0], order, &grad[0]);
    return TVO_OK;
}

/* A term whose gradient is NaN. */
static tvo_status_t nan_gradient_jet(const void *term, const tvo_jet_t *y, uint8_t dim, const tvo_time_jet_t *t,
                                     uint8_t order, tvo_jet_t *grad)
{
    (void)term;
    (void)y;
    (void)dim;
    (void)t;
    (void)order;
    grad[0].c[0] = TEST_NAN;
    return TVO_OK;
}

static const int dummy_term_storage = 0;

static tvo_status_t evaluate_single_term(tvo_gradient_jet_fn fn, tvo_real_t ydd[2], tvo_law_eval_t *ev)
{
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, fn, &dummy_term_storage));
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(0.5);
    ydd[0] = TVO_R(123.0);
    ydd[1] = TVO_R(456.0);
    return tvo_law_evaluate(&law, &obj, &y, &tj, ydd, ev);
}

/* H = diag(1, -1) is indefinite: the solve shifts it by the first ladder step that makes it
 * positive definite (1e-6 .. 1e2 times max(1, max |H_ii|) = 1: mu = 10), and the law returns
 * -(H + 10 I)^-1 (k_p g + k_d g') with g = (1, 0.5), g' = (0.3, -0.8). */
static void test_indefinite_hessian_is_regularized_by_the_ladder(void)
{
    tvo_real_t ydd[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, evaluate_single_term(saddle_gradient_jet, ydd, &ev));
    ASSERT_NEAR(10.0, ev.regularization, 10.0 * 1e-6);
    ASSERT_NEAR(-(40.0 * 1.0 + 13.0 * 0.3) / 11.0, ydd[0], 1e-5);
    ASSERT_NEAR(-(40.0 * 0.5 + 13.0 * -0.8) / 9.0, ydd[1], 1e-5);
}

/* H = diag(1, 0) is singular: the smallest ladder shift above the pivot floor (64 eps) is used;
 * the flat direction has zero gradient, so it gets no acceleration. */
static void test_singular_hessian_is_regularized_minimally(void)
{
    tvo_real_t ydd[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, evaluate_single_term(trough_gradient_jet, ydd, &ev));
    TEST_ASSERT_TRUE(ev.regularization > TVO_R(0.0));
    TEST_ASSERT_TRUE(ev.regularization <= TVO_R(1e-3));
    ASSERT_NEAR(-(40.0 * 1.0 + 13.0 * 0.3), ydd[0], 1e-2);
    ASSERT_NEAR(0.0, ydd[1], 0.0);
}

static void test_positive_definite_hessian_is_not_regularized(void)
{
    tvo_real_t ydd[2];
    tvo_law_eval_t ev;
    ASSERT_STATUS(TVO_OK, evaluate_single_term(identity_gradient_jet_for_regularization, ydd, &ev));
    ASSERT_NEAR(0.0, ev.regularization, 0.0);
}

static void test_non_finite_gradient_is_reported_and_output_zeroed(void)
{
    tvo_real_t ydd[2];
    ASSERT_STATUS(TVO_ERR_NUMERIC, evaluate_single_term(nan_gradient_jet, ydd, NULL));
    ASSERT_NEAR(0.0, ydd[0], 0.0);
    ASSERT_NEAR(0.0, ydd[1], 0.0);
}

static void test_term_error_is_propagated_and_output_zeroed(void)
{
    /* A streamed target without a sample: the tracking term's status comes out of the law. */
    tvo_target_t target;
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&target));
    tvo_tracking_term_t term;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&term, &target, w, 0));
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, tvo_tracking_gradient_jet, &term));
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(0.5);
    tvo_real_t ydd[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_law_evaluate(&law, &obj, &y, &tj, ydd, NULL)); /* misuse: the step checks first */
    ASSERT_NEAR(0.0, ydd[0], 0.0);
    ASSERT_NEAR(0.0, ydd[1], 0.0);
}

static void test_non_finite_state_is_rejected(void)
{
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    tvo_output_derivs_t y = state(2);
    y.d[1][1] = TEST_NAN;
    const tvo_time_jet_t tj = time_at(0.5);
    tvo_real_t ydd[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_ERR_NOT_FINITE, tvo_law_evaluate(&law, &fx.objective, &y, &tj, ydd, NULL));
    ASSERT_NEAR(0.0, ydd[0], 0.0);
    ASSERT_NEAR(0.0, ydd[1], 0.0);
}

static void test_objective_dimension_must_match_the_law(void)
{
    tracking_fx_t fx;
    tracking_fixture(&fx);
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 4, gain); /* law over R^4, objective over R^2 */
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(0.5);
    tvo_real_t ydd[4] = {TVO_R(1.0), TVO_R(1.0), TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_law_evaluate(&law, &fx.objective, &y, &tj, ydd, NULL));
    for (int i = 0; i < 4; ++i) {
        ASSERT_NEAR(0.0, ydd[i], 0.0); /* the law's dim: zeroed, as on any refusal of a known length */
    }
    tvo_law_workspace_t work;
    tvo_real_t gradient[4];
    tvo_real_t gradient_rate[4];
    tvo_law_report_t report = {gradient, gradient_rate, 4u, TVO_R(0.0)};
    ydd[3] = TVO_R(1.0);
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_law_evaluate_report(&law, &fx.objective, &y, &tj, ydd, &report, &work));
    ASSERT_NEAR(0.0, ydd[3], 0.0);
}

static void test_identical_inputs_give_bit_identical_outputs(void)
{
    quartic_term_t q = {{TVO_R(1.0), TVO_R(-2.0)}};
    tvo_objective_t obj;
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&obj, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&obj, quartic_gradient_jet, &q));
    const tvo_real_t gain[2] = {TVO_R(40.0), TVO_R(13.0)};
    tvo_law_t law;
    tvo_law_init(&law, 2, 2, gain);
    const tvo_output_derivs_t y = state(2);
    const tvo_time_jet_t tj = time_at(0.77);
    tvo_real_t a[2], b[2];
    tvo_law_eval_t ea, eb;
    memset(&ea, 0x5A, sizeof(ea));
    memset(&eb, 0xA5, sizeof(eb));
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &y, &tj, a, &ea));
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &y, &tj, b, &eb));
    TEST_ASSERT_EQUAL_MEMORY(a, b, sizeof(a));
    TEST_ASSERT_EQUAL_MEMORY(&ea, &eb, sizeof(ea));
    /* eval is optional and does not change the result. */
    tvo_real_t c[2];
    ASSERT_STATUS(TVO_OK, tvo_law_evaluate(&law, &obj, &y, &tj, c, NULL));
    TEST_ASSERT_EQUAL_MEMORY(a, c, sizeof(a));
}

/* ------------------------------------------------------------------------------------------------
 * Initialisation
 * --------------------------------------------------------------------------------------------- */

/* The gains' check the controllers' inits make before tvo_law_init (dim: the law's size, which the
 * check does not read). */
static tvo_status_t init_with(uint8_t k, uint8_t dim, double a0, double a1, double a2)
{
    const tvo_real_t gain[3] = {test_r(a0), test_r(a1), test_r(a2)};
    (void)dim;
    return tvo_law_gains_hurwitz(k, gain) ? TVO_OK : TVO_ERR_PARAM;
}

static void test_init_accepts_hurwitz_gains(void)
{
    ASSERT_STATUS(TVO_OK, init_with(1, 2, 0.5, 0, 0));
    ASSERT_STATUS(TVO_OK, init_with(2, 2, 40, 13, 0));
    ASSERT_STATUS(TVO_OK, init_with(3, 2, 4.096, 7.68, 4.8));
    ASSERT_STATUS(TVO_OK, init_with(3, 2, 10, 2, 5.5)); /* a2 a1 = 11 > 10 */
    ASSERT_STATUS(TVO_OK, init_with(2, TVO_MAX_OUTPUT_DIM, 1, 1, 0));
}

static void test_init_rejects_non_hurwitz_k1(void)
{
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(1, 2, 0, 0, 0));
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(1, 2, -1, 0, 0));
}

static void test_init_rejects_non_hurwitz_k2(void)
{
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, 0, 13, 0));  /* kp = 0: marginal */
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, 40, 0, 0));  /* kd = 0: oscillator */
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, -40, 13, 0));
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, 40, -13, 0));
}

static void test_init_rejects_non_hurwitz_k3(void)
{
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 10, 2, 5));   /* a2 a1 = a0: poles on the imaginary axis */
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 10, 2, 4));   /* a2 a1 < a0: unstable */
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 1, -1, 5));   /* a negative coefficient */
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 0, 7.68, 4.8));
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 4.096, 7.68, 0));
}

static void test_init_rejects_non_finite_gains(void)
{
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, (double)NAN, 13, 0));
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(2, 2, 40, (double)INFINITY, 0));
    ASSERT_STATUS(TVO_ERR_PARAM, init_with(3, 2, 4.096, (double)NAN, 4.8));
}

/* Roots within R = pi / h bound a_j by C(k, j) R^(k-j): each coefficient of each order just inside its
 * bound passes (the others at (s + R/2)^k's), just beyond it fails; NaN, k and h out of range fail. */
static void test_sampling_reach_bounds_each_coefficient(void)
{
    const double h = 0.01;
    const double reach = TEST_PI / h;
    const double binomial[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 2, 0}, {1, 3, 3}};
    for (uint8_t k = 1; k <= TVO_MAX_RELATIVE_DEGREE; ++k) {
        for (uint8_t j = 0; j < k; ++j) {
            tvo_real_t gain[TVO_MAX_RELATIVE_DEGREE];
            for (uint8_t i = 0; i < k; ++i) {
                gain[i] = test_r(binomial[k][i] * pow(0.5 * reach, (double)(k - i)));
            }
            const double bound = binomial[k][j] * pow(reach, (double)(k - j));
            gain[j] = test_r(0.999 * bound);
            ASSERT_STATUS(TVO_OK, tvo_law_check_sampling_reach(k, gain, test_r(h)));
            gain[j] = test_r(1.001 * bound);
            ASSERT_STATUS(TVO_ERR_PARAM, tvo_law_check_sampling_reach(k, gain, test_r(h)));
            gain[j] = TEST_NAN;
            ASSERT_STATUS(TVO_ERR_PARAM, tvo_law_check_sampling_reach(k, gain, test_r(h)));
        }
    }
}




int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_k2_tracking_law_is_the_pd_chain);
    RUN_TEST(test_k2_hand_value_at_t0);
    RUN_TEST(test_k1_tracking_law_is_gradient_flow_with_feedforward);
    RUN_TEST(test_k3_tracking_law_is_the_third_order_chain);
    RUN_TEST(test_k2_two_robots_are_decoupled);
    RUN_TEST(test_k2_custom_quartic_term_matches_hand_newton_step);
    RUN_TEST(test_k2_custom_term_closed_loop_identity);
    RUN_TEST(test_indefinite_hessian_is_regularized_by_the_ladder);
    RUN_TEST(test_singular_hessian_is_regularized_minimally);
    RUN_TEST(test_positive_definite_hessian_is_not_regularized);
    RUN_TEST(test_non_finite_gradient_is_reported_and_output_zeroed);
    RUN_TEST(test_term_error_is_propagated_and_output_zeroed);
    RUN_TEST(test_non_finite_state_is_rejected);
    RUN_TEST(test_objective_dimension_must_match_the_law);
    RUN_TEST(test_identical_inputs_give_bit_identical_outputs);
    RUN_TEST(test_init_accepts_hurwitz_gains);
    RUN_TEST(test_init_rejects_non_hurwitz_k1);
    RUN_TEST(test_init_rejects_non_hurwitz_k2);
    RUN_TEST(test_init_rejects_non_hurwitz_k3);
    RUN_TEST(test_sampling_reach_bounds_each_coefficient);
    RUN_TEST(test_init_rejects_non_finite_gains);
    return UNITY_END();
}
