/*
 * Sampled-data TV-O controller for N unicycles; see tvo/controller.h for the timing contract.
 *
 * One step: validate the measurement -> predict each pose over its age with the held command
 * -> estimate y' -> the law (y'') -> the flat map (v', omega) -> limits -> integrate the speed
 * state over the period -> hold the new command.
 */
#include "tvo/controller.h"
#include "tvo/defaults.h"

#include <string.h>

#include "internal/dirty_derivative.h"
#include "internal/law.h"
#include "internal/real_bits.h"
#include "position_velocity.h"
#include "sampled_loop.h"
#include "internal/unicycle.h"
#include "internal/trig.h"

tvo_status_t tvo_controller_config_default(tvo_controller_config_t *cfg)
{
    /* The paper's: its gains and limits, one robot, the pose velocity source. */
    static const tvo_controller_config_t defaults = {
        TVO_LOOP_CONFIG_DEFAULTS, .robot_count = 1u, .zoh_aware = 0u, .velocity_source = TVO_VELOCITY_FROM_POSE,
        .filter_tf_s = (tvo_real_t)TVO_DEFAULT_FILTER_TF_S, .gain_kp = (tvo_real_t)TVO_DEFAULT_GAIN_KP,
        .gain_kd = (tvo_real_t)TVO_DEFAULT_GAIN_KD, .omega_max_radps = (tvo_real_t)TVO_DEFAULT_OMEGA_MAX_RADPS,
        .accel_max_mps2 = (tvo_real_t)TVO_DEFAULT_ACCEL_MAX_MPS2, .speed_max_mps = (tvo_real_t)TVO_DEFAULT_SPEED_MAX_MPS,
        .min_speed_mps = (tvo_real_t)TVO_DEFAULT_MIN_SPEED_MPS};
    if (cfg == NULL) {
        return TVO_ERR_NULL;
    }
    *cfg = defaults;
    return TVO_OK;
}

/* position_velocity: the position-only source's plan, NULL if the caller does not offer it. */
static tvo_param_t first_bad_param(const tvo_controller_config_t *cfg, const tvo_objective_t *objective,
                                   const tvo_position_velocity_t *position_velocity)
{
    const tvo_param_t timing = tvo_sample_clock_check_timing(cfg->tick_hz, cfg->period_ticks, cfg->delay_ticks);
    if (timing != TVO_PARAM_NONE) {
        return timing;
    }
    if (cfg->robot_count == 0u || cfg->robot_count > TVO_MAX_ROBOTS) {
        return TVO_PARAM_ROBOT_COUNT;
    }
    if (cfg->delay_compensation > 1u || cfg->zoh_aware > 1u) {
        return TVO_PARAM_DELAY; /* switches are 0 or 1 */
    }
    if (cfg->velocity_source != TVO_VELOCITY_FROM_POSE &&
        (cfg->velocity_source != TVO_VELOCITY_FROM_POSITION || position_velocity == NULL)) {
        return TVO_PARAM_VELOCITY_SOURCE;
    }
    if (!real_positive_finite(cfg->filter_tf_s)) {
        return TVO_PARAM_FILTER_TF;
    }
    if (!real_positive_finite(cfg->gain_kp) || !real_positive_finite(cfg->gain_kd)) {
        return TVO_PARAM_GAINS; /* s^2 + kd s + kp is Hurwitz iff both are positive */
    }
    const tvo_real_t gains[2] = {cfg->gain_kp, cfg->gain_kd};
    if (tvo_law_check_sampling_reach(2u, gains, tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz)) != TVO_OK) {
        return TVO_PARAM_GAINS;
    }
    if (!real_positive_finite(cfg->omega_max_radps)) {
        return TVO_PARAM_OMEGA_MAX;
    }
    if (!real_positive_finite(cfg->accel_max_mps2)) {
        return TVO_PARAM_ACCEL_MAX;
    }
    if (!real_positive_finite(cfg->speed_max_mps)) {
        return TVO_PARAM_SPEED_MAX;
    }
    if (!real_positive_finite(cfg->min_speed_mps) || !(cfg->min_speed_mps < cfg->speed_max_mps)) {
        return TVO_PARAM_MIN_SPEED;
    }
    if (!tvo_sample_clock_watchdog_ok(cfg->period_ticks, cfg->watchdog_periods) || cfg->watchdog_counts_refusals > 1u) {
        return TVO_PARAM_WATCHDOG;
    }
    for (uint8_t r = 0; r < cfg->robot_count; ++r) {
        if (!real_within(cfg->initial_speed_mps[r], cfg->speed_max_mps)) {
            return TVO_PARAM_INITIAL_SPEED;
        }
    }
    if (objective->primal_dim != 2u * cfg->robot_count || objective->term_count == 0u) {
        return TVO_PARAM_OBJECTIVE;
    }
    return TVO_PARAM_NONE;
}

static const tvo_loop_plant_t unicycle_plant; /* the loop's table, below its pieces */

/* The robots a step loops over: a one-robot build's count is 1 (init refuses others), a constant, so
 * its loops fold. */
#define STEP_ROBOTS(count) ((uint8_t)(TVO_MAX_ROBOTS == 1 ? 1u : (count)))

/* Validates and binds the controller, all but the loop's clock and the position-only source's filter
 * (position_velocity: that source's plan, NULL when the caller does not link it); *bad names the
 * culprit of a refusal. */
static tvo_status_t controller_setup(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                     const tvo_objective_t *objective, tvo_param_t *bad,
                                     const tvo_position_velocity_t *position_velocity)
{
    *bad = first_bad_param(cfg, objective, position_velocity);
    if (*bad != TVO_PARAM_NONE) {
        return TVO_ERR_PARAM;
    }
    ctl->cfg = *cfg;
    ctl->internal.loop.objective = objective;
    ctl->internal.position_velocity = position_velocity;
    ctl->internal.loop.period_s = tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz);
    ctl->internal.speed_step_max_mps = cfg->accel_max_mps2 * ctl->internal.loop.period_s;
    ctl->internal.measured_speed_limit_mps = TVO_MEASURED_SPEED_FACTOR * cfg->speed_max_mps + TVO_MEASURED_SPEED_MARGIN_MPS;
    for (uint8_t r = 0; r < cfg->robot_count; ++r) {
        ctl->internal.speed_state_mps[r] = cfg->initial_speed_mps[r];
        ctl->internal.held.speed_mps[r] = cfg->initial_speed_mps[r];
    }
    if (objective->dim > TVO_MAX_Z_DIM) {
        *bad = TVO_PARAM_OBJECTIVE; /* an objective changed by hand: the law cannot hold its size */
        return TVO_ERR_DIMENSION;
    }
    const tvo_real_t gains[2] = {cfg->gain_kp, cfg->gain_kd}; /* positive: Hurwitz (first_bad_param) */
    tvo_law_init(&ctl->internal.law, 2u, objective->dim, gains);
    return TVO_OK;
}

/* Both inits: the loop's begin and end around the plant's setup; in each, so the pose-only one links
 * no filter. */
TVO_LOOP_ENTRY tvo_status_t controller_init(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                            const tvo_objective_t *objective, uint32_t epoch_tick,
                                            tvo_param_t *bad_param, const tvo_position_velocity_t *position_velocity)
{
    if (bad_param != NULL) {
        *bad_param = TVO_PARAM_NONE;
    }
    tvo_status_t st = loop_init_begin(&unicycle_plant, ctl, cfg, objective);
    if (st != TVO_OK) {
        return st;
    }
    tvo_param_t bad = TVO_PARAM_NONE;
    st = controller_setup(ctl, cfg, objective, &bad, position_velocity);
    if (st == TVO_OK && position_velocity != NULL) {
        st = tvo_dirty_derivative_init(&ctl->internal.velocity_filter, objective->primal_dim, cfg->filter_tf_s, ctl->internal.loop.period_s);
        bad = (st == TVO_OK) ? TVO_PARAM_NONE : TVO_PARAM_OBJECTIVE;
    }
    if (st != TVO_OK && bad_param != NULL) {
        *bad_param = bad;
    }
    return loop_init_end(&unicycle_plant, ctl, st, cfg->tick_hz, cfg->period_ticks, cfg->watchdog_periods,
                         cfg->watchdog_counts_refusals, epoch_tick);
}

tvo_status_t tvo_controller_init(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                 const tvo_objective_t *objective, uint32_t epoch_tick,
                                 tvo_param_t *bad_param)
{
    return controller_init(ctl, cfg, objective, epoch_tick, bad_param, &controller_position_velocity_plan);
}

tvo_status_t tvo_controller_init_pose_velocity(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                               const tvo_objective_t *objective, uint32_t epoch_tick,
                                               tvo_param_t *bad_param)
{
    return controller_init(ctl, cfg, objective, epoch_tick, bad_param, NULL);
}

/* Why a measurement failed the range check, off the common path: not finite if the sum of the robots'
 * values is not (a field the configuration does not read included), else out of range. */
TVO_COLD_BODY tvo_reason_t measurement_range_refusal(const tvo_controller_t *ctl, const tvo_measurement_t *meas)
{
    tvo_real_t probe = TVO_R(0.0);
    for (uint8_t r = 0; r < STEP_ROBOTS(ctl->cfg.robot_count) && r < TVO_MAX_ROBOTS; ++r) {
        probe += meas->position_m[r][0] + meas->position_m[r][1] + meas->heading_rad[r] + meas->speed_mps[r];
    }
    return isfinite(probe - probe) ? TVO_REASON_IMPLAUSIBLE_MEASUREMENT : TVO_REASON_NOT_FINITE;
}

/* The loop's refusal piece: the range check's refusal told apart (implausible, or not finite). */
static tvo_reason_t unicycle_refusal(const void *ctl, const void *meas, tvo_reason_t reason)
{
    return (reason == TVO_REASON_IMPLAUSIBLE_MEASUREMENT) ? measurement_range_refusal(ctl, meas) : reason;
}

/* The loop's refuse piece: its refusal, out of line (a cold path). */
TVO_COLD_BODY void unicycle_refuse(void *ctl, const void *meas, const tvo_period_t *period, tvo_reason_t reason,
                                   void *cmd)
{
    loop_refuse(&unicycle_plant, ctl, meas, period, reason, cmd);
}


/* The loop's check piece: the measurement's values, its stamp and the fields the source reads. */
static inline tvo_reason_t check_measurement(const void *ctl_any, const void *meas_any, uint32_t apply_tick)
{
    const tvo_controller_t *ctl = ctl_any;
    const tvo_measurement_t *meas = meas_any;
    const uint8_t n = STEP_ROBOTS(ctl->cfg.robot_count);
    const tvo_real_t speed_limit = ctl->internal.measured_speed_limit_mps;
    for (uint8_t r = 0; r < n; ++r) {
        /* One comparison per value refuses NaN, infinities and the impossible alike (internal/real_bits.h). */
        if (!real_within2(meas->position_m[r][0], meas->position_m[r][1], TVO_POSITION_LIMIT_M) ||
            (meas->heading_valid && !real_within(meas->heading_rad[r], TVO_HEADING_LIMIT_RAD)) ||
            (meas->speed_valid && !real_within(meas->speed_mps[r], speed_limit))) {
            return TVO_REASON_IMPLAUSIBLE_MEASUREMENT; /* or not finite: unicycle_refusal says which */
        }
    }
    const tvo_reason_t stamp = sample_clock_check_stamp(&ctl->internal.loop.clock, meas->stamp_tick, apply_tick);
    if (stamp != TVO_REASON_NONE) {
        return stamp;
    }
    if (ctl->cfg.velocity_source == TVO_VELOCITY_FROM_POSE) {
        if (!meas->heading_valid) {
            return TVO_REASON_MISSING_FIELD;
        }
    } else if (ctl->internal.position_velocity == NULL) {
        return TVO_REASON_SOURCE_NOT_LINKED; /* set by hand after tvo_controller_init_pose_velocity */
    }
    return TVO_REASON_NONE;
}

/* What a good step after the watchdog's gap takes as the inputs in force: the robots were stopped (only
 * its inputs are read). */
static const tvo_command_t rest_command;

/* v clipped to [-limit, limit] (flag set in *flags when it is; NaN passes as it is), asked as |v| <= limit
 * first: one comparison for a value within the limit, the common case. */
static inline tvo_real_t clamp(tvo_real_t v, tvo_real_t limit, uint32_t flag, uint32_t *flags)
{
    if (TVO_FABS(v) <= limit) {
        return v;
    }
    if (v > limit) {
        *flags |= flag;
        return limit;
    }
    if (v < -limit) {
        *flags |= flag;
        return -limit;
    }
    return v;
}

/* The loop's rest piece: speed states, the dual dynamics and the mismatch counts at rest (the robots
 * stop; a good step after the watchdog's gap commits from here). */
TVO_COLD_BODY void unicycle_rest(void *ctl_any)
{
    tvo_controller_t *ctl = ctl_any;
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        ctl->internal.speed_state_mps[r] = TVO_R(0.0);
    }
    for (uint8_t q = 0; q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES); ++q) {
        ctl->internal.multiplier_rate[q] = TVO_R(0.0);
    }
    ctl->internal.speed_mismatch_periods = 0u;
    ctl->internal.speed_mismatch_holdoff = 0u;
}

/* The command's speed moved beyond accel_max h from the one in force (a measured speed's re-sync):
 * held to the bound, the speed state moved with it. Returns the flag it sets. */
TVO_COLD_BODY uint32_t limit_speed_step(const tvo_controller_t *ctl, tvo_real_t *speed_mps, tvo_real_t *speed_next_mps,
                                        tvo_real_t held_speed_mps)
{
    const tvo_real_t step = *speed_mps - held_speed_mps;
    const tvo_real_t bound = step > TVO_R(0.0) ? ctl->internal.speed_step_max_mps : -ctl->internal.speed_step_max_mps;
    uint32_t unused = 0u;
    *speed_mps = held_speed_mps + bound;
    *speed_next_mps = clamp(*speed_next_mps - (step - bound), ctl->cfg.speed_max_mps, 0u, &unused);
    return TVO_FLAG_ACCEL_SATURATED;
}

/* The commit's mismatch count, after the held command's flags are written: a contradicted period
 * counts (a run of TVO_SPEED_MISMATCH_PERIODS flags the command, a longer one starts the stop), any
 * other clears the count; a period of a running stop holds the robots still. */
TVO_COLD_BODY tvo_reason_t commit_speed_mismatch(tvo_controller_t *ctl, uint8_t contradicted)
{
    ctl->internal.speed_mismatch_periods = contradicted ? ctl->internal.speed_mismatch_periods + 1u : 0u;
    if (ctl->internal.speed_mismatch_periods >= TVO_SPEED_MISMATCH_PERIODS) {
        ctl->internal.held.flags |= TVO_FLAG_SPEED_MISMATCH;
        if (ctl->internal.speed_mismatch_periods >= TVO_SPEED_MISMATCH_STOP_PERIODS) {
            ctl->internal.speed_mismatch_periods = 0u;
            ctl->internal.speed_mismatch_holdoff = TVO_SPEED_MISMATCH_HOLDOFF_PERIODS;
        }
    }
    if (ctl->internal.speed_mismatch_holdoff == 0u) {
        return TVO_REASON_NONE;
    }
    /* A period of the stop: accepted (clock, filters, multipliers move on), but the robots stand still
     * (the loop makes the held command the stop). */
    ctl->internal.speed_mismatch_holdoff--;
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        ctl->internal.speed_state_mps[r] = TVO_R(0.0);
        ctl->telemetry.accel_mps2[r] = TVO_R(0.0);
    }
    for (uint8_t q = 0; q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES); ++q) {
        ctl->internal.multiplier_rate[q] = TVO_R(0.0);
    }
    ctl->internal.held.flags = TVO_FLAG_SPEED_MISMATCH;
    return TVO_REASON_SPEED_MISMATCH;
}

/* The loop's prepare piece, for a period the clock has begun: the measurement checked, the state and
 * time the law is evaluated at (work->output, work->time); the frame's flags, its note (the measured
 * speed contradicted the held one) and the stamp. */
TVO_OFF_CHAIN_BODY tvo_reason_t unicycle_prepare(void *ctl_any, const void *meas_any, uint32_t apply_tick,
                                                 tvo_loop_frame_t *frame)
{
    tvo_controller_t *ctl = ctl_any;
    const tvo_measurement_t *meas = meas_any;
    const uint8_t n = STEP_ROBOTS(frame->shape);
    const tvo_controller_config_t *cfg = &ctl->cfg;
    tvo_controller_work_t *work = &ctl->internal.work;
    tvo_period_t *period = &work->period;
    work->from_rest = frame->from_rest;
    work->in_force = work->from_rest ? &rest_command : &ctl->internal.held;
    const tvo_reason_t refused = check_measurement(ctl, meas, apply_tick);
    if (refused != TVO_REASON_NONE) {
        return refused;
    }
    /* Where the law is evaluated and how far the sampled state is carried there (the age to the
     * application instant with compensation, half a period on when ZOH-aware). */
    sample_clock_locate(&ctl->internal.loop.clock, period, meas->stamp_tick, cfg->delay_compensation, cfg->zoh_aware);
    const int position_only = cfg->velocity_source == TVO_VELOCITY_FROM_POSITION;
    if (position_only) {
        const tvo_status_t st = ctl->internal.position_velocity->estimate(ctl, meas); /* init set it for this source */
        if (st != TVO_OK) {
            return loop_reason_of(st);
        }
    }
    const tvo_real_t *heading_at_sample = position_only ? work->heading_at_sample : meas->heading_rad;
    const tvo_real_t *rate_carried = work->rate_filtered;
    const int zoh_aware = cfg->zoh_aware != 0u;
    const tvo_real_t carry_s = period->carry_s;
    uint32_t flags = (carry_s > TVO_R(0.0)) ? TVO_FLAG_PREDICTED : 0u;
    const tvo_command_t *in_force = work->in_force;
    const int from_rest = work->from_rest;

    /* State the law sees: at the sample (no compensation), the application instant, or mid-interval. */
    tvo_output_derivs_t *y = &work->output;
    tvo_real_t *heading = work->heading;
    tvo_real_t(*heading_cs)[2] = work->heading_cs;
    tvo_real_t *speed = work->speed;
    tvo_real_t *speed_state = work->speed_state;
    int speed_contradicted = 0;
    for (uint8_t r = 0; r < n; ++r) {
        speed_state[r] = from_rest ? TVO_R(0.0) : ctl->internal.speed_state_mps[r];
        if (cfg->velocity_source == TVO_VELOCITY_FROM_POSE && meas->speed_valid) {
            /* Re-sync the extension with what the plant actually does (slip, disturbance): the plant
             * should run at the held speed, so shift the state by the measured departure from it. */
            const tvo_real_t held_speed = in_force->speed_mps[r];
            const tvo_real_t departure = meas->speed_mps[r] - held_speed;
            const tvo_real_t tolerance = TVO_SPEED_MISMATCH_FRACTION * TVO_FABS(held_speed);
            if (TVO_FABS(departure) > (tolerance > TVO_SPEED_MISMATCH_MPS ? tolerance : TVO_SPEED_MISMATCH_MPS)) {
                speed_contradicted = 1;
            }
            speed_state[r] = clamp(speed_state[r] + departure, cfg->speed_max_mps, 0u, &flags);
        }
        tvo_pose_t pose;
        pose.position_m[0] = meas->position_m[r][0];
        pose.position_m[1] = meas->position_m[r][1];
        pose.heading_rad = heading_at_sample[r];
        if (carry_s > TVO_R(0.0)) {
            tvo_unicycle_predict_cs(&pose, in_force->speed_mps[r], in_force->turn_rate_radps[r], carry_s, &pose,
                                    heading_cs[r]);
        } else {
            tvo_sincos(pose.heading_rad, &heading_cs[r][1], &heading_cs[r][0]);
        }
        if (position_only) {
            heading[r] = pose.heading_rad; /* the position-only source's estimate moves on from it */
        }
        /* Mid-interval speed: the state plus half a period of the last acceleration (O(h^2)). */
        speed[r] = zoh_aware && !from_rest
                       ? speed_state[r] + TVO_R(0.5) * ctl->internal.loop.period_s * ctl->telemetry.accel_mps2[r]
                       : speed_state[r];
        y->d[0][2u * r] = pose.position_m[0];
        y->d[0][2u * r + 1u] = pose.position_m[1];
        if (position_only) {
            y->d[1][2u * r] = rate_carried[2u * r];
            y->d[1][2u * r + 1u] = rate_carried[2u * r + 1u];
        } else {
            y->d[1][2u * r] = speed[r] * heading_cs[r][0];
            y->d[1][2u * r + 1u] = speed[r] * heading_cs[r][1];
        }
    }

    /* The objective's time, from the period's exact elapsed time (no 64-bit division). */
    tvo_time_jet_t *t = &work->time;
    time_jet_at_tick_time(&period->law_time, cfg->tick_hz, TVO_R(1.0), t); /* the clock's times are valid */

#if TVO_MAX_EQUALITIES > 0
    /* Multipliers (equality constraints) and their rates: controller states living at apply times. */
    const uint8_t primal = ctl->internal.loop.objective->primal_dim;
    const uint8_t dual = ctl->internal.loop.objective->dual_dim;
    for (uint8_t q = 0; q < dual && q < TVO_MAX_EQUALITIES; ++q) {
        y->d[0][primal + q] = ctl->internal.multiplier[q];
        y->d[1][primal + q] = from_rest ? TVO_R(0.0) : ctl->internal.multiplier_rate[q];
    }
#endif

    frame->flags = flags;
    frame->note = (uint8_t)speed_contradicted;
    return TVO_REASON_NONE;
}

/* The loop's law piece, in the step's own frame (the law's call chain is the step's deepest). */
TVO_LOOP_ENTRY tvo_reason_t unicycle_law(void *ctl_any, tvo_loop_frame_t *frame)
{
    tvo_controller_t *ctl = ctl_any;
    tvo_controller_work_t *work = &ctl->internal.work;
    tvo_law_report_t *report = &work->report;
    report->gradient = work->gradient;
    report->gradient_rate = work->gradient_rate;
    report->count = ctl->internal.loop.objective->primal_dim;
    const tvo_status_t st = tvo_law_evaluate_report(&ctl->internal.law, ctl->internal.loop.objective, &work->output, &work->time,
                                                    work->output_accel, report, &work->law);
    if (report->regularization > TVO_R(0.0)) {
        frame->flags |= TVO_FLAG_REGULARIZED;
    }
    return (st == TVO_OK) ? TVO_REASON_NONE : loop_reason_of(st);
}

/* The loop's command piece: the flat map and the limits, into work->command (nothing committed). */
TVO_OFF_CHAIN_BODY tvo_reason_t unicycle_command(void *ctl_any, tvo_loop_frame_t *frame)
{
    tvo_controller_t *ctl = ctl_any;
    const uint8_t n = STEP_ROBOTS(frame->shape);
    const tvo_controller_config_t *cfg = &ctl->cfg;
    tvo_controller_work_t *work = &ctl->internal.work;
    const tvo_real_t *y_accel = work->output_accel;
    tvo_real_t(*heading_cs)[2] = work->heading_cs;
    const tvo_real_t *speed = work->speed;
    const tvo_real_t *speed_state = work->speed_state;
    tvo_command_t *next = &work->command; /* robots 0..n-1; the held command's others stay zero */
    tvo_reason_t st = TVO_REASON_NONE;
    uint32_t flags = frame->flags;
    tvo_real_t *speed_next = work->speed_next;
    tvo_real_t *accel = work->accel;
    for (uint8_t r = 0; r < n && st == TVO_REASON_NONE; ++r) {
        uint8_t low_speed = 0;
        tvo_real_t turn_rate;
        tvo_unicycle_flat_map_cs(heading_cs[r], speed[r], &y_accel[2u * r], cfg->min_speed_mps, &accel[r],
                                 &turn_rate, &low_speed);
        if (low_speed) {
            flags |= TVO_FLAG_LOW_SPEED;
        }
        accel[r] = clamp(accel[r], cfg->accel_max_mps2, TVO_FLAG_ACCEL_SATURATED, &flags);
        next->turn_rate_radps[r] = clamp(turn_rate, cfg->omega_max_radps, TVO_FLAG_OMEGA_SATURATED, &flags);
        /* Anti-windup: the integrator state itself is limited, so no excess accumulates. */
        speed_next[r] = clamp(speed_state[r] + accel[r] * ctl->internal.loop.period_s, cfg->speed_max_mps,
                              TVO_FLAG_SPEED_SATURATED, &flags);
        /* Hold the interval average of the speed state, so the held straight-line distance matches
         * the continuous extension to second order in h (end-of-interval speed would lead by a h/2). */
        next->speed_mps[r] = TVO_R(0.5) * (speed_state[r] + speed_next[r]);
        /* The command in force bounds the new one, whatever a measured speed re-synced: the state moves
         * with the command, so the next period's command stays within a_max h of this one too. */
        if (!(TVO_FABS(next->speed_mps[r] - work->in_force->speed_mps[r]) <= ctl->internal.speed_step_max_mps)) {
            flags |= limit_speed_step(ctl, &next->speed_mps[r], &speed_next[r], work->in_force->speed_mps[r]);
        }
        /* x - x is 0 for a finite x, NaN for NaN and the infinities: one test for the command and the speed
         * state it commits (the step bound can make a NaN command finite, never the state). */
        if (isnan((next->speed_mps[r] - next->speed_mps[r]) + (next->turn_rate_radps[r] - next->turn_rate_radps[r]) +
                  (speed_next[r] - speed_next[r]))) {
            st = TVO_REASON_NUMERIC;
        }
    }
    frame->flags = flags;
    return st;
}

/* The loop's commit piece (the clock committed): the filter, the mismatch count, the multipliers, the
 * speed states, the held command and the telemetry. */
TVO_OFF_CHAIN_BODY tvo_reason_t unicycle_commit(void *ctl_any, const tvo_loop_frame_t *frame)
{
    tvo_controller_t *ctl = ctl_any;
    const uint8_t n = STEP_ROBOTS(frame->shape);
    uint32_t flags = frame->flags;
    const tvo_controller_config_t *cfg = &ctl->cfg;
    tvo_controller_work_t *work = &ctl->internal.work;
    const tvo_output_derivs_t *y = &work->output;
    const tvo_real_t *y_accel = work->output_accel;
    const tvo_command_t *next = &work->command;
#if TVO_MAX_EQUALITIES > 0
    const uint8_t primal = work->report.count; /* the objective's primal_dim */
    const uint8_t dual = ctl->internal.loop.objective->dual_dim;
#endif
    if (work->from_rest) {
        unicycle_rest(ctl);
    }
    if (cfg->velocity_source == TVO_VELOCITY_FROM_POSITION) {
        ctl->internal.position_velocity->commit(ctl); /* init set it for this source */
    }
    tvo_controller_telemetry_t *tm = &ctl->telemetry;
#if TVO_MAX_EQUALITIES > 0
    for (uint8_t q = 0; q < dual && q < TVO_MAX_EQUALITIES; ++q) {
        /* Exact for the constant nu'' the law asked for over the period. */
        const tvo_real_t accel_q = y_accel[primal + q];
        ctl->internal.multiplier[q] += (ctl->internal.multiplier_rate[q] + TVO_R(0.5) * accel_q * ctl->internal.loop.period_s) * ctl->internal.loop.period_s;
        ctl->internal.multiplier_rate[q] += accel_q * ctl->internal.loop.period_s;
        tm->multiplier[q] = ctl->internal.multiplier[q];
    }
#endif
    ctl->internal.held.flags = flags;
    tm->objective_time_s = work->time.t_s;
    /* Robot by robot, the entries this problem uses (the rest of the telemetry stays zero from init): a
     * robot's pair of each array moves as one 8-byte transfer, and a size build runs one loop. */
    for (uint8_t r = 0; r < n; ++r) {
        ctl->internal.speed_state_mps[r] = work->speed_next[r];
        tm->accel_mps2[r] = work->accel[r];
        ctl->internal.held.speed_mps[r] = next->speed_mps[r];
        ctl->internal.held.turn_rate_radps[r] = next->turn_rate_radps[r];
        const uint8_t x = (uint8_t)(2u * r); /* the robot's x entry; y follows it */
        tm->output_m[x] = y->d[0][x];
        tm->output_m[x + 1u] = y->d[0][x + 1u];
        tm->output_rate_mps[x] = y->d[1][x];
        tm->output_rate_mps[x + 1u] = y->d[1][x + 1u];
        tm->output_accel_mps2[x] = y_accel[x];
        tm->output_accel_mps2[x + 1u] = y_accel[x + 1u];
        tm->gradient[x] = work->gradient[x];
        tm->gradient[x + 1u] = work->gradient[x + 1u];
        tm->gradient_rate[x] = work->gradient_rate[x];
        tm->gradient_rate[x + 1u] = work->gradient_rate[x + 1u];
    }
    tm->regularization = work->report.regularization;
    const tvo_shared_values_t *shared = &work->law.shared;
    if (shared->owner != NULL) { /* a barrier term asked for the schedules: c(t), s(t) at the law's time */
        tm->barrier_c = shared->schedule.c.c[0];
        tm->barrier_slack = shared->schedule.slack.c[0];
    }
    /* The common period: no contradiction, none counted, no stop running (nothing to write). */
    if ((frame->note | ctl->internal.speed_mismatch_periods | ctl->internal.speed_mismatch_holdoff) != 0u) {
        return commit_speed_mismatch(ctl, frame->note);
    }
    return TVO_REASON_NONE;
}

/* Where the loop's parts live in the unicycle's types. */
static tvo_loop_state_t *unicycle_state(void *ctl)
{
    return &((tvo_controller_t *)ctl)->internal.loop;
}

static const tvo_loop_state_t *unicycle_state_of(const void *ctl)
{
    return &((const tvo_controller_t *)ctl)->internal.loop;
}

static tvo_period_t *unicycle_period(void *ctl)
{
    return &((tvo_controller_t *)ctl)->internal.work.period;
}

static void *unicycle_held(void *ctl)
{
    return &((tvo_controller_t *)ctl)->internal.held;
}

static tvo_loop_mark_t unicycle_mark(void *cmd_any)
{
    tvo_command_t *cmd = cmd_any;
    const tvo_loop_mark_t mark = {&cmd->flags, &cmd->outcome, &cmd->reason, offsetof(tvo_command_t, flags)};
    return mark;
}

static uint32_t unicycle_stamp_tick(const void *meas)
{
    return ((const tvo_measurement_t *)meas)->stamp_tick;
}

static const tvo_real_t *unicycle_positions(const void *meas)
{
    return ((const tvo_measurement_t *)meas)->position_m[0];
}

static const tvo_loop_plant_t unicycle_plant = {
    .controller_size = sizeof(tvo_controller_t), .command_size = sizeof(tvo_command_t),
    .state = unicycle_state, .state_of = unicycle_state_of, .period = unicycle_period, .held = unicycle_held, .mark = unicycle_mark,
    .stamp_tick = unicycle_stamp_tick, .positions = unicycle_positions,
    .check = check_measurement, .refusal = unicycle_refusal, .prepare = unicycle_prepare, .law = unicycle_law,
    .command = unicycle_command, .commit = unicycle_commit, .refuse = unicycle_refuse, .rest = unicycle_rest};

tvo_status_t tvo_controller_step(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                 uint32_t apply_tick, tvo_command_t *cmd)
{
    if (meas == NULL) {
        return tvo_controller_miss(ctl, apply_tick, cmd); /* its period record in its own frame */
    }
    const tvo_status_t st = loop_ready(&unicycle_plant, ctl, cmd);
    if (st != TVO_OK) {
        return st;
    }
#if TVO_SHAPE_COPIES
    if (ctl->cfg.robot_count == 1u) {
        return loop_period(&unicycle_plant, ctl, meas, apply_tick, cmd, 1u);
    }
#if TVO_MAX_ROBOTS >= 2
    if (ctl->cfg.robot_count == 2u) {
        return loop_period(&unicycle_plant, ctl, meas, apply_tick, cmd, 2u);
    }
#endif
#endif
    return loop_period(&unicycle_plant, ctl, meas, apply_tick, cmd, STEP_ROBOTS(ctl->cfg.robot_count));
}

tvo_status_t tvo_controller_miss(tvo_controller_t *ctl, uint32_t apply_tick, tvo_command_t *cmd)
{
    return loop_miss(&unicycle_plant, ctl, apply_tick, cmd);
}

tvo_status_t tvo_controller_refuse(tvo_controller_t *ctl, tvo_reason_t reason, tvo_command_t *cmd)
{
    return loop_refuse_unplaced(&unicycle_plant, ctl, reason, cmd);
}

tvo_status_t tvo_controller_check(const tvo_controller_t *ctl, const tvo_measurement_t *meas, uint32_t apply_tick,
                                  tvo_reason_t *reason)
{
    return loop_check(&unicycle_plant, ctl, meas, apply_tick, reason);
}

tvo_status_t tvo_controller_safe_stop(tvo_controller_t *ctl, tvo_command_t *cmd)
{
    return loop_safe_stop(&unicycle_plant, ctl, cmd);
}

tvo_status_t tvo_controller_sample_tick(const tvo_controller_t *ctl, uint32_t apply_tick, uint32_t *sample_tick)
{
    if (ctl == NULL || sample_tick == NULL) {
        return TVO_ERR_NULL;
    }
    if (!ctl->internal.loop.initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    *sample_tick = apply_tick - ctl->cfg.delay_ticks;
    return TVO_OK;
}

tvo_status_t tvo_controller_objective_ticks(const tvo_controller_t *ctl, uint32_t tick, uint64_t *objective_ticks)
{
    if (ctl == NULL || objective_ticks == NULL) {
        return TVO_ERR_NULL;
    }
    if (!ctl->internal.loop.initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    return tvo_sample_clock_objective_ticks(&ctl->internal.loop.clock, tick, objective_ticks);
}
