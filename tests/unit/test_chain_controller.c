/*
 * The sampled-data chain controller (tvo/chain_controller.h) of the integrator-chain testbed
 * y^(k) = u, y in R^2, k = 1..3, and the lifted closed-loop matrix the study tool (host/study) uses
 * for its exact stability edges.
 *
 * Target: the polynomial y_d(t) = (0.3 + 0.5t - 0.4t^2 + 0.2t^3,  -0.7 + 0.1t + 0.6t^2 - 0.1t^3), so
 *   y_d'   = (0.5 - 0.8t + 0.6t^2,   0.1 + 1.2t - 0.3t^2)
 *   y_d''  = (-0.8 + 1.2t,           1.2 - 0.6t)
 *   y_d''' = (1.2,                   -0.6)
 * For f0 = 1/2 |y - y_d|^2 the law is u = y_d^(k)(t) - sum_i a_i (y^(i) - y_d^(i)(t)) (paper,
 * eq. "chain_testbed"); tests compare the controller with that closed form computed in double.
 *
 * The plant here is double precision and exact (its own Taylor flow, not tvo_chain_predict), the
 * controller runs in tvo_real_t (float32 by default), so tolerances are a multiple of TEST_EPS.
 */
#include "test_support.h"

#include <float.h>

#include "tvo/chain_controller.h"
#include "internal/chain_controller.h"

void setUp(void) {}
void tearDown(void) {}

#define CH_TICK_HZ 1000000u
#define CH_EPOCH 5000000u

/* ------------------------------------------------------------------------------------------------
 * Fixture
 * --------------------------------------------------------------------------------------------- */

typedef struct {
    tvo_target_t target;
    tvo_tracking_term_t term;
    tvo_objective_t objective;
    tvo_chain_config_t cfg;
    tvo_chain_controller_t ctl;
    double x[2][3]; /* plant at the last apply tick: y, y', y'' per axis */
    double u[2];    /* command in force */
    uint32_t apply; /* apply tick of the next step */
    uint32_t steps;
} ch_t;

/* Gains of (s + 1.6)^k. */
static void ch_gains(uint8_t k, double a[3])
{
    a[0] = a[1] = a[2] = 0.0;
    if (k == 1u) {
        a[0] = 1.6;
    } else if (k == 2u) {
        a[0] = 2.56;
        a[1] = 3.2;
    } else {
        a[0] = 4.096;
        a[1] = 7.68;
        a[2] = 4.8;
    }
}

/* y_d^(j)(t), j = 0..3, by hand (see the header comment). */
static void ch_yd(double t, double yd[4][2])
{
    yd[0][0] = 0.3 + 0.5 * t - 0.4 * t * t + 0.2 * t * t * t;
    yd[0][1] = -0.7 + 0.1 * t + 0.6 * t * t - 0.1 * t * t * t;
    yd[1][0] = 0.5 - 0.8 * t + 0.6 * t * t;
    yd[1][1] = 0.1 + 1.2 * t - 0.3 * t * t;
    yd[2][0] = -0.8 + 1.2 * t;
    yd[2][1] = 1.2 - 0.6 * t;
    yd[3][0] = 1.2;
    yd[3][1] = -0.6;
}

/* The plant's exact flow over dt with u held (double, written out per k). */
static void plant_flow(uint8_t k, const double x[3], double u, double dt, double out[3])
{
    double r[3] = {0.0, 0.0, 0.0};
    if (k == 1u) {
        r[0] = x[0] + u * dt;
    } else if (k == 2u) {
        r[0] = x[0] + x[1] * dt + u * dt * dt / 2.0;
        r[1] = x[1] + u * dt;
    } else {
        r[0] = x[0] + x[1] * dt + x[2] * dt * dt / 2.0 + u * dt * dt * dt / 6.0;
        r[1] = x[1] + x[2] * dt + u * dt * dt / 2.0;
        r[2] = x[2] + u * dt;
    }
    out[0] = r[0];
    out[1] = r[1];
    out[2] = r[2];
}

/* The law's closed form at time t for state x (per axis). */
static double closed_form_law(uint8_t k, const double a[3], const double x[3], double t, int axis)
{
    double yd[4][2];
    ch_yd(t, yd);
    double u = yd[k][axis];
    for (uint8_t i = 0; i < k; ++i) {
        u -= a[i] * (x[i] - yd[i][axis]);
    }
    return u;
}

static void ch_config(ch_t *ch, uint8_t k, uint32_t period, uint32_t delay, uint8_t comp, uint8_t zoh)
{
    ASSERT_STATUS(TVO_OK, tvo_chain_config_default(&ch->cfg));
    ch->cfg.tick_hz = CH_TICK_HZ;
    ch->cfg.period_ticks = period;
    ch->cfg.delay_ticks = delay;
    ch->cfg.relative_degree = k;
    ch->cfg.delay_compensation = comp;
    ch->cfg.zoh_aware = zoh;
    ch->cfg.filtered_derivatives = 0;
    double a[3];
    ch_gains(k, a);
    for (uint8_t i = 0; i < TVO_MAX_RELATIVE_DEGREE; ++i) {
        ch->cfg.gain[i] = test_r(a[i]);
    }
    ch->cfg.input_max = TVO_R(1e6);
    ch->cfg.watchdog_periods = 3u;
}

/* Objective + controller; plant at rest at y = (2, 0) (k-1 derivatives zero); first apply = epoch. */
static tvo_status_t ch_init(ch_t *ch)
{
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    c[0][0] = TVO_R(0.3);
    c[0][1] = TVO_R(0.5);
    c[0][2] = TVO_R(-0.4);
    c[0][3] = TVO_R(0.2);
    c[1][0] = TVO_R(-0.7);
    c[1][1] = TVO_R(0.1);
    c[1][2] = TVO_R(0.6);
    c[1][3] = TVO_R(-0.1);
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(&ch->target, TEST_CONST_POLY(c)));
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_tracking_init(&ch->term, &ch->target, w, 0));
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&ch->objective, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&ch->objective, tvo_tracking_gradient_jet, &ch->term));
    memset(ch->x, 0, sizeof(ch->x));
    ch->x[0][0] = 2.0;
    ch->u[0] = ch->u[1] = 0.0;
    ch->apply = CH_EPOCH;
    ch->steps = 0;
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_OBJECTIVE; /* anything but NONE: init must write it */
    const tvo_status_t st = tvo_chain_controller_init(&ch->ctl, &ch->cfg, &ch->objective, CH_EPOCH, &bad);
    ASSERT_CHAIN_PARAM(st == TVO_OK ? TVO_CHAIN_PARAM_NONE : bad, bad);
    return st;
}

static double ticks_s(uint32_t ticks)
{
    return (double)ticks / (double)CH_TICK_HZ;
}

/* The plant sampled at apply - delay (state x_s), as the measurement the controller receives. */
static void ch_sample(const ch_t *ch, double xs[2][3], tvo_chain_measurement_t *m)
{
    const uint8_t k = ch->cfg.relative_degree;
    const double h = ticks_s(ch->cfg.period_ticks), tau = ticks_s(ch->cfg.delay_ticks);
    for (int i = 0; i < 2; ++i) {
        /* before the first apply the plant rests (u = 0, derivatives 0): the flow keeps it */
        plant_flow(k, ch->x[i], ch->u[i], ch->steps == 0u ? 0.0 : h - tau, xs[i]);
    }
    memset(m, 0, sizeof(*m));
    m->stamp_tick = ch->apply - ch->cfg.delay_ticks;
    for (uint8_t j = 0; j < k; ++j) {
        m->y.d[j][0] = test_r(xs[0][j]);
        m->y.d[j][1] = test_r(xs[1][j]);
    }
}

/* One closed-loop period: sample, step, move the plant to the apply tick, switch the command. */
static tvo_status_t ch_step(ch_t *ch, tvo_chain_command_t *cmd)
{
    const uint8_t k = ch->cfg.relative_degree;
    double xs[2][3];
    tvo_chain_measurement_t m;
    ch_sample(ch, xs, &m);
    const tvo_status_t st = tvo_chain_controller_step(&ch->ctl, &m, ch->apply, cmd);
    for (int i = 0; i < 2; ++i) {
        if (ch->steps > 0u) {
            plant_flow(k, ch->x[i], ch->u[i], ticks_s(ch->cfg.period_ticks), ch->x[i]);
        }
        ch->u[i] = test_d(cmd->u[i]);
    }
    ch->apply += ch->cfg.period_ticks;
    ch->steps++;
    return st;
}

/* ------------------------------------------------------------------------------------------------
 * tvo_chain_predict: hand-derived values
 * --------------------------------------------------------------------------------------------- */

/* state (1, 2, -4) per axis 0 and (-1, 0.5, 3) per axis 1; u = (8, -2); dt = 0.5. */
static void predict_fixture(tvo_output_derivs_t *s, tvo_real_t u[2])
{
    memset(s, 0, sizeof(*s));
    s->d[0][0] = TVO_R(1.0);
    s->d[1][0] = TVO_R(2.0);
    s->d[2][0] = TVO_R(-4.0);
    s->d[0][1] = TVO_R(-1.0);
    s->d[1][1] = TVO_R(0.5);
    s->d[2][1] = TVO_R(3.0);
    u[0] = TVO_R(8.0);
    u[1] = TVO_R(-2.0);
}

static void test_predict_k1_hand_values(void)
{
    tvo_output_derivs_t s, out;
    tvo_real_t u[2];
    predict_fixture(&s, u);
    ASSERT_STATUS(TVO_OK, tvo_chain_predict(1, 2, &s, u, TVO_R(0.5), &out));
    /* y + u dt */
    ASSERT_ULPS(1.0 + 8.0 * 0.5, out.d[0][0], 4);
    ASSERT_ULPS(-1.0 - 2.0 * 0.5, out.d[0][1], 4);
}

static void test_predict_k2_hand_values(void)
{
    tvo_output_derivs_t s, out;
    tvo_real_t u[2];
    predict_fixture(&s, u);
    ASSERT_STATUS(TVO_OK, tvo_chain_predict(2, 2, &s, u, TVO_R(0.5), &out));
    /* y + y' dt + u dt^2/2 = 1 + 1 + 1 = 3;  y' + u dt = 2 + 4 = 6 */
    ASSERT_ULPS(3.0, out.d[0][0], 4);
    ASSERT_ULPS(6.0, out.d[1][0], 4);
    /* -1 + 0.25 - 0.25 = -1;  0.5 - 1 = -0.5 */
    ASSERT_ULPS(-1.0, out.d[0][1], 4);
    ASSERT_ULPS(-0.5, out.d[1][1], 4);
}

static void test_predict_k3_hand_values_in_place(void)
{
    tvo_output_derivs_t s;
    tvo_real_t u[2];
    predict_fixture(&s, u);
    /* aliasing: out == state */
    ASSERT_STATUS(TVO_OK, tvo_chain_predict(3, 2, &s, u, TVO_R(0.5), &s));
    /* axis 0: y = 1 + 2(0.5) - 4(0.125) + 8(0.125)/6 = 1.5 + 1/6;  y' = 2 - 2 + 8(0.125) = 1;  y'' = -4 + 4 = 0 */
    ASSERT_ULPS(1.5 + 1.0 / 6.0, s.d[0][0], 8);
    ASSERT_ULPS(1.0, s.d[1][0], 8);
    ASSERT_NEAR(0.0, s.d[2][0], TEST_TOL(8, 4.0));
    /* axis 1: y = -1 + 0.25 + 3(0.125) - 2(0.125)/6 = -0.375 - 1/24;  y' = 0.5 + 1.5 - 0.25 = 1.75;  y'' = 3 - 1 = 2 */
    ASSERT_ULPS(-0.375 - 1.0 / 24.0, s.d[0][1], 8);
    ASSERT_ULPS(1.75, s.d[1][1], 8);
    ASSERT_ULPS(2.0, s.d[2][1], 8);
}

static void test_predict_rejects_bad_arguments(void)
{
    tvo_output_derivs_t s, out;
    tvo_real_t u[2];
    predict_fixture(&s, u);
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_predict(2, 2, NULL, u, TVO_R(0.1), &out));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_predict(2, 2, &s, NULL, TVO_R(0.1), &out));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_predict(2, 2, &s, u, TVO_R(0.1), NULL));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_chain_predict(0, 2, &s, u, TVO_R(0.1), &out));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_chain_predict(TVO_MAX_RELATIVE_DEGREE + 1, 2, &s, u, TVO_R(0.1), &out));
    ASSERT_STATUS(TVO_ERR_DIMENSION, tvo_chain_predict(2, 0, &s, u, TVO_R(0.1), &out));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_predict(2, 2, &s, u, TVO_R(-0.1), &out));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_predict(2, 2, &s, u, TEST_NAN, &out));
    /* dt = 0 is the identity */
    ASSERT_STATUS(TVO_OK, tvo_chain_predict(3, 2, &s, u, TVO_R(0.0), &out));
    TEST_ASSERT_EQUAL_MEMORY(&s.d[0][0], &out.d[0][0], sizeof(tvo_real_t));
    TEST_ASSERT_EQUAL_MEMORY(&s.d[2][1], &out.d[2][1], sizeof(tvo_real_t));
}

/* ------------------------------------------------------------------------------------------------
 * One step against the closed form of the law, k = 1, 2, 3
 * --------------------------------------------------------------------------------------------- */

/* u is O(10) here (gains up to 7.7 times errors O(2)); the law runs a few dozen float operations. */
#define LAW_TOL TEST_TOL(64, 30.0)

static void check_one_step_closed_form(uint8_t k)
{
    ch_t ch;
    ch_config(&ch, k, 10000u, 0u, 0u, 0u);
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    /* A non-trivial state: y = (2, 0) plus derivatives (0.7, -1.1) and (0.4, 0.9), at t = 0.35 s. */
    tvo_chain_measurement_t m;
    memset(&m, 0, sizeof(m));
    const double x[2][3] = {{2.0, 0.7, 0.4}, {0.0, -1.1, 0.9}};
    for (uint8_t j = 0; j < k; ++j) {
        m.y.d[j][0] = test_r(x[0][j]);
        m.y.d[j][1] = test_r(x[1][j]);
    }
    const uint32_t apply = CH_EPOCH + 350000u;
    m.stamp_tick = apply;
    tvo_chain_command_t cmd;
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, apply, &cmd), cmd);
    double a[3];
    ch_gains(k, a);
    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(closed_form_law(k, a, x[i], 0.35, i), cmd.u[i], LAW_TOL);
    }
    TEST_ASSERT_EQUAL_HEX32(0u, cmd.flags);
}

static void test_one_step_matches_closed_form_k1(void)
{
    check_one_step_closed_form(1);
}

static void test_one_step_matches_closed_form_k2(void)
{
    check_one_step_closed_form(2);
}

static void test_one_step_matches_closed_form_k3(void)
{
    check_one_step_closed_form(3);
}

/* Uncompensated with a delay: the law is evaluated at the sample instant, with the sampled state. */
static void test_uncompensated_delay_evaluates_at_the_sample_instant(void)
{
    ch_t ch;
    ch_config(&ch, 2, 10000u, 4000u, 0u, 0u);
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    tvo_chain_command_t cmd;
    double a[3];
    ch_gains(2, a);
    for (int n = 0; n < 5; ++n) {
        const uint32_t apply = ch.apply;
        double xs[2][3];
        tvo_chain_measurement_t m;
        ch_sample(&ch, xs, &m);
        ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
        const double t_sample = ticks_s(apply - CH_EPOCH) - 0.004;
        for (int i = 0; i < 2; ++i) {
            ASSERT_NEAR(closed_form_law(2, a, xs[i], t_sample < 0.0 ? 0.0 : t_sample, i), cmd.u[i], LAW_TOL);
        }
    }
}

/* ------------------------------------------------------------------------------------------------
 * Compensation and the ZOH-aware evaluation instant
 * --------------------------------------------------------------------------------------------- */

/*
 * Compensated tau = h on the exact plant commands what tau = 0 commands: the prediction over the
 * measurement's age with the held command is exact for the chain. The two runs differ only by the
 * float32 prediction's rounding (state O(3), one Taylor step: ~1e-6 seen with float32), held to
 * 128 eps (1.5e-5 in float32), far below the >= 0.07 gap an uncompensated tau = h run shows (checked
 * too, so the comparison can fail).
 */
static void test_compensation_makes_tau_h_equal_tau_0(void)
{
    for (uint8_t k = 1; k <= 3; ++k) {
        ch_t ref, comp, raw;
        ch_config(&ref, k, 20000u, 0u, 0u, 0u);
        ch_config(&comp, k, 20000u, 20000u, 1u, 0u);
        ch_config(&raw, k, 20000u, 20000u, 0u, 0u);
        ASSERT_STATUS(TVO_OK, ch_init(&ref));
        ASSERT_STATUS(TVO_OK, ch_init(&comp));
        ASSERT_STATUS(TVO_OK, ch_init(&raw));
        double worst_comp = 0.0, worst_raw = 0.0;
        for (int n = 0; n < 8; ++n) {
            tvo_chain_command_t c0, c1, c2;
            ASSERT_PERIOD(APPLIED, ch_step(&ref, &c0), c0);
            ASSERT_PERIOD(APPLIED, ch_step(&comp, &c1), c1);
            ASSERT_PERIOD(APPLIED, ch_step(&raw, &c2), c2);
            if (n > 0) {
                ASSERT_FLAG_SET(c1.flags, TVO_FLAG_PREDICTED);
            }
            ASSERT_FLAG_CLEAR(c2.flags, TVO_FLAG_PREDICTED);
            for (int i = 0; i < 2; ++i) {
                worst_comp = fmax(worst_comp, fabs(test_d(c1.u[i]) - test_d(c0.u[i])));
                worst_raw = fmax(worst_raw, fabs(test_d(c2.u[i]) - test_d(c0.u[i])));
            }
        }
        ASSERT_LE(worst_comp, TEST_TOL(64, 1.0), "compensated tau = h vs tau = 0");
        ASSERT_LE(1e-2, worst_raw, "uncompensated tau = h must differ from tau = 0");
    }
}

/* ZOH-aware: state carried by h/2 (plus the age when compensated) with the held command; law at apply + h/2. */
static void check_zoh_instant(uint8_t k, uint32_t delay, uint8_t comp)
{
    ch_t ch;
    ch_config(&ch, k, 20000u, delay, comp, 1u);
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    double a[3];
    ch_gains(k, a);
    const double h = 0.02, tau = ticks_s(delay);
    for (int n = 0; n < 6; ++n) {
        const uint32_t apply = ch.apply;
        const double held[2] = {ch.u[0], ch.u[1]};
        double xs[2][3];
        tvo_chain_measurement_t m;
        ch_sample(&ch, xs, &m);
        tvo_chain_command_t cmd;
        ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
        ASSERT_FLAG_SET(cmd.flags, TVO_FLAG_PREDICTED);
        const double carry = (comp ? tau : 0.0) + h / 2.0;
        const double t_law = ticks_s(apply - CH_EPOCH) - (comp ? 0.0 : tau) + h / 2.0;
        for (int i = 0; i < 2; ++i) {
            double xc[3];
            plant_flow(k, xs[i], held[i], carry, xc);
            ASSERT_NEAR(closed_form_law(k, a, xc, t_law, i), cmd.u[i], LAW_TOL);
        }
    }
}

static void test_zoh_aware_evaluates_at_the_middle_of_the_held_interval(void)
{
    for (uint8_t k = 1; k <= 3; ++k) {
        check_zoh_instant(k, 0u, 0u);
        check_zoh_instant(k, 10000u, 1u);
        check_zoh_instant(k, 20000u, 1u);
    }
}

/* ------------------------------------------------------------------------------------------------
 * Dirty-derivative filters
 * --------------------------------------------------------------------------------------------- */

/*
 * Filters start at rest: the first step sees y' = 0 (and y'' = 0) whatever the measurement carries;
 * the second step's y' is the ramp-invariant update (1 - a)(y1 - y0)/dt, a = exp(-dt/T_f), and (k = 3)
 * y'' is the same update applied to the first filter's outputs (0 -> y'_1).
 */
static void test_filters_start_at_rest_and_follow_the_ramp_update(void)
{
    for (uint8_t k = 2; k <= 3; ++k) {
        ch_t ch;
        ch_config(&ch, k, 10000u, 0u, 0u, 0u);
        ch.cfg.filtered_derivatives = 1u;
        ch.cfg.filter_tf_s = TVO_R(0.05);
        ASSERT_STATUS(TVO_OK, ch_init(&ch));
        double a[3];
        ch_gains(k, a);
        tvo_chain_measurement_t m;
        memset(&m, 0, sizeof(m));
        m.y.d[0][0] = TVO_R(2.0);
        m.y.d[0][1] = TVO_R(0.5);
        m.y.d[1][0] = TEST_NAN; /* not read when filtered */
        m.y.d[2][1] = TEST_NAN;
        m.stamp_tick = CH_EPOCH + 100000u;
        tvo_chain_command_t cmd;
        ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, CH_EPOCH + 100000u, &cmd), cmd);
        const double x0[2][3] = {{2.0, 0.0, 0.0}, {0.5, 0.0, 0.0}};
        for (int i = 0; i < 2; ++i) {
            ASSERT_NEAR(closed_form_law(k, a, x0[i], 0.1, i), cmd.u[i], LAW_TOL);
        }
        /* second sample 10 ms later */
        m.y.d[0][0] = TVO_R(2.01);
        m.y.d[0][1] = TVO_R(0.48);
        m.stamp_tick = CH_EPOCH + 110000u;
        ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, CH_EPOCH + 110000u, &cmd), cmd);
        const double dec = exp(-0.01 / 0.05), g = (1.0 - dec) / 0.01;
        for (int i = 0; i < 2; ++i) {
            const double y1 = test_d(m.y.d[0][i]);
            double x1[3];
            x1[0] = y1;
            x1[1] = g * (y1 - x0[i][0]);
            x1[2] = g * (x1[1] - 0.0);
            /* the filter gain (1 - a)/dt ~ 18 amplifies the float rounding of y (O(2)): scale 40 */
            ASSERT_NEAR(closed_form_law(k, a, x1, 0.11, i), cmd.u[i], TEST_TOL(256, 40.0));
        }
    }
}

/* ------------------------------------------------------------------------------------------------
 * Rejections, holding and the watchdog
 * --------------------------------------------------------------------------------------------- */

static void test_init_names_the_first_bad_parameter(void)
{
    ch_t ch;
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_NONE;
    ch_config(&ch, 2, 10000u, 20000u, 1u, 0u);
    ASSERT_STATUS(TVO_ERR_PARAM, ch_init(&ch));
    (void)tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad);
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_DELAY, bad);
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.relative_degree = 4u;
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_RELATIVE_DEGREE, bad);
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.gain[1] = TVO_R(-1.0); /* s^2 - s + 2.56: not Hurwitz */
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_GAIN, bad);
    /* Beyond the sampling's reach (h = 10 ms: a_1 <= 2 pi / h = 628.3), and a gain that would overflow. */
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.gain[1] = TVO_R(629.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_GAIN, bad);
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.gain[0] = TVO_R(3e38);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_GAIN, bad);
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.gain[1] = TVO_R(628.0); /* just inside; s^2 + 628 s + 2.56 is Hurwitz */
    ASSERT_STATUS(TVO_OK, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ch_config(&ch, 2, 10000u, 0u, 0u, 0u);
    ch.cfg.filtered_derivatives = 1u;
    ch.cfg.filter_tf_s = TVO_R(0.0);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_FILTER_TF, bad);
    ch_config(&ch, 2, 0u, 0u, 0u, 0u);
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    ASSERT_CHAIN_PARAM(TVO_CHAIN_PARAM_PERIOD, bad);
    /* a failed init leaves an instance that refuses to step, with a safe command */
    tvo_chain_command_t cmd;
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_chain_controller_step(&ch.ctl, NULL, CH_EPOCH, &cmd));
    ASSERT_OUTCOME(TVO_OUTCOME_STOPPED, cmd);
}

static void test_bad_measurements_hold_the_command_then_the_watchdog_stops(void)
{
    ch_t ch;
    ch_config(&ch, 2, 10000u, 5000u, 1u, 0u);
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    tvo_chain_command_t good, cmd;
    ASSERT_PERIOD(APPLIED, ch_step(&ch, &good), good);
    ASSERT_PERIOD(APPLIED, ch_step(&ch, &good), good);
    tvo_chain_measurement_t m;
    double xs[2][3];

    /* NaN position: held (watchdog 3 periods: 1 missed) */
    ch_sample(&ch, xs, &m);
    m.y.d[0][1] = TEST_NAN;
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_HELD, cmd);
    TEST_ASSERT_EQUAL_MEMORY(good.u, cmd.u, sizeof(cmd.u));
    ch.apply += ch.cfg.period_ticks;

    /* NaN in a measured derivative (not filtered: it is read) */
    ch_sample(&ch, xs, &m);
    m.y.d[1][0] = TEST_INF;
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    TEST_ASSERT_EQUAL_MEMORY(good.u, cmd.u, sizeof(cmd.u));
    ch.apply += ch.cfg.period_ticks;

    /* a good one (stamped at the apply tick itself: age 0) restarts the watchdog */
    ch_sample(&ch, xs, &m);
    m.stamp_tick = ch.apply;
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &good), good);
    const uint32_t last_stamp = m.stamp_tick;
    ch.apply += ch.cfg.period_ticks;

    /* not newer than the last accepted (age h: not stale), stale (older than one period), future */
    m.stamp_tick = last_stamp;
    ASSERT_PERIOD(HELD(STAMP_NOT_NEWER), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_HELD, cmd);
    TEST_ASSERT_EQUAL_MEMORY(good.u, cmd.u, sizeof(cmd.u));
    ch.apply += ch.cfg.period_ticks;
    m.stamp_tick = ch.apply - ch.cfg.period_ticks - 1u;
    ASSERT_PERIOD(HELD(STALE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_HELD, cmd);
    TEST_ASSERT_EQUAL_MEMORY(good.u, cmd.u, sizeof(cmd.u));
    ch.apply += ch.cfg.period_ticks;
    /* third missed period in a row (a future stamp): the watchdog expires -> zero command, safe stop */
    m.stamp_tick = ch.apply + 1u;
    ASSERT_PERIOD(STOPPED(WATCHDOG), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_STOPPED, cmd);
    ASSERT_NEAR(0.0, cmd.u[0], 0.0);
    ASSERT_NEAR(0.0, cmd.u[1], 0.0);
    ch.apply += ch.cfg.period_ticks;
    ASSERT_PERIOD(STOPPED(WATCHDOG), tvo_chain_controller_step(&ch.ctl, NULL, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_STOPPED, cmd);

    /* a future stamp before the watchdog expires is its own status */
    {
        ch_t f;
        ch_config(&f, 2, 10000u, 0u, 0u, 0u);
        ASSERT_STATUS(TVO_OK, ch_init(&f));
        tvo_chain_command_t fc;
        ASSERT_PERIOD(APPLIED, ch_step(&f, &fc), fc);
        ch_sample(&f, xs, &m);
        m.stamp_tick = f.apply + 1u;
        ASSERT_PERIOD(HELD(FUTURE_STAMP), tvo_chain_controller_step(&f.ctl, &m, f.apply, &cmd), cmd);
        ASSERT_OUTCOME(TVO_OUTCOME_HELD, cmd);
        TEST_ASSERT_EQUAL_MEMORY(fc.u, cmd.u, sizeof(cmd.u));
    }

    /* an apply tick that does not advance: a call error, the command in force */
    ASSERT_PERIOD(CALL_ERROR(TVO_ERR_TICK_NOT_ADVANCING), tvo_chain_controller_step(&ch.ctl, NULL, ch.apply, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_HELD, cmd);
    ch.apply += ch.cfg.period_ticks;

    /* measurements resume: a fresh, newer stamp is accepted again */
    memset(&m, 0, sizeof(m));
    m.y.d[0][0] = TVO_R(1.0);
    m.stamp_tick = ch.apply - ch.cfg.delay_ticks;
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ASSERT_NOT_OUTCOME(TVO_OUTCOME_STOPPED, cmd);
    TEST_ASSERT_TRUE(test_is_finite(cmd.u[0]) && test_is_finite(cmd.u[1]));
}

/* ------------------------------------------------------------------------------------------------
 * The lifted closed-loop matrix (the same construction as host/study/src/lifted.cpp)
 * --------------------------------------------------------------------------------------------- */

#define LMAX (TVO_MAX_RELATIVE_DEGREE + 1)

/* A(dt): x <- sum_{m>=j} x_m dt^(m-j)/(m-j)!;  B(dt): dt^(k-j)/(k-j)! */
static void flow_matrices(uint8_t k, double dt, double A[3][3], double B[3])
{
    memset(A, 0, 9 * sizeof(double));
    for (uint8_t j = 0; j < k; ++j) {
        double f = 1.0;
        for (uint8_t m = j; m < k; ++m) {
            A[j][m] = f;
            f *= dt / (double)(m - j + 1u);
        }
        B[j] = f;
    }
}

/*
 * z = [x; u] per axis; M = [[A(h), B(h)], [-a^T A(c) A(h - tau), -a^T (A(c) B(h - tau) + B(c))]],
 * c = (comp ? tau : 0) + (zoh ? h/2 : 0).
 */
static void lifted_matrix(uint8_t k, const double a[3], double h, double tau, int comp, int zoh, double M[LMAX][LMAX])
{
    double Ah[3][3], Bh[3], As[3][3], Bs[3], Ac[3][3], Bc[3];
    const double c = (comp ? tau : 0.0) + (zoh ? 0.5 * h : 0.0);
    flow_matrices(k, h, Ah, Bh);
    flow_matrices(k, h - tau, As, Bs);
    flow_matrices(k, c, Ac, Bc);
    memset(M, 0, sizeof(double) * LMAX * LMAX);
    for (uint8_t r = 0; r < k; ++r) {
        for (uint8_t col = 0; col < k; ++col) {
            M[r][col] = Ah[r][col];
        }
        M[r][k] = Bh[r];
    }
    for (uint8_t col = 0; col < k; ++col) {
        double s = 0.0;
        for (uint8_t i = 0; i < k; ++i) {
            double acas = 0.0; /* (A(c) A(h - tau))[i][col] */
            for (uint8_t j = 0; j < k; ++j) {
                acas += Ac[i][j] * As[j][col];
            }
            s += a[i] * acas;
        }
        M[k][col] = -s;
    }
    double s = 0.0;
    for (uint8_t i = 0; i < k; ++i) {
        double v = Bc[i];
        for (uint8_t j = 0; j < k; ++j) {
            v += Ac[i][j] * Bs[j];
        }
        s += a[i] * v;
    }
    M[k][k] = -s;
}

/* d^j/dt^j of sum_m p[m] t^m (m <= 3). */
static double poly_deriv(const double p[4], uint8_t j, double t)
{
    double v = 0.0;
    for (uint8_t m = j; m <= 3u; ++m) {
        double f = 1.0; /* m! / (m - j)! */
        for (uint8_t q = 0; q < j; ++q) {
            f *= (double)(m - q);
        }
        v += p[m] * f * pow(t, (double)(m - j));
    }
    return v;
}

/* Error state of axis i at the last apply tick: [e, e', .., e^(k-1); u - y_d^(k)] for target p. */
static void error_state(const ch_t *ch, double p[2][4], int axis, double z[LMAX])
{
    const uint8_t k = ch->cfg.relative_degree;
    const double t = ticks_s(ch->apply - ch->cfg.period_ticks - CH_EPOCH);
    for (uint8_t j = 0; j < k; ++j) {
        z[j] = ch->x[axis][j] - poly_deriv(p[axis], j, t);
    }
    z[k] = ch->u[axis] - poly_deriv(p[axis], k, t);
}

/*
 * With a target whose k-th derivative is constant (polynomial of degree k) the error dynamics are
 * exactly the homogeneous lifted system, so M^j z_1 must reproduce z_{1+j} of controller + plant.
 * Deviations come only from the controller's tvo_real_t arithmetic (the plant rows are exact double):
 * each command carries the rounding of its inputs (|y| <= 3, times gains <= 7.7: a few ulps of ~20),
 * and M's iterates stay O(1) (the loop is stable at h = 50 ms), so 8 steps stay within 256 eps
 * (3e-5 in float32; ~1.2e-6 is what float32 gives). A matrix with the wrong timing (tau = 0 for a
 * delayed loop, h/2 for tau = 0, half the compensation's carry) misses by more than 1e-2
 * (asserted, so the check has teeth; >= 0.048 seen).
 */
static void check_lifted(uint8_t k, uint32_t delay, uint8_t comp, uint8_t zoh)
{
    const uint32_t period = 50000u;
    const double h = ticks_s(period), tau = ticks_s(delay);
    const double tol = 256.0 * TEST_EPS;
    double a[3];
    ch_gains(k, a);
    /* the target's k-th derivative must be constant: keep only degree <= k terms */
    ch_t ch;
    ch_config(&ch, k, period, delay, comp, zoh);
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    tvo_real_t c[2][TVO_POLY_MAX_DEGREE + 1];
    memset(c, 0, sizeof(c));
    const double full[2][4] = {{0.3, 0.5, -0.4, 0.2}, {-0.7, 0.1, 0.6, -0.1}};
    double p[2][4] = {{0.0, 0.0, 0.0, 0.0}, {0.0, 0.0, 0.0, 0.0}};
    for (int i = 0; i < 2; ++i) {
        for (uint8_t j = 0; j <= k; ++j) {
            c[i][j] = test_r(full[i][j]);
            p[i][j] = test_d(c[i][j]); /* the float coefficients the firmware sees */
        }
    }
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(&ch.target, TEST_CONST_POLY(c)));
    double M[LMAX][LMAX], Mwrong[LMAX][LMAX];
    lifted_matrix(k, a, h, tau, comp, zoh, M);
    lifted_matrix(k, a, h, comp ? 0.5 * tau : (tau > 0.0 ? 0.0 : 0.5 * h), 0, zoh, Mwrong);

    tvo_chain_command_t cmd;
    ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd); /* step 0: from rest (not the lifted recursion yet) */
    ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
    double z[2][LMAX], zw[2][LMAX];
    for (int i = 0; i < 2; ++i) {
        error_state(&ch, p, i, z[i]);
        memcpy(zw[i], z[i], sizeof(z[i]));
    }
    double worst = 0.0, worst_wrong = 0.0;
    for (int n = 0; n < 8; ++n) {
        ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
        for (int i = 0; i < 2; ++i) {
            double next[LMAX] = {0}, next_w[LMAX] = {0}, sim[LMAX];
            for (uint8_t r = 0; r <= k; ++r) {
                for (uint8_t col = 0; col <= k; ++col) {
                    next[r] += M[r][col] * z[i][col];
                    next_w[r] += Mwrong[r][col] * zw[i][col];
                }
            }
            memcpy(z[i], next, sizeof(next));
            memcpy(zw[i], next_w, sizeof(next_w));
            error_state(&ch, p, i, sim);
            for (uint8_t r = 0; r <= k; ++r) {
                worst = fmax(worst, fabs(sim[r] - z[i][r]));
                worst_wrong = fmax(worst_wrong, fabs(sim[r] - zw[i][r]));
            }
        }
    }
    char what[96];
    (void)snprintf(what, sizeof(what), "lifted vs simulated, k=%u tau=%u comp=%u zoh=%u", (unsigned)k, (unsigned)delay,
                   (unsigned)comp, (unsigned)zoh);
    ASSERT_LE(worst, tol, what);
    (void)snprintf(what, sizeof(what), "wrong-timing matrix must miss, k=%u tau=%u comp=%u zoh=%u", (unsigned)k,
                   (unsigned)delay, (unsigned)comp, (unsigned)zoh);
    ASSERT_LE(1e-2, worst_wrong, what);
}

static void test_lifted_matrix_reproduces_the_closed_loop(void)
{
    for (uint8_t k = 1; k <= 3; ++k) {
        check_lifted(k, 0u, 0u, 0u);
        check_lifted(k, 25000u, 0u, 0u);
        check_lifted(k, 50000u, 0u, 0u);
        check_lifted(k, 50000u, 1u, 0u);
        check_lifted(k, 0u, 0u, 1u);
        check_lifted(k, 25000u, 1u, 1u);
    }
}

/* ------------------------------------------------------------------------------------------------
 * For the edge (issue 9): check, safe stop, refusals that leave no trace
 * --------------------------------------------------------------------------------------------- */

/* k = 3 with dirty-derivative filters (the state a refusal must not touch), after `steps` periods. */
static void ch_filtered_running(ch_t *ch, uint32_t steps)
{
    ch_config(ch, 3, 10000u, 5000u, 1u, 0u);
    ch->cfg.filtered_derivatives = 1u;
    ch->cfg.watchdog_periods = 5u;
    ASSERT_STATUS(TVO_OK, ch_init(ch));
    tvo_chain_command_t cmd;
    for (uint32_t i = 0; i < steps; ++i) {
        ASSERT_PERIOD(APPLIED, ch_step(ch, &cmd), cmd);
    }
}

static tvo_chain_controller_t ch_before;
static tvo_chain_controller_t ch_copy;

static void test_chain_check_changes_nothing_and_says_what_the_step_would(void)
{
    for (int filtered = 0; filtered < 2; ++filtered) {
        ch_t ch;
        ch_filtered_running(&ch, 8u);
        ch.ctl.cfg.filtered_derivatives = (uint8_t)filtered; /* measured derivatives are read: NaN counts */
        double xs[2][3];
        tvo_chain_measurement_t good;
        ch_sample(&ch, xs, &good);
        struct {
            tvo_chain_measurement_t m;
            uint32_t apply;
            int null_meas;
            test_period_t expected;
        } cases[8];
        size_t n = 0;
        cases[n].m = good, cases[n].apply = ch.apply, cases[n].null_meas = 0, cases[n++].expected = APPLIED;
        cases[n].m = good, cases[n].m.y.d[0][1] = TEST_NAN, cases[n].apply = ch.apply, cases[n].null_meas = 0;
        cases[n++].expected = HELD(NOT_FINITE);
        cases[n].m = good, cases[n].m.y.d[2][0] = TEST_INF, cases[n].apply = ch.apply, cases[n].null_meas = 0;
        cases[n++].expected = filtered ? APPLIED : HELD(NOT_FINITE); /* y'' is read only when measured */
        cases[n].m = good, cases[n].m.stamp_tick = ch.apply - ch.cfg.period_ticks - 1u, cases[n].apply = ch.apply;
        cases[n].null_meas = 0, cases[n++].expected = HELD(STALE);
        cases[n].m = good, cases[n].m.stamp_tick = ch.apply + 1u, cases[n].apply = ch.apply;
        cases[n].null_meas = 0, cases[n++].expected = HELD(FUTURE_STAMP);
        cases[n].m = good, cases[n].apply = ch.apply - ch.cfg.period_ticks, cases[n].null_meas = 0;
        cases[n++].expected = CALL_ERROR(TVO_ERR_TICK_NOT_ADVANCING);
        cases[n].m = good, cases[n].apply = ch.apply, cases[n].null_meas = 1;
        cases[n++].expected = HELD(NO_MEASUREMENT);
        for (size_t i = 0; i < n; ++i) {
            const tvo_chain_measurement_t *m = cases[i].null_meas ? NULL : &cases[i].m;
            memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
            tvo_reason_t reason = TVO_REASON_COUNT;
            ASSERT_STATUS(cases[i].expected.status, tvo_chain_controller_check(&ch.ctl, m, cases[i].apply, &reason));
            if (cases[i].expected.status == TVO_OK) {
                TEST_ASSERT_EQUAL_INT(cases[i].expected.reason, reason);
            }
            TEST_ASSERT_EQUAL_MEMORY(&ch_before, &ch.ctl, sizeof(ch_before));
            memcpy(&ch_copy, &ch.ctl, sizeof(ch_copy));
            tvo_chain_command_t cmd;
            ASSERT_PERIOD(cases[i].expected, tvo_chain_controller_step(&ch_copy, m, cases[i].apply, &cmd), cmd);
        }
    }
    tvo_reason_t reason = TVO_REASON_NONE;
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_controller_check(NULL, NULL, 0u, &reason));
    tvo_chain_controller_t blank;
    memset(&blank, 0, sizeof(blank));
    tvo_chain_measurement_t m;
    memset(&m, 0, sizeof(m));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_chain_controller_check(&blank, &m, CH_EPOCH, &reason));
}

static void test_chain_safe_stop_drops_to_rest_without_advancing_the_clock(void)
{
    ch_t ch;
    ch_filtered_running(&ch, 8u);
    TEST_ASSERT_TRUE(ch.ctl.internal.held.u[0] != TVO_R(0.0));
    const tvo_sample_clock_t clock_before = ch.ctl.internal.loop.clock;
    tvo_chain_command_t cmd;
    memset(&cmd, 0x5A, sizeof(cmd));
    ASSERT_PERIOD(STOPPED(STOP_REQUESTED), tvo_chain_controller_safe_stop(&ch.ctl, &cmd), cmd);
    TEST_ASSERT_EQUAL_HEX32(0u, cmd.flags);
    for (int i = 0; i < TVO_MAX_OUTPUT_DIM; ++i) {
        ASSERT_NEAR(0.0, cmd.u[i], 0.0);
        ASSERT_NEAR(0.0, ch.ctl.internal.held.u[i], 0.0);
    }
    TEST_ASSERT_EQUAL_UINT8(1u, ch.ctl.internal.loop.clock.stopped);
    TEST_ASSERT_EQUAL_UINT32(ch.cfg.watchdog_periods, ch.ctl.internal.loop.clock.periods_without_measurement);
    TEST_ASSERT_EQUAL_HEX32(clock_before.last_apply_tick, ch.ctl.internal.loop.clock.last_apply_tick);
    TEST_ASSERT_EQUAL_UINT64(clock_before.elapsed.ticks, ch.ctl.internal.loop.clock.elapsed.ticks);
    /* The plant applies the stop; the next measurement is accepted, the filters restart at rest. */
    ch.u[0] = ch.u[1] = 0.0;
    ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
    ASSERT_OUTCOME(TVO_OUTCOME_APPLIED, cmd);
    TEST_ASSERT_EQUAL_UINT8(0u, ch.ctl.internal.loop.clock.stopped);
    for (int i = 0; i < 2; ++i) {
        ASSERT_NEAR(0.0, ch.ctl.internal.filter[0].output[i], 0.0);
    }
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_controller_safe_stop(&ch.ctl, NULL));
    memset(&cmd, 0x5A, sizeof(cmd));
    ASSERT_STATUS(TVO_ERR_NULL, tvo_chain_controller_safe_stop(NULL, &cmd));
    TEST_ASSERT_EQUAL_HEX32(0u, cmd.flags);
    ASSERT_OUTCOME(TVO_OUTCOME_STOPPED, cmd);
    tvo_chain_controller_t blank;
    memset(&blank, 0, sizeof(blank));
    ASSERT_STATUS(TVO_ERR_NOT_INITIALIZED, tvo_chain_controller_safe_stop(&blank, &cmd));
    ASSERT_NEAR(0.0, cmd.u[0], 0.0);
}

/* The chain's caller refusals, as the unicycle's (the same loop): held and nothing changed on a clock
 * with a timer; the watchdog_periods-th in a row stops a clock that counts refusals. */
static void test_chain_callers_refusals_hold_or_stop_as_the_clock_counts(void)
{
    ch_t ch;
    ch_filtered_running(&ch, 8u);
    tvo_chain_command_t cmd;
    tvo_chain_controller_t before;
    memcpy(&before, &ch.ctl, sizeof(before));
    for (uint32_t i = 0; i < 2u * ch.cfg.watchdog_periods; ++i) {
        ASSERT_PERIOD(HELD(REFUSED), tvo_chain_controller_refuse(&ch.ctl, TVO_REASON_REFUSED, &cmd), cmd);
        ASSERT_NEAR(test_d(before.internal.held.u[0]), cmd.u[0], 0.0);
    }
    memset(&before.internal.work, 0, sizeof(before.internal.work));
    memset(&ch.ctl.internal.work, 0, sizeof(ch.ctl.internal.work));
    TEST_ASSERT_EQUAL_MEMORY(&before, &ch.ctl, sizeof(before));
    ASSERT_STATUS(TVO_ERR_PARAM, tvo_chain_controller_refuse(&ch.ctl, TVO_REASON_WATCHDOG, &cmd));
    ch.ctl.internal.loop.clock.counts_refusals = 1u; /* as init sets it from watchdog_counts_refusals */
    for (uint32_t i = 1; i < ch.cfg.watchdog_periods; ++i) {
        ASSERT_PERIOD(HELD(REFUSED), tvo_chain_controller_refuse(&ch.ctl, TVO_REASON_REFUSED, &cmd), cmd);
    }
    ASSERT_PERIOD(STOPPED(WATCHDOG), tvo_chain_controller_refuse(&ch.ctl, TVO_REASON_REFUSED, &cmd), cmd);
    ASSERT_NEAR(0.0, cmd.u[0], 0.0);
    ASSERT_NEAR(0.0, ch.ctl.internal.held.u[0], 0.0);
}

/* The filters, the held command and the last stamp: what a refused step must not touch. */
static void assert_chain_untouched(const tvo_chain_controller_t *before, const tvo_chain_controller_t *after)
{
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(before->internal.filter, after->internal.filter, sizeof(after->internal.filter), "filters");
    TEST_ASSERT_EQUAL_MEMORY_MESSAGE(before->internal.held.u, after->internal.held.u, sizeof(after->internal.held.u), "held command");
    TEST_ASSERT_EQUAL_HEX32_MESSAGE(before->internal.loop.clock.last_stamp_tick, after->internal.loop.clock.last_stamp_tick, "last stamp");
    TEST_ASSERT_EQUAL_UINT8_MESSAGE(before->internal.loop.clock.has_stamp, after->internal.loop.clock.has_stamp, "has stamp");
}

static void test_chain_refused_measurement_leaves_filters_and_stamp_untouched(void)
{
    ch_t ch;
    ch_filtered_running(&ch, 8u);
    TEST_ASSERT_EQUAL_UINT8(1u, ch.ctl.internal.filter[0].primed);
    double xs[2][3];
    tvo_chain_measurement_t m;
    tvo_chain_command_t cmd;
    const test_period_t why[] = {HELD(STALE), HELD(FUTURE_STAMP)};
    for (int i = 0; i < 2; ++i) {
        ch_sample(&ch, xs, &m);
        m.y.d[0][0] += TVO_R(0.25); /* a jump the filters would follow if they saw it */
        m.stamp_tick = (i == 0) ? ch.apply - ch.cfg.period_ticks - 1u : ch.apply + 1u;
        memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
        ASSERT_PERIOD(why[i], tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
        assert_chain_untouched(&ch_before, &ch.ctl);
        ch.apply += ch.cfg.period_ticks;
    }
    ch_sample(&ch, xs, &m);
    m.y.d[0][1] = TEST_NAN;
    memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    assert_chain_untouched(&ch_before, &ch.ctl);
}

/* Issue 39: a position outside the workspace (tvo/config.h: |y| <= TVO_POSITION_LIMIT_M per axis for
 * every accepted measurement) is refused as the unicycle's is, IMPLAUSIBLE_MEASUREMENT, and nothing of
 * it is kept: the next good sample gets the command a controller that never saw it computes. */
static void test_chain_position_outside_the_workspace_is_implausible_and_keeps_nothing(void)
{
    const double limit = (double)TVO_POSITION_LIMIT_M_VALUE;
    const double bad[] = {limit + 1.0, -(limit + 1.0), 3.4e38, -3.4e38};
    for (int filtered = 0; filtered < 2; ++filtered) {
        for (size_t b = 0; b < sizeof(bad) / sizeof(bad[0]); ++b) {
            ch_t ch;
            ch_filtered_running(&ch, 8u);
            ch.ctl.cfg.filtered_derivatives = (uint8_t)filtered;
            memcpy(&ch_copy, &ch.ctl, sizeof(ch_copy)); /* never sees the bad sample */
            double xs[2][3];
            tvo_chain_measurement_t m;
            ch_sample(&ch, xs, &m);
            m.y.d[0][b % 2u] = test_r(bad[b]);
            tvo_reason_t reason = TVO_REASON_NONE;
            ASSERT_STATUS(TVO_OK, tvo_chain_controller_check(&ch.ctl, &m, ch.apply, &reason));
            TEST_ASSERT_EQUAL_INT(TVO_REASON_IMPLAUSIBLE_MEASUREMENT, reason);
            memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
            tvo_chain_command_t cmd;
            ASSERT_PERIOD(HELD(IMPLAUSIBLE_MEASUREMENT), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
            TEST_ASSERT_EQUAL_MEMORY(ch_before.internal.held.u, cmd.u, sizeof(cmd.u)); /* the command in force */
            assert_chain_untouched(&ch_before, &ch.ctl);
            /* The next period's good sample: the same command, bit for bit, as without the bad one. */
            ch.apply += ch.cfg.period_ticks;
            ch_sample(&ch, xs, &m);
            tvo_chain_command_t reference;
            ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch_copy, &m, ch.apply, &reference), reference);
            ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
            TEST_ASSERT_EQUAL_MEMORY(reference.u, cmd.u, sizeof(cmd.u));
            TEST_ASSERT_EQUAL_HEX32(reference.flags, cmd.flags);
        }
    }
}

/* Issue 39: a value the step computed from finite inputs that came out NaN or infinite is a numerical
 * failure (TVO_REASON_NUMERIC, wire status 8), not a measured one (TVO_REASON_NOT_FINITE, status 2).
 * Measured y' and y'' at the type's largest finite value (finite: the check passes them; the chain
 * bounds no derivative) are carried over the delay, which takes y' past it. */
static void test_chain_computed_overflow_is_numeric_and_a_measured_nan_is_not_finite(void)
{
#if TVO_USE_DOUBLE
    const tvo_real_t largest = DBL_MAX;
#else
    const tvo_real_t largest = FLT_MAX;
#endif
    ch_t ch;
    ch_config(&ch, 3, 10000u, 5000u, 1u, 0u); /* derivatives measured, the delay compensated */
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    tvo_chain_command_t cmd;
    for (int i = 0; i < 3; ++i) {
        ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
    }
    double xs[2][3];
    tvo_chain_measurement_t m;
    ch_sample(&ch, xs, &m);
    m.y.d[1][0] = largest;
    m.y.d[2][0] = largest;
    tvo_reason_t reason = TVO_REASON_COUNT;
    ASSERT_STATUS(TVO_OK, tvo_chain_controller_check(&ch.ctl, &m, ch.apply, &reason));
    TEST_ASSERT_EQUAL_INT(TVO_REASON_NONE, reason); /* every input finite */
    memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
    ASSERT_PERIOD(HELD(NUMERIC), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    assert_chain_untouched(&ch_before, &ch.ctl);
    /* The same period measured NaN (y) or infinite (y'): the measurement's reason. */
    ch_sample(&ch, xs, &m);
    m.y.d[0][1] = TEST_NAN;
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    ch_sample(&ch, xs, &m);
    m.y.d[1][0] = TEST_INF;
    ASSERT_PERIOD(HELD(NOT_FINITE), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
    assert_chain_untouched(&ch_before, &ch.ctl);
    /* ... and the period's good sample is served. */
    ch_sample(&ch, xs, &m);
    ASSERT_PERIOD(APPLIED, tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd);
}

static void test_chain_law_failure_after_the_filters_leaves_them_untouched(void)
{
    /* A streamed target in place of the polynomial: the filters step (their working copies), then
     * the period is refused because the latest target sample is stamped after the law's time (the
     * loop's check before the law). */
    ch_t ch;
    ch_config(&ch, 3, 10000u, 5000u, 1u, 0u);
    ch.cfg.filtered_derivatives = 1u;
    ch.cfg.watchdog_periods = 5u;
    ASSERT_STATUS(TVO_OK, ch_init(&ch));
    tvo_real_t sample[TVO_STREAM_MAX_DERIV + 1][2];
    memset(sample, 0, sizeof(sample));
    sample[0][0] = TVO_R(0.3);
    sample[1][1] = TVO_R(0.2);
    ASSERT_STATUS(TVO_OK, tvo_target_init_streamed(&ch.target));
    /* The objective notes a streamed target as its term is added: built again, then the controller. */
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&ch.objective, 2));
    ASSERT_STATUS(TVO_OK, tvo_objective_add_term(&ch.objective, tvo_tracking_gradient_jet, &ch.term));
    tvo_chain_param_t bad = TVO_CHAIN_PARAM_NONE;
    ASSERT_STATUS(TVO_OK, tvo_chain_controller_init(&ch.ctl, &ch.cfg, &ch.objective, CH_EPOCH, &bad));
    tvo_chain_command_t cmd;
    {
        /* No sample yet: the loop holds the command in force (its check before the law), nothing kept. */
        double xs0[2][3];
        tvo_chain_measurement_t m0;
        ch_sample(&ch, xs0, &m0);
        memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
        ASSERT_PERIOD(HELD(TARGET_NOT_READY), tvo_chain_controller_step(&ch.ctl, &m0, ch.apply, &cmd), cmd);
        TEST_ASSERT_EQUAL_MEMORY(ch_before.internal.held.u, cmd.u, sizeof(cmd.u));
        assert_chain_untouched(&ch_before, &ch.ctl);
    }
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&ch.target, 0u, TEST_CONST_STREAM(sample)));
    for (int i = 0; i < 8; ++i) {
        ASSERT_PERIOD(APPLIED, ch_step(&ch, &cmd), cmd);
    }
    TEST_ASSERT_EQUAL_UINT8(1u, ch.ctl.internal.filter[1].primed);
    ASSERT_STATUS(TVO_OK, tvo_target_stream_update(&ch.target, 1000000u, TEST_CONST_STREAM(sample)));
    double xs[2][3];
    tvo_chain_measurement_t m;
    ch_sample(&ch, xs, &m);
    m.y.d[0][0] += TVO_R(0.1);
    ASSERT_CHECK_USES(tvo_chain_controller_check, &ch.ctl, &m, ch.apply);
    memcpy(&ch_before, &ch.ctl, sizeof(ch_before));
    ASSERT_PERIOD(HELD(FUTURE_STAMP), tvo_chain_controller_step(&ch.ctl, &m, ch.apply, &cmd), cmd); /* the target's */
    assert_chain_untouched(&ch_before, &ch.ctl);
}

int main(void)
{
    UNITY_BEGIN();
    RUN_TEST(test_predict_k1_hand_values);
    RUN_TEST(test_predict_k2_hand_values);
    RUN_TEST(test_predict_k3_hand_values_in_place);
    RUN_TEST(test_predict_rejects_bad_arguments);
    RUN_TEST(test_one_step_matches_closed_form_k1);
    RUN_TEST(test_one_step_matches_closed_form_k2);
    RUN_TEST(test_one_step_matches_closed_form_k3);
    RUN_TEST(test_uncompensated_delay_evaluates_at_the_sample_instant);
    RUN_TEST(test_compensation_makes_tau_h_equal_tau_0);
    RUN_TEST(test_zoh_aware_evaluates_at_the_middle_of_the_held_interval);
    RUN_TEST(test_filters_start_at_rest_and_follow_the_ramp_update);
    RUN_TEST(test_init_names_the_first_bad_parameter);
    RUN_TEST(test_bad_measurements_hold_the_command_then_the_watchdog_stops);
    RUN_TEST(test_chain_callers_refusals_hold_or_stop_as_the_clock_counts);
    RUN_TEST(test_lifted_matrix_reproduces_the_closed_loop);
    RUN_TEST(test_chain_check_changes_nothing_and_says_what_the_step_would);
    RUN_TEST(test_chain_safe_stop_drops_to_rest_without_advancing_the_clock);
    RUN_TEST(test_chain_refused_measurement_leaves_filters_and_stamp_untouched);
    RUN_TEST(test_chain_law_failure_after_the_filters_leaves_them_untouched);
    RUN_TEST(test_chain_position_outside_the_workspace_is_implausible_and_keeps_nothing);
    RUN_TEST(test_chain_computed_overflow_is_numeric_and_a_measured_nan_is_not_finite);
    return UNITY_END();
}
