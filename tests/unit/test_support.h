/*
 * Shared helpers of the unit tests: tolerances that follow tvo_real_t, assertion shorthands, and a
 * controller + objective fixture with a unicycle plant simulated by tvo_unicycle_predict.
 *
 * Header-only (static functions), so each test executable stays a single translation unit plus
 * Unity and tvo_core.
 */
#ifndef TVO_TEST_SUPPORT_H
#define TVO_TEST_SUPPORT_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>

#include "unity.h"

#include "tvo/config.h"
#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/objective.h"
#include "tvo/status.h"
#include "tvo/target.h"
#include "tvo/tracking.h"
#include "tvo/unicycle.h"
#include "internal/objective.h"
#include "internal/target.h"
#include "internal/unicycle.h"

/* ------------------------------------------------------------------------------------------------
 * Precision
 * --------------------------------------------------------------------------------------------- */

/** Machine epsilon of tvo_real_t, as a double. */
#define TEST_EPS ((double)TVO_EPSILON)

/** A tolerance "n ulps of magnitude scale" for a computation of a few operations in tvo_real_t. */
#define TEST_TOL(n_eps, scale) ((double)(n_eps) * TEST_EPS * (1.0 + fabs((double)(scale))))

/** Converts a double (closed forms are computed in double) to the core's scalar. */
static inline tvo_real_t test_r(double x)
{
    return (tvo_real_t)x;
}

/** The double value of a tvo_real_t (exactly representable). */
static inline double test_d(tvo_real_t x)
{
    return (double)x;
}

#define TEST_PI 3.14159265358979323846

/* Non-finite values of the core's scalar (NAN and INFINITY are float constants). */
#define TEST_NAN ((tvo_real_t)NAN)
#define TEST_INF ((tvo_real_t)INFINITY)

/*
 * C11 does not convert T (*)[n] to const T (*)[n] implicitly (-Wpedantic flags it), so passing a
 * mutable 2-D array to a `const tvo_real_t x[2][n]` parameter needs these casts.
 */
#define TEST_CONST_POLY(a) ((const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])(a))
#define TEST_CONST_STREAM(a) ((const tvo_real_t(*)[2])(a))

/* ------------------------------------------------------------------------------------------------
 * Assertions
 * --------------------------------------------------------------------------------------------- */

/** |actual - expected| <= tol, with actual of any real type. */
#define ASSERT_NEAR(expected, actual, tol) \
    TEST_ASSERT_DOUBLE_WITHIN((double)(tol), (double)(expected), (double)(actual))
#define ASSERT_NEAR_MSG(expected, actual, tol, msg) \
    TEST_ASSERT_DOUBLE_WITHIN_MESSAGE((double)(tol), (double)(expected), (double)(actual), (msg))

/** Relative-plus-absolute: |actual - expected| <= n_eps * eps * (1 + |expected|). */
#define ASSERT_ULPS(expected, actual, n_eps) ASSERT_NEAR((expected), (actual), TEST_TOL((n_eps), (expected)))

/* Status / parameter equality whose failure message names both values. */
static inline void test_assert_status(tvo_status_t expected, tvo_status_t actual, int line)
{
    if (expected != actual) {
        static char msg[200];
        (void)snprintf(msg, sizeof(msg), "expected status %d (%s), got %d (%s)", (int)expected,
                       tvo_status_str(expected), (int)actual, tvo_status_str(actual));
        UNITY_TEST_FAIL(line, msg);
    }
}
static inline void test_assert_param(tvo_param_t expected, tvo_param_t actual, int line)
{
    if (expected != actual) {
        static char msg[200];
        (void)snprintf(msg, sizeof(msg), "expected bad_param %d (%s), got %d (%s)", (int)expected,
                       tvo_param_str(expected), (int)actual, tvo_param_str(actual));
        UNITY_TEST_FAIL(line, msg);
    }
}
/* A period's answer as the tests state it: the call's status, and (TVO_OK) the command's outcome and reason. */
typedef struct {
    tvo_status_t status;
    tvo_outcome_t outcome;
    tvo_reason_t reason;
} test_period_t;
#define APPLIED ((test_period_t){TVO_OK, TVO_OUTCOME_APPLIED, TVO_REASON_NONE})
#define HELD(why) ((test_period_t){TVO_OK, TVO_OUTCOME_HELD, TVO_REASON_##why})
#define STOPPED(why) ((test_period_t){TVO_OK, TVO_OUTCOME_STOPPED, TVO_REASON_##why})
/* A call error: nothing changed; the command (held, reason NONE) is the one in force. */
#define CALL_ERROR(error) ((test_period_t){(error), TVO_OUTCOME_HELD, TVO_REASON_NONE})

static inline void test_assert_period(test_period_t expected, tvo_status_t status, unsigned outcome, unsigned reason,
                                      int line)
{
    if (expected.status != status || (unsigned)expected.outcome != outcome || (unsigned)expected.reason != reason) {
        static char msg[300];
        (void)snprintf(msg, sizeof(msg), "expected %s, %s (%s), got %s, %s (%s)", tvo_status_str(expected.status),
                       tvo_outcome_str(expected.outcome), tvo_reason_str(expected.reason), tvo_status_str(status),
                       tvo_outcome_str((tvo_outcome_t)outcome), tvo_reason_str((tvo_reason_t)reason));
        UNITY_TEST_FAIL(line, msg);
    }
}
/** The call (a step, a miss, a safe stop) returns expected.status and leaves cmd (a command, not a pointer)
 *  with expected's outcome and reason. */
#define ASSERT_PERIOD(expected, call, cmd)                                                            \
    do {                                                                                              \
        const tvo_status_t period_status_ = (call);                                                   \
        test_assert_period((expected), period_status_, (cmd).outcome, (cmd).reason, __LINE__);        \
    } while (0)
/** A controller's check (check_fn, e.g. tvo_controller_check) says the step would use the measurement:
 *  TVO_OK, TVO_REASON_NONE. */
#define ASSERT_CHECK_USES(check_fn, ctl, meas, apply)                            \
    do {                                                                         \
        tvo_reason_t check_reason_ = TVO_REASON_COUNT;                           \
        ASSERT_STATUS(TVO_OK, check_fn((ctl), (meas), (apply), &check_reason_)); \
        TEST_ASSERT_EQUAL_INT(TVO_REASON_NONE, check_reason_);                   \
    } while (0)
/** The command's outcome (any reason). */
#define ASSERT_OUTCOME(expected, cmd) \
    TEST_ASSERT_EQUAL_INT_MESSAGE((int)(expected), (int)(cmd).outcome, "outcome should be " #expected)
#define ASSERT_NOT_OUTCOME(unexpected, cmd) \
    TEST_ASSERT_NOT_EQUAL_INT_MESSAGE((int)(unexpected), (int)(cmd).outcome, "outcome should not be " #unexpected)


static inline void test_assert_chain_param(tvo_chain_param_t expected, tvo_chain_param_t actual, int line)
{
    if (expected != actual) {
        static char msg[200];
        (void)snprintf(msg, sizeof(msg), "expected bad_param %d (%s), got %d (%s)", (int)expected,
                       tvo_chain_param_str(expected), (int)actual, tvo_chain_param_str(actual));
        UNITY_TEST_FAIL(line, msg);
    }
}
#define ASSERT_CHAIN_PARAM(expected, actual) test_assert_chain_param((expected), (actual), __LINE__)
/* a <= b (+ slack), with both values in the failure message. */
static inline void test_assert_le(double a, double b, const char *what, int line)
{
    if (!(a <= b)) {
        static char msg[200];
        (void)snprintf(msg, sizeof(msg), "%s: %.9g is not <= %.9g", what, a, b);
        UNITY_TEST_FAIL(line, msg);
    }
}
#define ASSERT_STATUS(expected, actual) test_assert_status((expected), (actual), __LINE__)
#define ASSERT_PARAM(expected, actual) test_assert_param((expected), (actual), __LINE__)
#define ASSERT_LE(a, b, what) test_assert_le((double)(a), (double)(b), (what), __LINE__)

#define ASSERT_FLAG_SET(flags, flag) TEST_ASSERT_BITS_HIGH_MESSAGE((flag), (flags), #flag " should be set")
#define ASSERT_FLAG_CLEAR(flags, flag) TEST_ASSERT_BITS_LOW_MESSAGE((flag), (flags), #flag " should be clear")

static inline int test_is_finite(tvo_real_t x)
{
    return isfinite(x) ? 1 : 0;
}

/* ------------------------------------------------------------------------------------------------
 * Controller fixture: N robots, each tracking its own target with W = I (unless changed).
 * --------------------------------------------------------------------------------------------- */

/** Fixture timing: microsecond ticks, h = 10 ms, tau = 5 ms (the paper's defaults, tau = h / 2). */
#define FX_TICK_HZ 1000000u
#define FX_PERIOD 10000u
#define FX_DELAY 5000u

typedef struct {
    tvo_target_t target[TVO_MAX_ROBOTS];
    tvo_tracking_term_t term[TVO_MAX_ROBOTS];
    tvo_objective_t objective;
    tvo_controller_config_t cfg;
    tvo_controller_t ctl;
    tvo_param_t bad_param;
    uint32_t epoch;
    uint32_t apply;                    /* apply tick of the next step */
    tvo_pose_t pose[TVO_MAX_ROBOTS];   /* plant pose at the last apply tick */
    tvo_command_t cmd;                 /* command in force on the plant */
    uint32_t steps;                    /* closed-loop steps taken */
    uint8_t meas_mode;                 /* FX_MEAS_*: what the next closed-loop step delivers */
    uint8_t heading_first_only;        /* 1: heading_valid only on the first measurement */
} fx_t;

#define FX_MEAS_NORMAL 0u
#define FX_MEAS_NONE 1u    /* no measurement arrives (NULL) */
#define FX_MEAS_NAN 2u     /* a measurement with a NaN position */

/** A complete, valid configuration for n robots (values spelled out, not the defaults). */
static inline void fx_config(tvo_controller_config_t *cfg, uint8_t robots)
{
    memset(cfg, 0, sizeof(*cfg));
    cfg->tick_hz = FX_TICK_HZ;
    cfg->period_ticks = FX_PERIOD;
    cfg->delay_ticks = FX_DELAY;
    cfg->robot_count = robots;
    cfg->delay_compensation = 1;
    cfg->velocity_source = TVO_VELOCITY_FROM_POSE;
    cfg->filter_tf_s = TVO_R(0.02);
    cfg->gain_kp = TVO_R(40.0);
    cfg->gain_kd = TVO_R(13.0);
    cfg->omega_max_radps = test_r(2.0 * TEST_PI);
    cfg->accel_max_mps2 = TVO_R(15.0);
    cfg->speed_max_mps = TVO_R(2.0);
    cfg->min_speed_mps = TVO_R(0.05);
    cfg->watchdog_periods = 5;
    for (int i = 0; i < TVO_MAX_ROBOTS; ++i) {
        cfg->initial_speed_mps[i] = TVO_R(0.0);
    }
}

/** Polynomial target y_d(t) = (x0 + vx t, y0 + vy t). */
static inline void fx_line_target(tvo_target_t *target, double x0, double y0, double vx, double vy)
{
    tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
    memset(coeff, 0, sizeof(coeff));
    coeff[0][0] = test_r(x0);
    coeff[0][1] = test_r(vx);
    coeff[1][0] = test_r(y0);
    coeff[1][1] = test_r(vy);
    ASSERT_STATUS(TVO_OK, tvo_target_init_polynomial(target, TEST_CONST_POLY(coeff)));
}

/** The paper's circle: centre c, radius r, rate w (y_d = c + r (cos wt, sin wt)). */
static inline void fx_circle_target(tvo_target_t *target, double cx, double cy, double r, double w)
{
    const tvo_real_t c[2] = {test_r(cx), test_r(cy)};
    ASSERT_STATUS(TVO_OK, tvo_target_init_circle(target, c, test_r(r), test_r(w), TVO_R(0.0)));
}

/**
 * Builds the objective over the targets already in fx->target[0..robots-1] (W = I) and initialises
 * the controller with fx->cfg (which the caller may have edited after fx_config) at epoch.
 * The plant starts at the given poses; the first apply tick is epoch + h.
 */
static inline tvo_status_t fx_init_controller(fx_t *fx, uint32_t epoch)
{
    const uint8_t n = fx->cfg.robot_count;
    const tvo_real_t w[2] = {TVO_R(1.0), TVO_R(1.0)};
    ASSERT_STATUS(TVO_OK, tvo_objective_init(&fx->objective, (uint8_t)(2u * n)));
    for (uint8_t i = 0; i < n; ++i) {
        ASSERT_STATUS(TVO_OK, tvo_tracking_init(&fx->term[i], &fx->target[i], w, (uint8_t)(2u * i)));
        ASSERT_STATUS(TVO_OK,
                              tvo_objective_add_term(&fx->objective, tvo_tracking_gradient_jet, &fx->term[i]));
    }
    fx->epoch = epoch;
    fx->apply = epoch + fx->cfg.period_ticks;
    fx->bad_param = TVO_PARAM_INITIAL_SPEED; /* anything but NONE: init must write it */
    memset(&fx->cmd, 0, sizeof(fx->cmd));
    return tvo_controller_init(&fx->ctl, &fx->cfg, &fx->objective, epoch, &fx->bad_param);
}

/** Zeroes the fixture and sets a valid config for `robots` robots. */
static inline void fx_reset(fx_t *fx, uint8_t robots)
{
    memset(fx, 0, sizeof(*fx));
    fx_config(&fx->cfg, robots);
}

/** A measurement of the given poses stamped at stamp (heading valid, speed not). */
static inline void fx_measure(const fx_t *fx, const tvo_pose_t *poses, uint32_t stamp, tvo_measurement_t *m)
{
    memset(m, 0, sizeof(*m));
    m->stamp_tick = stamp;
    for (uint8_t i = 0; i < fx->cfg.robot_count; ++i) {
        m->position_m[i][0] = poses[i].position_m[0];
        m->position_m[i][1] = poses[i].position_m[1];
        m->heading_rad[i] = poses[i].heading_rad;
        m->speed_mps[i] = TVO_R(0.0);
    }
    m->heading_valid = 1;
    m->speed_valid = 0;
}

static inline void fx_predict_all(const fx_t *fx, const tvo_command_t *cmd, const tvo_pose_t *from,
                                  uint32_t ticks, tvo_pose_t *to)
{
    const tvo_real_t dt = test_r((double)ticks / (double)fx->cfg.tick_hz);
    for (uint8_t i = 0; i < fx->cfg.robot_count; ++i) {
        tvo_unicycle_predict(&from[i], cmd->speed_mps[i], cmd->turn_rate_radps[i],
                                                           dt, &to[i]);
    }
}

/**
 * A time jet at t_s (kept as given: finite differences step below a tick) whose exact tick count
 * and its split into whole seconds are `ticks` at tick_hz (the split the ellipse's phase reads).
 */
static inline tvo_time_jet_t test_time_jet(tvo_real_t t_s, tvo_real_t rate, uint32_t tick_hz, uint64_t ticks)
{
    tvo_time_jet_t t;
    if (tvo_time_jet_at_ticks(ticks, tick_hz, rate, &t) != TVO_OK) {
        t.ticks = ticks;
        t.tick_hz = tick_hz;
        t.rate = rate;
        t.whole_s = 0u;
        t.frac_ticks = 0u;
        t.frac_s = TVO_R(0.0);
        t.shared = NULL;
    }
    t.t_s = t_s;
    return t;
}

/** Target position y_d(t) of robot r, for tracking-error checks. */
static inline void fx_target_position(const fx_t *fx, uint8_t r, double t_s, double out[2])
{
    tvo_time_jet_t t = test_time_jet(test_r(t_s), TVO_R(1.0), fx->cfg.tick_hz, (uint64_t)llround(t_s * (double)fx->cfg.tick_hz));
    tvo_real_t d[TVO_JET_MAX_ORDER + 1][2];
    ASSERT_STATUS(TVO_OK, tvo_target_derivatives(&fx->target[r], &t, 0, d));
    out[0] = test_d(d[0][0]);
    out[1] = test_d(d[0][1]);
}

/** Objective time (s) of the plant at the last apply tick (fx->apply has moved on by h). */
static inline double fx_time_of_last_apply(const fx_t *fx)
{
    return (double)(uint32_t)(fx->apply - fx->cfg.period_ticks - fx->epoch) / (double)fx->cfg.tick_hz;
}

/** Distance of robot r (plant, at the last apply tick) from its target there. */
static inline double fx_tracking_error(const fx_t *fx, uint8_t r)
{
    double yd[2];
    fx_target_position(fx, r, fx_time_of_last_apply(fx), yd);
    return hypot(test_d(fx->pose[r].position_m[0]) - yd[0], test_d(fx->pose[r].position_m[1]) - yd[1]);
}

/**
 * One closed-loop period on the simulated plant. On entry fx->pose is the plant at the previous
 * apply tick, with fx->cmd in force since then. The plant moves to the sampling instant
 * (apply - delay), is measured there, the controller computes the command for fx->apply, and the
 * plant moves on to fx->apply under the old command, where the new one takes over.
 */
static inline tvo_status_t fx_closed_loop_step(fx_t *fx, tvo_command_t *out)
{
    const uint32_t delay = fx->cfg.delay_ticks;
    const uint32_t h = fx->cfg.period_ticks;
    tvo_pose_t at_sample[TVO_MAX_ROBOTS];
    tvo_measurement_t m;
    tvo_command_t cmd;
    fx_predict_all(fx, &fx->cmd, fx->pose, h - delay, at_sample);
    uint32_t sample_tick = 0;
    ASSERT_STATUS(TVO_OK, tvo_controller_sample_tick(&fx->ctl, fx->apply, &sample_tick));
    fx_measure(fx, at_sample, sample_tick, &m);
    if (fx->heading_first_only && fx->steps > 0u) {
        m.heading_valid = 0;
    }
    if (fx->meas_mode == FX_MEAS_NAN) {
        m.position_m[0][0] = TEST_NAN;
    }
    const tvo_status_t st =
        tvo_controller_step(&fx->ctl, fx->meas_mode == FX_MEAS_NONE ? NULL : &m, fx->apply, &cmd);
    fx_predict_all(fx, &fx->cmd, at_sample, delay, fx->pose);
    fx->cmd = cmd;
    fx->apply += h;
    fx->steps++;
    if (out != NULL) {
        *out = cmd;
    }
    return st;
}

/** Field-wise bit equality of two commands (memcmp of a whole struct would compare padding). */
static inline void assert_commands_bit_identical(const tvo_command_t *a, const tvo_command_t *b)
{
    TEST_ASSERT_EQUAL_MEMORY(a->speed_mps, b->speed_mps, sizeof(a->speed_mps));
    TEST_ASSERT_EQUAL_MEMORY(a->turn_rate_radps, b->turn_rate_radps, sizeof(a->turn_rate_radps));
    TEST_ASSERT_EQUAL_HEX32(a->flags, b->flags);
    TEST_ASSERT_EQUAL_INT(a->outcome, b->outcome);
    TEST_ASSERT_EQUAL_INT(a->reason, b->reason);
}

#endif /* TVO_TEST_SUPPORT_H */
