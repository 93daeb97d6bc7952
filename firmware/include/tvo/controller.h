/*
 * Sampled-data TV-O controller for N unicycles (k = 2), one instance per control loop.
 *
 * Timing (all times are integer ticks of a free-running, wrapping uint32 clock at tick_hz):
 *   - the command for the interval [t_{n+1}, t_{n+2}) is applied at apply_tick = t_{n+1} and held
 *     (zero-order hold) until the next one;
 *   - it is computed from a measurement sampled at stamp_tick, nominally t_{n+1} - delay (the
 *     computation delay, 0 <= delay <= period); tvo_controller_sample_tick() says when to sample;
 *   - with delay compensation on, the measured pose is first predicted to apply_tick by the exact
 *     arc of the command held over [stamp_tick, apply_tick] (the previous command), so the law sees
 *     the state at the instant its command takes effect. The actual age apply_tick - stamp_tick is
 *     used, so jitter in the sampling instant is compensated too.
 *
 *   - ZOH-aware (zoh_aware = 1): the pose is carried on to the middle of the held interval, the
 *     speed state by half a period of the last acceleration, and the law is evaluated there, so the
 *     held command matches the continuous law's interval average to second order in h (the
 *     tracking error becomes O(h^2); see the chain controller and the study in README);
 *   - with compensation off, the law is evaluated at the sampling instant (state and objective
 *     time both at stamp_tick), as an uncompensated implementation of the paper would;
 *   - the held speed is the interval average of the speed state, v_n + a_n h / 2 (the held arc then
 *     covers the continuous extension's distance to second order in h; holding the end-of-interval
 *     speed measured 7x worse RMS tracking in the default demo);
 *   - a valid measured speed (pose mode) shifts the speed state by (measured - held): slip and
 *     disturbances the plant reports are absorbed instead of integrated against;
 *   - position-only mode: y' comes from the dirty-derivative filter; the heading used by the flat
 *     map starts from the first sample's heading if it has one, is dead-reckoned with the held
 *     turn rate, and is pulled toward the filtered velocity direction with time constant 10 T_f.
 *
 * A step is a transaction: it commits a whole period (cmd.outcome TVO_OUTCOME_APPLIED) or changes
 * nothing, its clock included. Measurements are refused (cmd is the command in force, outcome
 * TVO_OUTCOME_HELD, cmd.reason says why) when they carry NaN/Inf, are stamped after apply_tick, are
 * older than one period, or do not advance, and so is a step whose law fails. A period that passes
 * without a good step is counted by tvo_controller_miss (or a step with no measurement): the core's
 * watchdog is the only watchdog. After watchdog_periods periods without a good step the robots stop
 * (v = 0, omega = 0, speed state reset; TVO_OUTCOME_STOPPED, TVO_REASON_WATCHDOG), and the next good
 * step starts from rest. The stop is the one thing a refusal commits: a refused step whose period
 * would expire the watchdog counts it and stops. Whatever the outcome, the step returns TVO_OK: an
 * error (tvo/status.h) means the call was misused and changed nothing.
 *
 * A valid measured speed that departs from the held speed by more than
 * max(TVO_SPEED_MISMATCH_MPS, TVO_SPEED_MISMATCH_FRACTION |held|) for TVO_SPEED_MISMATCH_PERIODS
 * accepted steps in a row flags the command TVO_FLAG_SPEED_MISMATCH (stalled wheels, or a plant
 * that reports a speed it does not have); for TVO_SPEED_MISMATCH_STOP_PERIODS in a row, it stops the
 * robots for TVO_SPEED_MISMATCH_HOLDOFF_PERIODS accepted periods.
 *
 * Limits hold against any input: every command satisfies |v| <= speed_max, |omega| <= omega_max and
 * |v_{n+1} - v_n| <= accel_max h against the command in force (a measured speed's re-sync moves the
 * command by at most that; the speed state moves with the command, so the next period's limit holds
 * too). Finite but impossible measurements are refused (see TVO_HEADING_LIMIT_RAD). A step whose
 * law results (y'', gradient, its rate) are not finite is held (TVO_REASON_NUMERIC).
 */
#ifndef TVO_CONTROLLER_H
#define TVO_CONTROLLER_H

#include "tvo/dirty_derivative.h"
#include "tvo/law.h"
#include "tvo/loop_state.h"
#include "tvo/objective.h"
#include "tvo/sample_clock.h"
#include "tvo/unicycle.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Speed-mismatch flag: departure threshold (m/s), relative part, and periods in a row. */
#define TVO_SPEED_MISMATCH_MPS TVO_R(0.05)
#define TVO_SPEED_MISMATCH_FRACTION TVO_R(0.25)
#define TVO_SPEED_MISMATCH_PERIODS 5u
/** ... acted on: after this many contradicted periods in a row the robots stop (TVO_OUTCOME_STOPPED,
 *  TVO_REASON_SPEED_MISMATCH, flagged TVO_FLAG_SPEED_MISMATCH: the measurements are accepted) and stay stopped for
 *  TVO_SPEED_MISMATCH_HOLDOFF_PERIODS accepted periods; then the controller starts again from rest. */
#define TVO_SPEED_MISMATCH_STOP_PERIODS 10u
#define TVO_SPEED_MISMATCH_HOLDOFF_PERIODS 50u

/** Plausibility: a finite measurement is refused with TVO_REASON_IMPLAUSIBLE_MEASUREMENT when a position
 *  lies beyond TVO_POSITION_LIMIT_M (tvo/config.h), a valid heading beyond +-TVO_HEADING_LIMIT_RAD
 *  (unwrapped headings are fine up to it; float32 keeps 0.008 rad there), or a valid measured speed
 *  beyond TVO_MEASURED_SPEED_FACTOR * speed_max_mps + TVO_MEASURED_SPEED_MARGIN_MPS (no command
 *  reaches it). A jump within the workspace is served: the command's limits bound its effect. */
#define TVO_HEADING_LIMIT_RAD TVO_R(65536.0)
#define TVO_MEASURED_SPEED_FACTOR TVO_R(2.0)
#define TVO_MEASURED_SPEED_MARGIN_MPS TVO_R(0.5)

typedef enum {
    /** y' = v e_theta with the measured heading; a valid measured speed re-syncs the speed state. */
    TVO_VELOCITY_FROM_POSE = 0,
    /** y' from a dirty-derivative filter on measured positions; heading and speed are not used
        (but for an initial heading, if the first sample has one). */
    TVO_VELOCITY_FROM_POSITION = 1
} tvo_velocity_source_t;

typedef struct {
    uint32_t tick_hz;            /* ticks per second of every timestamp, > 0 */
    uint32_t period_ticks;       /* h, > 0 and < 2^30 */
    uint32_t delay_ticks;        /* tau: nominal sampling instant is apply - tau; 0 <= tau <= h */
    uint8_t robot_count;         /* N, 1 .. TVO_MAX_ROBOTS; the objective's dim must be 2N */
    uint8_t delay_compensation;  /* 1: predict over the measurement's age before the law */
    uint8_t zoh_aware;           /* 1: evaluate the law at the middle of the held interval */
    uint8_t watchdog_counts_refusals; /* 1: no timer (lockstep): watchdog_periods refusals in a row stop too */
    tvo_velocity_source_t velocity_source;
    tvo_real_t filter_tf_s;      /* dirty-derivative time constant T_f > 0 */
    tvo_real_t gain_kp;          /* a_0; with gain_kd must make s^2 + kd s + kp Hurwitz */
    tvo_real_t gain_kd;          /* a_1 */
    tvo_real_t omega_max_radps;  /* |omega| limit, > 0 */
    tvo_real_t accel_max_mps2;   /* |dv/dt| limit, > 0 */
    tvo_real_t speed_max_mps;    /* |v| limit, > 0 */
    tvo_real_t min_speed_mps;    /* 1/v regularisation floor, 0 < min_speed < speed_max */
    uint32_t watchdog_periods;   /* safe stop after this many periods without a valid measurement, >= 1 */
    tvo_real_t initial_speed_mps[TVO_MAX_ROBOTS]; /* dynamic-extension speed at start, |v0| <= speed_max */
} tvo_controller_config_t;

typedef struct {
    uint32_t stamp_tick;                         /* when the pose was sampled */
    tvo_real_t position_m[TVO_MAX_ROBOTS][2];
    tvo_real_t heading_rad[TVO_MAX_ROBOTS];
    tvo_real_t speed_mps[TVO_MAX_ROBOTS];
    uint8_t heading_valid;
    uint8_t speed_valid;
} tvo_measurement_t;

typedef struct {
    tvo_real_t speed_mps[TVO_MAX_ROBOTS];
    tvo_real_t turn_rate_radps[TVO_MAX_ROBOTS];
    uint32_t flags;                              /* TVO_FLAG_*: what shaped an applied command */
    uint8_t outcome;                             /* tvo_outcome_t: applied, held or stopped */
    uint8_t reason;                              /* tvo_reason_t: why held or stopped (NONE when applied) */
} tvo_command_t;

/** What the last applied step computed. */
typedef struct {
    tvo_real_t objective_time_s;
    tvo_real_t output_m[TVO_MAX_OUTPUT_DIM];          /* y the law used */
    tvo_real_t output_rate_mps[TVO_MAX_OUTPUT_DIM];   /* y' the law used */
    tvo_real_t output_accel_mps2[TVO_MAX_OUTPUT_DIM]; /* y'' the law demanded */
    tvo_real_t gradient[TVO_MAX_OUTPUT_DIM];
    tvo_real_t gradient_rate[TVO_MAX_OUTPUT_DIM];
    tvo_real_t accel_mps2[TVO_MAX_ROBOTS];            /* v' after limits */
    tvo_real_t multiplier[TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)]; /* nu after the step (equality constraints) */
    tvo_real_t regularization;                        /* Hessian shift of the solve, 0 if none */
    tvo_real_t barrier_c;                             /* the barrier's c(t) and s(t) at objective_time_s, */
    tvo_real_t barrier_slack;                         /*   as the law evaluated them (0 without inequalities) */
} tvo_controller_telemetry_t;

/** The step's working storage (the law's, the derivatives it is evaluated at, the filter's trial
 *  copy): written before it is read, so it holds nothing between steps, and not on the stack. */
typedef struct {
    tvo_law_workspace_t law;
    tvo_output_derivs_t output;                      /* z^(0..k-1) where the law is evaluated */
    tvo_real_t output_accel[TVO_MAX_Z_DIM];          /* z^(k) it demands */
    tvo_real_t gradient[TVO_MAX_OUTPUT_DIM];
    tvo_real_t gradient_rate[TVO_MAX_OUTPUT_DIM];
    tvo_real_t rate_filtered[TVO_MAX_OUTPUT_DIM];    /* position-only: the filter's y', carried to the law */
    tvo_dirty_derivative_t velocity_filter;          /* the filter as the step would leave it */
    tvo_time_jet_t time;                             /* the objective's time where the law is evaluated */
    tvo_command_t command;                           /* the command the step would hold */
    tvo_law_report_t report;                         /* what the law reports to the step */
    const tvo_command_t *in_force;                   /* the command applied before apply_tick (zero from rest) */
    uint8_t from_rest;                               /* the watchdog stopped the robots: start at rest */
    /* Per robot (entries 0..n-1): */
    tvo_real_t heading_at_sample[TVO_MAX_ROBOTS];
    tvo_real_t heading[TVO_MAX_ROBOTS];              /* where the law is evaluated */
    tvo_real_t heading_cs[TVO_MAX_ROBOTS][2];        /* its cos, sin: trigonometry once per robot */
    tvo_real_t speed[TVO_MAX_ROBOTS];                /* the dynamic extension's speed there */
    tvo_real_t speed_state[TVO_MAX_ROBOTS];          /* the extension's state as the step would leave it */
    tvo_real_t speed_next[TVO_MAX_ROBOTS];
    tvo_real_t accel[TVO_MAX_ROBOTS];
    tvo_period_t period;                             /* the period's timing; last, beside the loop's clock the step
                                                        reads with it (one base register for both) */
} tvo_controller_work_t;

typedef struct tvo_controller tvo_controller_t;

/** The position-only velocity source's plan, which tvo_controller_init picks (and so links): estimate
 *  makes, from the measurement, the step's trial filter, the heading at the sample and y' where the law
 *  is evaluated (work's velocity_filter, heading_at_sample, rate_filtered); commit keeps the accepted
 *  period's filter and heading estimate. */
typedef struct {
    tvo_status_t (*estimate)(tvo_controller_t *ctl, const tvo_measurement_t *meas);
    void (*commit)(tvo_controller_t *ctl);
} tvo_position_velocity_t;

/* cfg and telemetry are the firmware's to read (the validated configuration; what the last applied
 * step computed); everything else is the controller's own. */
struct tvo_controller {
    tvo_controller_config_t cfg;
    struct {
        /* not part of the API: read through the accessors (the layout may change with any release) */
        tvo_law_t law;
        tvo_controller_work_t work; /* scratch, off the step's stack: no state between steps */
        tvo_dirty_derivative_t velocity_filter;
        tvo_loop_state_t loop;           /* the objective, h, the clock (ticks, stamps, watchdog) */
        tvo_real_t speed_state_mps[TVO_MAX_ROBOTS];   /* dynamic extension v */
        tvo_real_t heading_estimate_rad[TVO_MAX_ROBOTS]; /* position-only mode: dead-reckoned heading (else unused) */
        tvo_real_t multiplier[TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)];      /* nu of equality constraints, at apply_tick */
        tvo_real_t multiplier_rate[TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)]; /* nu' */
        tvo_command_t held;              /* command applied over the current interval */
        uint32_t speed_mismatch_periods; /* accepted steps in a row whose measured speed contradicted the held one */
        uint32_t speed_mismatch_holdoff; /* accepted periods the mismatch stop still lasts */
        tvo_real_t speed_step_max_mps;   /* accel_max h: the most a command's speed may differ from the one in force */
        tvo_real_t measured_speed_limit_mps; /* a measured speed beyond it is refused (TVO_MEASURED_SPEED_FACTOR) */
        const tvo_position_velocity_t *position_velocity; /* set by tvo_controller_init only: NULL links none */
    } internal;
    tvo_controller_telemetry_t telemetry;
};

/** The paper's defaults: k_p = 40, k_d = 13, omega_max = 2 pi, accel_max = 15, h = 10 ms, tau = h/2. */
tvo_status_t tvo_controller_config_default(tvo_controller_config_t *cfg);

/**
 * Validates every parameter (on TVO_ERR_PARAM *bad_param names the first wrong one; bad_param may
 * be NULL) and binds the objective (primal_dim must be 2 * robot_count; it must outlive the
 * controller). Multipliers of equality constraints start at 0 and are integrated by the controller
 * with the nu'' the law returns (they are not measured).
 * epoch_tick is the tick at which the objective's time is 0.
 */
tvo_status_t tvo_controller_init(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                 const tvo_objective_t *objective, uint32_t epoch_tick,
                                 tvo_param_t *bad_param);

/**
 * tvo_controller_init for the pose velocity source only: TVO_VELOCITY_FROM_POSITION is refused
 * (TVO_ERR_PARAM, TVO_PARAM_VELOCITY_SOURCE). A firmware that calls no other init links neither
 * the position-only estimate nor its dirty-derivative filter (about 1 KiB of flash on Cortex-M4F)
 * when its link drops unused sections (-ffunction-sections and --gc-sections, as the project's
 * toolchain files set). The controller then steps exactly as one from tvo_controller_init with the
 * same arguments; a measurement for the position source set by hand afterwards is refused
 * (TVO_REASON_SOURCE_NOT_LINKED).
 */
tvo_status_t tvo_controller_init_pose_velocity(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                               const tvo_objective_t *objective, uint32_t epoch_tick,
                                               tvo_param_t *bad_param);

/**
 * One period: computes the command applied at apply_tick from the measurement (NULL when none
 * arrived: tvo_controller_miss). Returns TVO_OK with the period's command in cmd: the new one
 * (TVO_OUTCOME_APPLIED, committed); or, with nothing changed, the one in force (TVO_OUTCOME_HELD,
 * cmd->reason the refusal); or, when the period would expire the watchdog, the stop (counted;
 * TVO_OUTCOME_STOPPED, TVO_REASON_WATCHDOG). Errors change nothing: TVO_ERR_NULL,
 * TVO_ERR_NOT_INITIALIZED (cmd the stop), TVO_ERR_TICK_NOT_ADVANCING when apply_tick does not
 * advance past the last period, TVO_ERR_BEFORE_EPOCH when the first precedes the epoch (cmd the
 * command in force, reason NONE): cmd is safe to apply in every case.
 */
tvo_status_t tvo_controller_step(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                 uint32_t apply_tick, tvo_command_t *cmd);

/**
 * A period that passed without a good step: TVO_OK with the command applied at apply_tick, the one in
 * force (TVO_OUTCOME_HELD, TVO_REASON_NO_MEASUREMENT), or the watchdog's stop once watchdog_periods
 * periods passed so (TVO_OUTCOME_STOPPED, TVO_REASON_WATCHDOG; the robots are at rest until a good
 * step). Counts the periods since the last application; the errors are the step's, changing nothing.
 * tvo_controller_step with meas NULL is the same call.
 */
tvo_status_t tvo_controller_miss(tvo_controller_t *ctl, uint32_t apply_tick, tvo_command_t *cmd);

/**
 * A measurement the caller refused before the core saw it (its own checks: a stamp it cannot place, a
 * robot it has not heard), with no period of its own: TVO_OK with the command in force (TVO_OUTCOME_HELD,
 * `reason`), nothing changed; with watchdog_counts_refusals, the watchdog_periods-th refusal in a row
 * since the last good step is the watchdog's stop (TVO_OUTCOME_STOPPED, TVO_REASON_WATCHDOG), and so is
 * every one after it. reason: a measurement's (TVO_REASON_NOT_FINITE .. TVO_REASON_SOURCE_NOT_LINKED, or
 * TVO_REASON_REFUSED), else TVO_ERR_PARAM (cmd the command in force); the other errors are the step's.
 */
tvo_status_t tvo_controller_refuse(tvo_controller_t *ctl, tvo_reason_t reason, tvo_command_t *cmd);

/**
 * What tvo_controller_step would say of this measurement before computing anything: *reason is
 * TVO_REASON_NONE if it would use it, else the refusal (not finite, implausible, future, stale, not
 * newer, missing field; TVO_REASON_NO_MEASUREMENT for meas NULL). Returns the step's errors (and
 * TVO_ERR_NULL for reason NULL). Changes nothing.
 */
tvo_status_t tvo_controller_check(const tvo_controller_t *ctl, const tvo_measurement_t *meas, uint32_t apply_tick,
                                  tvo_reason_t *reason);

/**
 * Drops to rest now, as the watchdog does: held command and speed states zero, multiplier rates
 * zero, the watchdog counted as expired (so filters restart with the next accepted measurement).
 * cmd receives the stop (all zero, TVO_OUTCOME_STOPPED, TVO_REASON_STOP_REQUESTED). The clock does
 * not advance.
 */
tvo_status_t tvo_controller_safe_stop(tvo_controller_t *ctl, tvo_command_t *cmd);

/** Tick at which to sample for the command applied at apply_tick: apply_tick - delay. */
tvo_status_t tvo_controller_sample_tick(const tvo_controller_t *ctl, uint32_t apply_tick,
                                        uint32_t *sample_tick);

/** Converts an objective-time tick count to the streamed-target stamp for a plant tick. */
tvo_status_t tvo_controller_objective_ticks(const tvo_controller_t *ctl, uint32_t tick,
                                            uint64_t *objective_ticks);

#ifdef __cplusplus
}
#endif

#endif /* TVO_CONTROLLER_H */
