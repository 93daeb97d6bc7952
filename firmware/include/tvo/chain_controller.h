/*
 * Sampled-data TV-O controller for the integrator-chain testbed y^(k) = u, y in R^m, k = 1..3: the
 * simplest flat system of each relative degree (paper, "Practical considerations"). The flat map is
 * the identity, so u is the law's y^(k); everything else is the unicycle controller's sampled-data
 * machinery: the same sample clock, timing convention, delay compensation and dirty-derivative
 * filters.
 *
 * Timing (ticks; see tvo/controller.h): the command applied at apply_tick is held until the next;
 * it is computed from a measurement stamped at apply_tick - delay.
 *   - compensation off: the law is evaluated at the sample instant with the sampled state, so its
 *     command lags the state by tau + h/2 on average (the paper's convention: error ratios 1 + 2 tau/h);
 *   - compensation on: the state is first predicted to apply_tick with the held command (exact for
 *     the chain), and the law is evaluated at apply_tick;
 *   - ZOH-aware (zoh_aware = 1, past the paper): the state is predicted on to the middle of the held
 *     interval, apply_tick + h/2, still with the held command, and the law (its feedforward included)
 *     is evaluated there. The held value then matches the continuous law's interval average to
 *     second order, so the tracking error becomes O(h^2) instead of O(h).
 * Derivatives y^(1..k-1) are measured, or (filtered_derivatives = 1) reconstructed from y by dirty-
 * derivative filters: one for y', a second in cascade on the first's output for y''.
 */
#ifndef TVO_CHAIN_CONTROLLER_H
#define TVO_CHAIN_CONTROLLER_H

#include "tvo/dirty_derivative.h"
#include "tvo/law.h"
#include "tvo/loop_state.h"
#include "tvo/objective.h"
#include "tvo/sample_clock.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Names the field of tvo_chain_config_t an init rejected. */
typedef enum {
    TVO_CHAIN_PARAM_NONE = 0,
    TVO_CHAIN_PARAM_TICK_HZ = 1,
    TVO_CHAIN_PARAM_PERIOD = 2,
    TVO_CHAIN_PARAM_DELAY = 3,             /* delay_ticks, or a switch (delay_compensation, zoh_aware) not 0/1 */
    TVO_CHAIN_PARAM_RELATIVE_DEGREE = 4,
    TVO_CHAIN_PARAM_GAIN = 5,              /* not Hurwitz, or too fast for the period */
    TVO_CHAIN_PARAM_FILTER_TF = 6,
    TVO_CHAIN_PARAM_INPUT_MAX = 7,
    TVO_CHAIN_PARAM_WATCHDOG = 8,
    TVO_CHAIN_PARAM_OBJECTIVE = 9          /* the objective argument: equality constraints, or no term */
} tvo_chain_param_t;

#define TVO_CHAIN_PARAM_COUNT 10

typedef struct {
    uint32_t tick_hz;             /* > 0 */
    uint32_t period_ticks;        /* h, > 0 and < 2^30 */
    uint32_t delay_ticks;         /* tau, 0 .. h */
    uint8_t relative_degree;      /* k, 1 .. TVO_MAX_RELATIVE_DEGREE */
    uint8_t delay_compensation;   /* 1: predict over the measurement's age */
    uint8_t zoh_aware;            /* 1: evaluate at the middle of the held interval */
    uint8_t filtered_derivatives; /* 1: y^(1..k-1) from dirty-derivative filters on y */
    tvo_real_t filter_tf_s;       /* T_f > 0 (used when filtered) */
    tvo_real_t gain[TVO_MAX_RELATIVE_DEGREE]; /* a_0 .. a_{k-1}, Hurwitz */
    tvo_real_t input_max;         /* |u_i| limit, > 0 */
    uint32_t watchdog_periods;    /* >= 1 */
    uint8_t watchdog_counts_refusals; /* 1: no timer (lockstep): watchdog_periods refusals in a row stop too */
} tvo_chain_config_t;

typedef struct {
    uint32_t stamp_tick;
    tvo_output_derivs_t y;        /* y.d[0] = y; y.d[1..k-1] = its derivatives (read only if measured) */
} tvo_chain_measurement_t;

typedef struct {
    tvo_real_t u[TVO_MAX_OUTPUT_DIM];
    uint32_t flags;               /* TVO_FLAG_* (TVO_FLAG_ACCEL_SATURATED: |u| clipped) */
    uint8_t outcome;              /* tvo_outcome_t: applied, held or stopped */
    uint8_t reason;               /* tvo_reason_t: why held or stopped (NONE when applied) */
} tvo_chain_command_t;

/** The step's working storage (written before it is read: nothing in it between steps). */
typedef struct {
    tvo_law_workspace_t law;
    tvo_output_derivs_t state;                                 /* x^(0..k-1) where the law is evaluated */
    tvo_dirty_derivative_t filter[TVO_MAX_RELATIVE_DEGREE - 1]; /* the filters as the step would leave them */
    tvo_real_t input[TVO_MAX_Z_DIM];                           /* the law's u */
    tvo_period_t period;                                       /* the period's timing */
    tvo_time_jet_t time;                                       /* the objective's time for the law */
    tvo_chain_command_t command;                               /* the command the step would hold */
    tvo_law_report_t report;                                   /* what the law reports to the step */
} tvo_chain_controller_work_t;

/* cfg is the firmware's to read (the validated configuration); everything else is the controller's own. */
typedef struct {
    tvo_chain_config_t cfg;
    struct {
        /* not part of the API: read through the accessors (the layout may change with any release) */
        tvo_law_t law;
        tvo_chain_controller_work_t work; /* scratch, off the step's stack: no state between steps */
        tvo_loop_state_t loop;            /* the objective, h, the clock */
        tvo_dirty_derivative_t filter[TVO_MAX_RELATIVE_DEGREE - 1]; /* cascade: y -> y' -> y'' */
        tvo_chain_command_t held;
    } internal;
} tvo_chain_controller_t;

/** k = 2, poles at -1.6 (a = 2.56, 3.2), h = 10 ms, tau = h/2 compensated, T_f = 0.05 s, |u| <= 1e3. */
tvo_status_t tvo_chain_config_default(tvo_chain_config_t *cfg);

/** Validates cfg (*bad_param names the first wrong field) and binds the objective (primal only). */
tvo_status_t tvo_chain_controller_init(tvo_chain_controller_t *ctl, const tvo_chain_config_t *cfg,
                                       const tvo_objective_t *objective, uint32_t epoch_tick,
                                       tvo_chain_param_t *bad_param);

/** Name of a parameter as it appears in tvo_chain_config_t. */
const char *tvo_chain_param_str(tvo_chain_param_t param);

/**
 * One period, as tvo_controller_step (a transaction: commits a whole period or changes nothing): TVO_OK
 * with the period's command (applied, held, or the watchdog's stop: its outcome and reason say which
 * and why); an error only when the call changed nothing. meas NULL: tvo_chain_controller_miss.
 */
tvo_status_t tvo_chain_controller_step(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                       uint32_t apply_tick, tvo_chain_command_t *cmd);

/** A period that passed without a good step, counted as tvo_controller_miss counts it. */
tvo_status_t tvo_chain_controller_miss(tvo_chain_controller_t *ctl, uint32_t apply_tick, tvo_chain_command_t *cmd);

/** A measurement the caller refused before the core saw it, as tvo_controller_refuse. */
tvo_status_t tvo_chain_controller_refuse(tvo_chain_controller_t *ctl, tvo_reason_t reason, tvo_chain_command_t *cmd);

/** What tvo_chain_controller_step would say of this measurement (*reason), changing nothing (as
 *  tvo_controller_check). */
tvo_status_t tvo_chain_controller_check(const tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                        uint32_t apply_tick, tvo_reason_t *reason);

/** Drops to rest now (held u = 0, watchdog expired, filters restart); cmd receives the stop
 *  (TVO_OUTCOME_STOPPED, TVO_REASON_STOP_REQUESTED). */
tvo_status_t tvo_chain_controller_safe_stop(tvo_chain_controller_t *ctl, tvo_chain_command_t *cmd);

#ifdef __cplusplus
}
#endif

#endif /* TVO_CHAIN_CONTROLLER_H */
