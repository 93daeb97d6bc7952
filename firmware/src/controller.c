/*
 * Sampled-data TV-O controller for N unicycles; see tvo/controller.h for the timing contract.
 *
 * One step: validate the measurement -> predict each pose over its age with the held command
 * -> estimate y' -> the law (y'') -> the flat map (v', omega) -> limits -> integrate the speed
 * state over the period -> hold the new command.
 */
#include "tvo/controller.h"

#include <string.h>

#include "law_step.h"
#include "position_velocity.h"
#include "sample_clock_kernel.h"
#include "shape.h"
#include "unicycle_kernel.h"
#include "tvo/trig.h"

tvo_status_t tvo_controller_config_default(tvo_controller_config_t *cfg)
{
    if (cfg == NULL) {
        return TVO_ERR_NULL;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->tick_hz = 1000000u;
    cfg->period_ticks = 10000u;
    cfg->delay_ticks = 5000u;
    cfg->robot_count = 1u;
    cfg->delay_compensation = 1u;
    cfg->zoh_aware = 0u;
    cfg->velocity_source = TVO_VELOCITY_FROM_POSE;
    cfg->filter_tf_s = TVO_R(0.05);
    cfg->gain_kp = TVO_R(40.0);
    cfg->gain_kd = TVO_R(13.0);
    cfg->omega_max_radps = TVO_R(2.0) * TVO_PI;
    cfg->accel_max_mps2 = TVO_R(15.0);
    cfg->speed_max_mps = TVO_R(5.0);
    cfg->min_speed_mps = TVO_R(0.05);
    cfg->watchdog_periods = 10u;
    return TVO_OK;
}

static int positive_finite(tvo_real_t v)
{
    return isfinite(v) && v > TVO_R(0.0);
}

/* position_velocity: the position-only source's estimate, NULL if the caller does not offer it. */
static tvo_param_t first_bad_param(const tvo_controller_config_t *cfg, const tvo_objective_t *objective,
                                   tvo_position_velocity_fn position_velocity)
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
    if (!positive_finite(cfg->filter_tf_s)) {
        return TVO_PARAM_FILTER_TF;
    }
    if (!positive_finite(cfg->gain_kp) || !positive_finite(cfg->gain_kd)) {
        return TVO_PARAM_GAINS; /* s^2 + kd s + kp is Hurwitz iff both are positive */
    }
    const tvo_real_t gains[2] = {cfg->gain_kp, cfg->gain_kd};
    if (tvo_law_check_sampling_reach(2u, gains, tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz)) != TVO_OK) {
        return TVO_PARAM_GAINS;
    }
    if (!positive_finite(cfg->omega_max_radps)) {
        return TVO_PARAM_OMEGA_MAX;
    }
    if (!positive_finite(cfg->accel_max_mps2)) {
        return TVO_PARAM_ACCEL_MAX;
    }
    if (!positive_finite(cfg->speed_max_mps)) {
        return TVO_PARAM_SPEED_MAX;
    }
    if (!positive_finite(cfg->min_speed_mps) || !(cfg->min_speed_mps < cfg->speed_max_mps)) {
        return TVO_PARAM_MIN_SPEED;
    }
    if (!tvo_sample_clock_watchdog_ok(cfg->period_ticks, cfg->watchdog_periods)) {
        return TVO_PARAM_WATCHDOG;
    }
    for (uint8_t r = 0; r < cfg->robot_count; ++r) {
        if (!isfinite(cfg->initial_speed_mps[r]) || TVO_FABS(cfg->initial_speed_mps[r]) > cfg->speed_max_mps) {
            return TVO_PARAM_INITIAL_SPEED;
        }
    }
    if (objective->primal_dim != 2u * cfg->robot_count || objective->term_count == 0u) {
        return TVO_PARAM_OBJECTIVE;
    }
    return TVO_PARAM_NONE;
}

/* Validates, binds and starts the controller, all but marking it initialised and the position-only
 * source's filter (position_velocity: that source's estimate, NULL when the caller does not link it). */
static tvo_status_t controller_setup(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                     const tvo_objective_t *objective, uint32_t epoch_tick,
                                     tvo_param_t *bad_param, tvo_position_velocity_fn position_velocity)
{
    if (bad_param != NULL) {
        *bad_param = TVO_PARAM_NONE;
    }
    if (ctl == NULL || cfg == NULL || objective == NULL) {
        return TVO_ERR_NULL;
    }
    memset(ctl, 0, sizeof(*ctl));
    const tvo_param_t bad = first_bad_param(cfg, objective, position_velocity);
    if (bad != TVO_PARAM_NONE) {
        if (bad_param != NULL) {
            *bad_param = bad;
        }
        return TVO_ERR_PARAM;
    }
    ctl->cfg = *cfg;
    ctl->objective = objective;
    ctl->position_velocity = position_velocity;
    ctl->period_s = tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz);
    ctl->speed_step_max_mps = cfg->accel_max_mps2 * ctl->period_s;
    ctl->measured_speed_limit_mps = TVO_MEASURED_SPEED_FACTOR * cfg->speed_max_mps + TVO_MEASURED_SPEED_MARGIN_MPS;
    const tvo_real_t gains[2] = {cfg->gain_kp, cfg->gain_kd};
    const tvo_status_t st = tvo_law_init(&ctl->law, 2u, objective->dim, gains);
    if (st != TVO_OK) {
        if (bad_param != NULL) {
            *bad_param = TVO_PARAM_OBJECTIVE;
        }
        return st;
    }
    /* The timing was validated above: the clock cannot reject it. */
    (void)tvo_sample_clock_init(&ctl->clock, cfg->tick_hz, cfg->period_ticks, cfg->watchdog_periods, epoch_tick);
    for (uint8_t r = 0; r < cfg->robot_count; ++r) {
        ctl->speed_state_mps[r] = cfg->initial_speed_mps[r];
        ctl->held.speed_mps[r] = cfg->initial_speed_mps[r];
    }
    return TVO_OK;
}

tvo_status_t tvo_controller_init(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                 const tvo_objective_t *objective, uint32_t epoch_tick,
                                 tvo_param_t *bad_param)
{
    tvo_status_t st = controller_setup(ctl, cfg, objective, epoch_tick, bad_param, controller_position_velocity);
    if (st == TVO_OK) {
        st = tvo_dirty_derivative_init(&ctl->velocity_filter, objective->primal_dim, cfg->filter_tf_s, ctl->period_s);
        if (st != TVO_OK && bad_param != NULL) {
            *bad_param = TVO_PARAM_OBJECTIVE;
        }
        ctl->initialized = st == TVO_OK;
    }
    return st;
}

tvo_status_t tvo_controller_init_pose_velocity(tvo_controller_t *ctl, const tvo_controller_config_t *cfg,
                                               const tvo_objective_t *objective, uint32_t epoch_tick,
                                               tvo_param_t *bad_param)
{
    const tvo_status_t st = controller_setup(ctl, cfg, objective, epoch_tick, bad_param, NULL);
    if (st == TVO_OK) {
        ctl->initialized = 1;
    }
    return st;
}

/* Why a measurement failed the range check, off the common path: not finite if the sum of the robots'
 * values is not (a field the configuration does not read included), else out of range. */
TVO_COLD_BODY tvo_status_t measurement_range_refusal(const tvo_controller_t *ctl, const tvo_measurement_t *meas)
{
    tvo_real_t probe = TVO_R(0.0);
    for (uint8_t r = 0; r < ctl->cfg.robot_count && r < TVO_MAX_ROBOTS; ++r) {
        probe += meas->position_m[r][0] + meas->position_m[r][1] + meas->heading_rad[r] + meas->speed_mps[r];
    }
    return isfinite(probe - probe) ? TVO_ERR_IMPLAUSIBLE_MEASUREMENT : TVO_ERR_NOT_FINITE;
}

static inline tvo_status_t check_measurement(const tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                      uint32_t apply_tick)
{
    if (meas == NULL) {
        return TVO_ERR_NO_MEASUREMENT;
    }
    const uint8_t n = ctl->cfg.robot_count;
    const tvo_real_t speed_limit = ctl->measured_speed_limit_mps;
    for (uint8_t r = 0; r < n; ++r) {
        /* One comparison per value refuses NaN, infinities and the impossible alike (NaN compares false). */
        if (!(TVO_FABS(meas->position_m[r][0]) <= TVO_POSITION_LIMIT_M) ||
            !(TVO_FABS(meas->position_m[r][1]) <= TVO_POSITION_LIMIT_M) ||
            (meas->heading_valid && !(TVO_FABS(meas->heading_rad[r]) <= TVO_HEADING_LIMIT_RAD)) ||
            (meas->speed_valid && !(TVO_FABS(meas->speed_mps[r]) <= speed_limit))) {
            return TVO_ERR_IMPLAUSIBLE_MEASUREMENT; /* or not finite: measurement_range_refusal says which */
        }
    }
    const tvo_status_t st = sample_clock_check_stamp(&ctl->clock, meas->stamp_tick, apply_tick);
    if (st != TVO_OK) {
        return st;
    }
    if (ctl->cfg.velocity_source == TVO_VELOCITY_FROM_POSE) {
        if (!meas->heading_valid) {
            return TVO_ERR_MISSING_FIELD;
        }
    } else if (ctl->position_velocity == NULL) {
        return TVO_ERR_NOT_INITIALIZED; /* the source was set by hand after tvo_controller_init_pose_velocity */
    }
    return TVO_OK;
}

/* What a good step after the watchdog's gap takes as the command in force: the robots were stopped. */
static const tvo_command_t rest_command = {{TVO_R(0.0)}, {TVO_R(0.0)}, 0u};

static void stop_command(tvo_command_t *cmd, uint32_t flags)
{
    memset(cmd, 0, sizeof(*cmd));
    cmd->flags = flags;
}

static tvo_real_t clamp(tvo_real_t v, tvo_real_t limit, uint32_t flag, uint32_t *flags)
{
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

/* The robots stop: speed states, the dual dynamics and the held command go to zero. */
static void drop_to_rest(tvo_controller_t *ctl, tvo_command_t *cmd)
{
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        ctl->speed_state_mps[r] = TVO_R(0.0);
    }
    for (uint8_t q = 0; q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES); ++q) {
        ctl->multiplier_rate[q] = TVO_R(0.0);
    }
    ctl->speed_mismatch_periods = 0u;
    ctl->speed_mismatch_holdoff = 0u;
    stop_command(&ctl->held, 0u);
    stop_command(cmd, TVO_FLAG_SAFE_STOP);
}

/* The command in force, flagged HOLDING (zero once the robots were stopped). */
static void hold_command(const tvo_controller_t *ctl, tvo_command_t *cmd)
{
    *cmd = ctl->held;
    cmd->flags = TVO_FLAG_HOLDING;
}

/* A period counted without a good step (committed): held, or stopped once the watchdog expires. */
static tvo_status_t miss_period(tvo_controller_t *ctl, const tvo_period_t *period, tvo_command_t *cmd)
{
    if (tvo_sample_clock_end(&ctl->clock, period, 0, 0u)) {
        drop_to_rest(ctl, cmd);
        return TVO_ERR_WATCHDOG;
    }
    hold_command(ctl, cmd);
    return TVO_ERR_NO_MEASUREMENT;
}

/* A step that cannot use its measurement (or its law result), committing nothing: the refusal named
 * and the command in force. The one exception is the watchdog's stop: when counting the period would
 * expire it, the period is counted and the robots stop (the stop is the state the plant is left in). */
TVO_COLD_BODY tvo_status_t refuse_step(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                       const tvo_period_t *period, tvo_status_t reason, tvo_command_t *cmd)
{
    if (sample_clock_refusal_stops(&ctl->clock, period)) {
        (void)miss_period(ctl, period, cmd);
        return TVO_ERR_WATCHDOG;
    }
    hold_command(ctl, cmd);
    return (reason == TVO_ERR_IMPLAUSIBLE_MEASUREMENT) ? measurement_range_refusal(ctl, meas) : reason;
}

/* A good step after the watchdog's gap: what the stop leaves at rest (the speed states and the held
 * command the step read as zero) is committed so. */
TVO_COLD_BODY void commit_rest(tvo_controller_t *ctl)
{
    for (uint8_t q = 0; q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES); ++q) {
        ctl->multiplier_rate[q] = TVO_R(0.0);
    }
    ctl->speed_mismatch_periods = 0u;
    ctl->speed_mismatch_holdoff = 0u;
}

/* The command's speed moved beyond accel_max h from the one in force (a measured speed's re-sync):
 * held to the bound, the speed state moved with it. Returns the flag it sets. */
TVO_COLD_BODY uint32_t limit_speed_step(const tvo_controller_t *ctl, tvo_real_t *speed_mps, tvo_real_t *speed_next_mps,
                                        tvo_real_t held_speed_mps)
{
    const tvo_real_t step = *speed_mps - held_speed_mps;
    const tvo_real_t bound = step > TVO_R(0.0) ? ctl->speed_step_max_mps : -ctl->speed_step_max_mps;
    uint32_t unused = 0u;
    *speed_mps = held_speed_mps + bound;
    *speed_next_mps = clamp(*speed_next_mps - (step - bound), ctl->cfg.speed_max_mps, 0u, &unused);
    return TVO_FLAG_ACCEL_SATURATED;
}

/* A period of the speed mismatch's stop, after the period's commit: accepted (clock, filters,
 * multipliers move on), but the robots stand still. */
TVO_COLD_BODY tvo_status_t hold_mismatch_stop(tvo_controller_t *ctl, tvo_command_t *cmd)
{
    ctl->speed_mismatch_holdoff--;
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        ctl->speed_state_mps[r] = TVO_R(0.0);
        ctl->telemetry.accel_mps2[r] = TVO_R(0.0);
    }
    for (uint8_t q = 0; q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES); ++q) {
        ctl->multiplier_rate[q] = TVO_R(0.0);
    }
    stop_command(&ctl->held, TVO_FLAG_SAFE_STOP | TVO_FLAG_SPEED_MISMATCH);
    *cmd = ctl->held;
    return TVO_OK;
}

/* The step before the law, for a period the clock has begun: the measurement checked, the state and
 * time the law is evaluated at (work->output, work->time), *flags and *speed_contradicted. */
TVO_OFF_CHAIN_BODY tvo_status_t step_before_law(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                                uint32_t apply_tick, const uint8_t n, uint32_t *flags_out,
                                                int *speed_contradicted_out)
{
    const tvo_controller_config_t *cfg = &ctl->cfg;
    tvo_controller_work_t *work = &ctl->work;
    tvo_period_t *period = &work->period;
    tvo_status_t st = check_measurement(ctl, meas, apply_tick);
    if (st != TVO_OK) {
        return st;
    }
    /* Where the law is evaluated and how far the sampled state is carried there (the age to the
     * application instant with compensation, half a period on when ZOH-aware). */
    sample_clock_locate(&ctl->clock, period, meas->stamp_tick, cfg->delay_compensation, cfg->zoh_aware);
    const int position_only = cfg->velocity_source == TVO_VELOCITY_FROM_POSITION;
    if (position_only) {
        st = ctl->position_velocity(ctl, meas); /* init set it for this source */
        if (st != TVO_OK) {
            return st;
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
    for (uint8_t r = 0; r < n && st == TVO_OK; ++r) {
        speed_state[r] = from_rest ? TVO_R(0.0) : ctl->speed_state_mps[r];
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
            unicycle_predict_unchecked(&pose, in_force->speed_mps[r], in_force->turn_rate_radps[r], carry_s, &pose,
                                       heading_cs[r]);
        } else {
            tvo_sincos(pose.heading_rad, &heading_cs[r][1], &heading_cs[r][0]);
        }
        heading[r] = pose.heading_rad;
        /* Mid-interval speed: the state plus half a period of the last acceleration (O(h^2)). */
        speed[r] = speed_state[r] +
                   (zoh_aware && !from_rest ? TVO_R(0.5) * ctl->period_s * ctl->telemetry.accel_mps2[r] : TVO_R(0.0));
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
    const uint8_t primal = ctl->objective->primal_dim;
    const uint8_t dual = ctl->objective->dual_dim;
    for (uint8_t q = 0; q < dual && q < TVO_MAX_EQUALITIES; ++q) {
        y->d[0][primal + q] = ctl->multiplier[q];
        y->d[1][primal + q] = from_rest ? TVO_R(0.0) : ctl->multiplier_rate[q];
    }
#endif

    *flags_out = flags;
    *speed_contradicted_out = speed_contradicted;
    return st;
}

/* The step after the law: the flat map, the limits, and on success the period's commit. */
TVO_OFF_CHAIN_BODY tvo_status_t step_after_law(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                               tvo_command_t *cmd, const uint8_t n, uint32_t flags,
                                               int speed_contradicted)
{
    const tvo_controller_config_t *cfg = &ctl->cfg;
    tvo_controller_work_t *work = &ctl->work;
    tvo_period_t *period = &work->period;
    const int position_only = cfg->velocity_source == TVO_VELOCITY_FROM_POSITION;
    const tvo_output_derivs_t *y = &work->output;
    const tvo_time_jet_t *t = &work->time;
    const tvo_real_t *y_accel = work->output_accel;
    const tvo_real_t *heading = work->heading;
    tvo_real_t(*heading_cs)[2] = work->heading_cs;
    const tvo_real_t *speed = work->speed;
    const tvo_real_t *speed_state = work->speed_state;
#if TVO_MAX_EQUALITIES > 0
    const uint8_t primal = work->report.count; /* the objective's primal_dim */
    const uint8_t dual = ctl->objective->dual_dim;
#endif
    const tvo_real_t carry_s = period->carry_s;
    tvo_command_t *next = &work->command; /* robots 0..n-1; the held command's others stay zero */
    tvo_status_t st = TVO_OK;
    tvo_real_t *speed_next = work->speed_next;
    tvo_real_t *accel = work->accel;
    for (uint8_t r = 0; r < n && st == TVO_OK; ++r) {
        uint8_t low_speed = 0;
        tvo_real_t turn_rate;
        unicycle_flat_map_unchecked(heading_cs[r], speed[r], &y_accel[2u * r], cfg->min_speed_mps, &accel[r],
                                    &turn_rate, &low_speed);
        if (low_speed) {
            flags |= TVO_FLAG_LOW_SPEED;
        }
        accel[r] = clamp(accel[r], cfg->accel_max_mps2, TVO_FLAG_ACCEL_SATURATED, &flags);
        next->turn_rate_radps[r] = clamp(turn_rate, cfg->omega_max_radps, TVO_FLAG_OMEGA_SATURATED, &flags);
        /* Anti-windup: the integrator state itself is limited, so no excess accumulates. */
        speed_next[r] = clamp(speed_state[r] + accel[r] * ctl->period_s, cfg->speed_max_mps,
                              TVO_FLAG_SPEED_SATURATED, &flags);
        /* Hold the interval average of the speed state, so the held straight-line distance matches
         * the continuous extension to second order in h (end-of-interval speed would lead by a h/2). */
        next->speed_mps[r] = TVO_R(0.5) * (speed_state[r] + speed_next[r]);
        /* The command in force bounds the new one, whatever a measured speed re-synced: the state moves
         * with the command, so the next period's command stays within a_max h of this one too. */
        if (!(TVO_FABS(next->speed_mps[r] - work->in_force->speed_mps[r]) <= ctl->speed_step_max_mps)) {
            flags |= limit_speed_step(ctl, &next->speed_mps[r], &speed_next[r], work->in_force->speed_mps[r]);
        }
        if (!isfinite(next->speed_mps[r]) || !isfinite(next->turn_rate_radps[r])) {
            st = TVO_ERR_NUMERIC;
        }
    }

    if (st != TVO_OK) {
        return refuse_step(ctl, meas, period, st, cmd);
    }
    /* The step succeeded: from here on its working copies become the controller's state. */
    if (work->from_rest) {
        commit_rest(ctl);
    }
    sample_clock_end_good(&ctl->clock, period, meas->stamp_tick);
    if (position_only) {
        ctl->velocity_filter = work->velocity_filter;
        for (uint8_t r = 0; r < n; ++r) {
            /* The estimate lives at the application instant; the next sample dead-reckons from here. */
            ctl->heading_estimate_rad[r] =
                unicycle_wrap_angle_near(heading[r] + work->in_force->turn_rate_radps[r] * (period->age_s - carry_s));
        }
    }
    ctl->speed_mismatch_periods = speed_contradicted ? ctl->speed_mismatch_periods + 1u : 0u;
    if (ctl->speed_mismatch_periods >= TVO_SPEED_MISMATCH_PERIODS) {
        flags |= TVO_FLAG_SPEED_MISMATCH;
        if (ctl->speed_mismatch_periods >= TVO_SPEED_MISMATCH_STOP_PERIODS) {
            ctl->speed_mismatch_periods = 0u;
            ctl->speed_mismatch_holdoff = TVO_SPEED_MISMATCH_HOLDOFF_PERIODS;
        }
    }
    tvo_controller_telemetry_t *tm = &ctl->telemetry;
#if TVO_MAX_EQUALITIES > 0
    for (uint8_t q = 0; q < dual && q < TVO_MAX_EQUALITIES; ++q) {
        /* Exact for the constant nu'' the law asked for over the period. */
        const tvo_real_t accel_q = y_accel[primal + q];
        ctl->multiplier[q] += (ctl->multiplier_rate[q] + TVO_R(0.5) * accel_q * ctl->period_s) * ctl->period_s;
        ctl->multiplier_rate[q] += accel_q * ctl->period_s;
        tm->multiplier[q] = ctl->multiplier[q];
    }
#endif
    for (uint8_t r = 0; r < n; ++r) {
        ctl->speed_state_mps[r] = speed_next[r];
        tm->accel_mps2[r] = accel[r];
    }
    for (uint8_t r = 0; r < n; ++r) {
        ctl->held.speed_mps[r] = next->speed_mps[r];
        ctl->held.turn_rate_radps[r] = next->turn_rate_radps[r];
    }
    ctl->held.flags = flags;
    *cmd = ctl->held;

    /* Telemetry of the entries this problem uses (the rest stay zero from init). */
    tm->objective_time_s = t->t_s;
    for (uint8_t i = 0; i < 2u * n; ++i) {
        tm->output_m[i] = y->d[0][i];
        tm->output_rate_mps[i] = y->d[1][i];
        tm->output_accel_mps2[i] = y_accel[i];
        tm->gradient[i] = work->gradient[i];
        tm->gradient_rate[i] = work->gradient_rate[i];
    }
    tm->regularization = work->report.regularization;
    if (ctl->speed_mismatch_holdoff > 0u) {
        return hold_mismatch_stop(ctl, cmd);
    }
    return TVO_OK;
}

/* The step of an initialised controller driving n robots (n = cfg.robot_count): before the law, the
 * law, after it, with only what crosses the law's call in this frame. */
TVO_SHAPE_BODY tvo_status_t step_shape(tvo_controller_t *ctl, const tvo_measurement_t *meas, uint32_t apply_tick,
                                       tvo_command_t *cmd, const uint8_t n)
{
    /* The period's timing: apply ticks must advance; elapsed time never wraps. */
    tvo_controller_work_t *work = &ctl->work;
    if (sample_clock_begin(&ctl->clock, apply_tick, &work->period) != TVO_OK) {
        hold_command(ctl, cmd);
        return TVO_ERR_OUT_OF_ORDER;
    }
    work->from_rest = ctl->clock.stopped;
    work->in_force = work->from_rest ? &rest_command : &ctl->held;
    uint32_t flags = 0u;
    int speed_contradicted = 0;
    tvo_status_t st = step_before_law(ctl, meas, apply_tick, n, &flags, &speed_contradicted);
    if (st == TVO_OK) {
        tvo_law_report_t *report = &work->report;
        report->gradient = work->gradient;
        report->gradient_rate = work->gradient_rate;
        report->count = ctl->objective->primal_dim;
        st = law_evaluate_report_unchecked(&ctl->law, ctl->objective, &work->output, &work->time,
                                           work->output_accel, report, &work->law);
        if (report->regularization > TVO_R(0.0)) {
            flags |= TVO_FLAG_REGULARIZED;
        }
    }
    if (st != TVO_OK) {
        return refuse_step(ctl, meas, &work->period, st, cmd);
    }
    return step_after_law(ctl, meas, cmd, n, flags, speed_contradicted);
}

tvo_status_t tvo_controller_step(tvo_controller_t *ctl, const tvo_measurement_t *meas,
                                 uint32_t apply_tick, tvo_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    if (ctl == NULL) {
        stop_command(cmd, TVO_FLAG_SAFE_STOP);
        return TVO_ERR_NULL;
    }
    if (!ctl->initialized) {
        stop_command(cmd, TVO_FLAG_SAFE_STOP);
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (meas == NULL) {
        return tvo_controller_miss(ctl, apply_tick, cmd);
    }
#if TVO_SHAPE_COPIES
    if (ctl->cfg.robot_count == 1u) {
        return step_shape(ctl, meas, apply_tick, cmd, 1u);
    }
#if TVO_MAX_ROBOTS >= 2
    if (ctl->cfg.robot_count == 2u) {
        return step_shape(ctl, meas, apply_tick, cmd, 2u);
    }
#endif
#endif
    return step_shape(ctl, meas, apply_tick, cmd, ctl->cfg.robot_count);
}

tvo_status_t tvo_controller_miss(tvo_controller_t *ctl, uint32_t apply_tick, tvo_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    if (ctl == NULL || !ctl->initialized) {
        stop_command(cmd, TVO_FLAG_SAFE_STOP);
        return (ctl == NULL) ? TVO_ERR_NULL : TVO_ERR_NOT_INITIALIZED;
    }
    tvo_period_t period;
    if (sample_clock_begin(&ctl->clock, apply_tick, &period) != TVO_OK) {
        hold_command(ctl, cmd);
        return TVO_ERR_OUT_OF_ORDER;
    }
    return miss_period(ctl, &period, cmd);
}

tvo_status_t tvo_controller_check(const tvo_controller_t *ctl, const tvo_measurement_t *meas, uint32_t apply_tick)
{
    if (ctl == NULL) {
        return TVO_ERR_NULL;
    }
    if (!ctl->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    tvo_period_t period;
    if (tvo_sample_clock_begin(&ctl->clock, apply_tick, &period) != TVO_OK) {
        return TVO_ERR_OUT_OF_ORDER;
    }
    const tvo_status_t st = check_measurement(ctl, meas, apply_tick);
    return (st == TVO_ERR_IMPLAUSIBLE_MEASUREMENT) ? measurement_range_refusal(ctl, meas) : st;
}

tvo_status_t tvo_controller_safe_stop(tvo_controller_t *ctl, tvo_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    if (ctl == NULL || !ctl->initialized) {
        stop_command(cmd, TVO_FLAG_SAFE_STOP);
        return (ctl == NULL) ? TVO_ERR_NULL : TVO_ERR_NOT_INITIALIZED;
    }
    (void)tvo_sample_clock_expire(&ctl->clock);
    drop_to_rest(ctl, cmd);
    return TVO_OK;
}

tvo_status_t tvo_controller_sample_tick(const tvo_controller_t *ctl, uint32_t apply_tick, uint32_t *sample_tick)
{
    if (ctl == NULL || sample_tick == NULL) {
        return TVO_ERR_NULL;
    }
    if (!ctl->initialized) {
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
    if (!ctl->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    return tvo_sample_clock_objective_ticks(&ctl->clock, tick, objective_ticks);
}
