/* Sampled-data controller of the integrator-chain testbed; see tvo/chain_controller.h. */
#include "internal/chain_controller.h"

#include <string.h>

#include "tvo/defaults.h"

#include "internal/law.h"
#include "internal/real_bits.h"
#include "sampled_loop.h"

tvo_status_t tvo_chain_config_default(tvo_chain_config_t *cfg)
{
    static const tvo_chain_config_t defaults = {
        TVO_LOOP_CONFIG_DEFAULTS, .relative_degree = 2u, .filter_tf_s = (tvo_real_t)TVO_DEFAULT_FILTER_TF_S,
        .gain = {(tvo_real_t)TVO_DEFAULT_CHAIN_GAIN_0, (tvo_real_t)TVO_DEFAULT_CHAIN_GAIN_1},
        .input_max = (tvo_real_t)TVO_DEFAULT_CHAIN_INPUT_MAX};
    if (cfg == NULL) {
        return TVO_ERR_NULL;
    }
    *cfg = defaults;
    return TVO_OK;
}

const char *tvo_chain_param_str(tvo_chain_param_t param)
{
    switch (param) {
    case TVO_CHAIN_PARAM_NONE: return "none";
    case TVO_CHAIN_PARAM_TICK_HZ: return "tick_hz";
    case TVO_CHAIN_PARAM_PERIOD: return "period_ticks";
    case TVO_CHAIN_PARAM_DELAY: return "delay_ticks";
    case TVO_CHAIN_PARAM_RELATIVE_DEGREE: return "relative_degree";
    case TVO_CHAIN_PARAM_GAIN: return "gain";
    case TVO_CHAIN_PARAM_FILTER_TF: return "filter_tf_s";
    case TVO_CHAIN_PARAM_INPUT_MAX: return "input_max";
    case TVO_CHAIN_PARAM_WATCHDOG: return "watchdog_periods";
    case TVO_CHAIN_PARAM_OBJECTIVE: return "objective";
    default: return "unknown parameter";
    }
}

static tvo_chain_param_t first_bad_param(const tvo_chain_config_t *cfg, const tvo_objective_t *objective)
{
    /* The sample clock names the timing fields the controllers share in tvo_param_t's words. */
    const tvo_param_t timing = tvo_sample_clock_check_timing(cfg->tick_hz, cfg->period_ticks, cfg->delay_ticks);
    if (timing != TVO_PARAM_NONE) {
        return (timing == TVO_PARAM_TICK_HZ) ? TVO_CHAIN_PARAM_TICK_HZ
               : (timing == TVO_PARAM_PERIOD) ? TVO_CHAIN_PARAM_PERIOD
                                              : TVO_CHAIN_PARAM_DELAY;
    }
    if (cfg->relative_degree == 0u || cfg->relative_degree > TVO_MAX_RELATIVE_DEGREE) {
        return TVO_CHAIN_PARAM_RELATIVE_DEGREE;
    }
    if (tvo_law_check_sampling_reach(cfg->relative_degree, cfg->gain,
                                     tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz)) != TVO_OK) {
        return TVO_CHAIN_PARAM_GAIN;
    }
    if (cfg->filtered_derivatives && !(isfinite(cfg->filter_tf_s) && cfg->filter_tf_s > TVO_R(0.0))) {
        return TVO_CHAIN_PARAM_FILTER_TF;
    }
    if (!(isfinite(cfg->input_max) && cfg->input_max > TVO_R(0.0))) {
        return TVO_CHAIN_PARAM_INPUT_MAX;
    }
    if (!tvo_sample_clock_watchdog_ok(cfg->period_ticks, cfg->watchdog_periods) || cfg->watchdog_counts_refusals > 1u) {
        return TVO_CHAIN_PARAM_WATCHDOG;
    }
    if (objective->dual_dim != 0u || objective->term_count == 0u) {
        return TVO_CHAIN_PARAM_OBJECTIVE;
    }
    return TVO_CHAIN_PARAM_NONE;
}

static const tvo_loop_plant_t chain_plant; /* the loop's table, below its pieces */

/* Validates and binds the controller, all but the loop's clock: TVO_CHAIN_PARAM_NONE, or the culprit. */
static tvo_chain_param_t chain_setup(tvo_chain_controller_t *ctl, const tvo_chain_config_t *cfg,
                                     const tvo_objective_t *objective)
{
    const tvo_chain_param_t bad = first_bad_param(cfg, objective);
    if (bad != TVO_CHAIN_PARAM_NONE) {
        return bad;
    }
    if (!tvo_law_gains_hurwitz(cfg->relative_degree, cfg->gain) || objective->primal_dim == 0u ||
        objective->primal_dim > TVO_MAX_Z_DIM) {
        return TVO_CHAIN_PARAM_GAIN;
    }
    tvo_law_init(&ctl->internal.law, cfg->relative_degree, objective->primal_dim, cfg->gain);
    ctl->internal.loop.period_s = tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz);
    for (uint8_t j = 0; j + 1u < cfg->relative_degree; ++j) {
        if (tvo_dirty_derivative_init(&ctl->internal.filter[j], objective->primal_dim,
                                      cfg->filtered_derivatives ? cfg->filter_tf_s : TVO_R(1.0),
                                      ctl->internal.loop.period_s) != TVO_OK) {
            return TVO_CHAIN_PARAM_FILTER_TF;
        }
    }
    ctl->cfg = *cfg;
    ctl->internal.loop.objective = objective;
    return TVO_CHAIN_PARAM_NONE;
}

tvo_status_t tvo_chain_controller_init(tvo_chain_controller_t *ctl, const tvo_chain_config_t *cfg,
                                       const tvo_objective_t *objective, uint32_t epoch_tick,
                                       tvo_chain_param_t *bad_param)
{
    if (bad_param != NULL) {
        *bad_param = TVO_CHAIN_PARAM_NONE;
    }
    const tvo_status_t st = loop_init_begin(&chain_plant, ctl, cfg, objective);
    if (st != TVO_OK) {
        return st;
    }
    const tvo_chain_param_t bad = chain_setup(ctl, cfg, objective);
    if (bad != TVO_CHAIN_PARAM_NONE && bad_param != NULL) {
        *bad_param = bad;
    }
    return loop_init_end(&chain_plant, ctl, (bad == TVO_CHAIN_PARAM_NONE) ? TVO_OK : TVO_ERR_PARAM, cfg->tick_hz,
                         cfg->period_ticks, cfg->watchdog_periods, cfg->watchdog_counts_refusals, epoch_tick);
}

tvo_status_t tvo_chain_predict(uint8_t relative_degree, uint8_t dim, const tvo_output_derivs_t *state,
                               const tvo_real_t *u, tvo_real_t dt_s, tvo_output_derivs_t *out)
{
    if (state == NULL || u == NULL || out == NULL) {
        return TVO_ERR_NULL;
    }
    if (relative_degree == 0u || relative_degree > TVO_MAX_RELATIVE_DEGREE || dim == 0u || dim > TVO_MAX_OUTPUT_DIM) {
        return TVO_ERR_DIMENSION;
    }
    if (!isfinite(dt_s) || dt_s < TVO_R(0.0)) {
        return TVO_ERR_PARAM;
    }
    const uint8_t k = relative_degree;
    for (uint8_t i = 0; i < dim; ++i) {
        /* Taylor polynomial of degree k in dt, exact because y^(k) = u is constant; j ascending
         * reads only entries >= j, which are not yet overwritten when out aliases state. */
        for (uint8_t j = 0; j < k; ++j) {
            tvo_real_t sum = TVO_R(0.0);
            tvo_real_t factor = TVO_R(1.0); /* dt^(m-j) / (m-j)! */
            for (uint8_t m = j; m <= k; ++m) {
                sum += ((m < k) ? state->d[m][i] : u[i]) * factor;
                factor *= dt_s / (tvo_real_t)(m - j + 1u);
            }
            out->d[j][i] = sum;
        }
    }
    return TVO_OK;
}

/* The filters a step reads and keeps: the cascade's k - 1 when the derivatives are filtered, else none
 * (their trial copies would be dead weight on every step). */
static inline uint8_t chain_filters_in_use(const tvo_chain_config_t *cfg)
{
    return cfg->filtered_derivatives ? (uint8_t)(cfg->relative_degree - 1u) : 0u;
}

/* y^(1..k-1) at the sample, from the filters (cascade; the step's working copies in `filter`,
 * kept only when the step succeeds) or as measured. */
static tvo_status_t derivatives_at_sample(const tvo_chain_controller_t *ctl, tvo_dirty_derivative_t *filter,
                                          const tvo_chain_measurement_t *meas, tvo_output_derivs_t *x)
{
    const uint8_t k = ctl->cfg.relative_degree;
    const uint8_t m = ctl->internal.loop.objective->primal_dim;
    *x = meas->y;
    if (!ctl->cfg.filtered_derivatives || k == 1u) {
        return TVO_OK;
    }
    tvo_status_t st = TVO_OK;
    const int primed = filter[0].primed;
    const tvo_real_t dt_s =
        primed ? clock_ticks_to_seconds(meas->stamp_tick - ctl->internal.loop.clock.last_stamp_tick, ctl->cfg.tick_hz) : TVO_R(0.0);
    for (uint8_t j = 0; st == TVO_OK && j + 1u < k; ++j) {
        if (!primed || !filter[j].primed) {
            /* Start at rest: the filters have seen nothing yet. */
            tvo_real_t zero[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
            st = tvo_dirty_derivative_reset(&filter[j], x->d[j], zero);
            for (uint8_t i = 0; i < m; ++i) {
                x->d[j + 1u][i] = TVO_R(0.0);
            }
        } else {
            st = tvo_dirty_derivative_step(&filter[j], x->d[j], dt_s, x->d[j + 1u]);
        }
    }
    return st;
}

/* The loop's check piece: the values the configuration reads (finite, the positions within the
 * workspace), and the stamp. */
static tvo_reason_t chain_check(const void *ctl_any, const void *meas_any, uint32_t apply_tick)
{
    const tvo_chain_controller_t *ctl = ctl_any;
    const tvo_chain_measurement_t *meas = meas_any;
    const uint8_t read = ctl->cfg.filtered_derivatives ? 1u : ctl->cfg.relative_degree;
    const uint8_t m = ctl->internal.loop.objective->primal_dim;
    for (uint8_t j = 0; j < read; ++j) {
        for (uint8_t i = 0; i < m; ++i) {
            if (!isfinite(meas->y.d[j][i])) {
                return TVO_REASON_NOT_FINITE;
            }
        }
    }
    for (uint8_t i = 0; i < m; ++i) {
        if (!real_within(meas->y.d[0][i], TVO_POSITION_LIMIT_M)) {
            return TVO_REASON_IMPLAUSIBLE_MEASUREMENT; /* finite, but no robot's (tvo/config.h's workspace) */
        }
    }
    return sample_clock_check_stamp(&ctl->internal.loop.clock, meas->stamp_tick, apply_tick);
}

/* The loop's refuse piece: its refusal, out of line (a cold path). */
TVO_COLD_BODY void chain_refuse(void *ctl, const void *meas, const tvo_period_t *period, tvo_reason_t reason,
                                void *cmd)
{
    loop_refuse(&chain_plant, ctl, meas, period, reason, cmd);
}

/* What a good step after the watchdog's gap takes as the input in force: the chain was stopped. */
static const tvo_real_t rest_input[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};

/* The loop's prepare piece, for a period the clock has begun: the measurement checked, the filters'
 * trial copies, the state carried to where the law is evaluated, its time; the frame's flags. */
TVO_OFF_CHAIN_BODY tvo_reason_t chain_prepare(void *ctl_any, const void *meas_any, uint32_t apply_tick,
                                              tvo_loop_frame_t *frame)
{
    tvo_chain_controller_t *ctl = ctl_any;
    const tvo_chain_measurement_t *meas = meas_any;
    tvo_chain_controller_work_t *work = &ctl->internal.work;
    tvo_period_t *period = &work->period;
    const tvo_reason_t refused = chain_check(ctl, meas, apply_tick);
    if (refused != TVO_REASON_NONE) {
        return refused;
    }
    tvo_output_derivs_t *x = &work->state;
    tvo_dirty_derivative_t *filter = work->filter; /* kept on success */
    tvo_status_t st;
    {
        for (uint8_t j = 0; j < chain_filters_in_use(&ctl->cfg) && j + 1u < TVO_MAX_RELATIVE_DEGREE; ++j) {
            filter[j] = ctl->internal.filter[j];
            if (frame->from_rest) {
                filter[j].primed = 0; /* the gap makes old filter state meaningless */
            }
        }
        st = derivatives_at_sample(ctl, filter, meas, x);
    }
    if (st != TVO_OK) {
        return loop_reason_of(st);
    }

    const uint8_t k = ctl->cfg.relative_degree;
    const uint8_t m = ctl->internal.loop.objective->primal_dim;
    /* Where the law is evaluated (the sample, the application instant, or the middle of the held
     * interval); the state is carried there with the held command. */
    sample_clock_locate(&ctl->internal.loop.clock, period, meas->stamp_tick, ctl->cfg.delay_compensation, ctl->cfg.zoh_aware);
    frame->flags = (period->carry_s > TVO_R(0.0)) ? TVO_FLAG_PREDICTED : 0u;
    if (period->carry_s > TVO_R(0.0)) {
        st = tvo_chain_predict(k, m, x, frame->from_rest ? rest_input : ctl->internal.held.u, period->carry_s, x);
    }
    time_jet_at_tick_time(&period->law_time, ctl->cfg.tick_hz, TVO_R(1.0), &work->time); /* valid times */
    return loop_reason_of(st);
}

/* The loop's law piece, in the step's own frame. */
TVO_LOOP_ENTRY tvo_reason_t chain_law(void *ctl_any, tvo_loop_frame_t *frame)
{
    tvo_chain_controller_t *ctl = ctl_any;
    tvo_chain_controller_work_t *work = &ctl->internal.work;
    tvo_law_report_t *report = &work->report;
    (void)frame;
    report->gradient = NULL;
    report->gradient_rate = NULL;
    report->count = 0u;
    const tvo_status_t st = tvo_law_evaluate_report(&ctl->internal.law, ctl->internal.loop.objective, &work->state, &work->time,
                                                    work->input, report, &work->law);
    return (st == TVO_OK) ? TVO_REASON_NONE : loop_reason_of(st);
}

/* The loop's command piece: u is the law's y^(k), clipped to the input's limit (work->command). */
TVO_OFF_CHAIN_BODY tvo_reason_t chain_command(void *ctl_any, tvo_loop_frame_t *frame)
{
    tvo_chain_controller_t *ctl = ctl_any;
    tvo_chain_controller_work_t *work = &ctl->internal.work;
    const uint8_t m = ctl->internal.loop.objective->primal_dim;
    const tvo_real_t *u = work->input;
    tvo_chain_command_t *next = &work->command;
    memset(next, 0, sizeof(*next));
    next->flags = frame->flags;
    for (uint8_t i = 0; i < m; ++i) {
        next->u[i] = u[i];
        if (next->u[i] > ctl->cfg.input_max) {
            next->u[i] = ctl->cfg.input_max;
            next->flags |= TVO_FLAG_ACCEL_SATURATED;
        } else if (next->u[i] < -ctl->cfg.input_max) {
            next->u[i] = -ctl->cfg.input_max;
            next->flags |= TVO_FLAG_ACCEL_SATURATED;
        }
    }
    return TVO_REASON_NONE;
}

/* The loop's commit piece (the clock committed): the filters and the held input. */
TVO_OFF_CHAIN_BODY tvo_reason_t chain_commit(void *ctl_any, const tvo_loop_frame_t *frame)
{
    tvo_chain_controller_t *ctl = ctl_any;
    (void)frame;
    for (uint8_t j = 0; j < chain_filters_in_use(&ctl->cfg) && j + 1u < TVO_MAX_RELATIVE_DEGREE; ++j) {
        ctl->internal.filter[j] = ctl->internal.work.filter[j];
    }
    ctl->internal.held = ctl->internal.work.command; /* applied: chain_command zeroed its outcome and reason */
    return TVO_REASON_NONE; /* the chain has no stop of its own */
}

/* Where the loop's parts live in the chain's types. */
static tvo_loop_state_t *chain_state(void *ctl)
{
    return &((tvo_chain_controller_t *)ctl)->internal.loop;
}

static const tvo_loop_state_t *chain_state_of(const void *ctl)
{
    return &((const tvo_chain_controller_t *)ctl)->internal.loop;
}

static tvo_period_t *chain_period(void *ctl)
{
    return &((tvo_chain_controller_t *)ctl)->internal.work.period;
}

static void *chain_held(void *ctl)
{
    return &((tvo_chain_controller_t *)ctl)->internal.held;
}

static tvo_loop_mark_t chain_mark(void *cmd_any)
{
    tvo_chain_command_t *cmd = cmd_any;
    const tvo_loop_mark_t mark = {&cmd->flags, &cmd->outcome, &cmd->reason, offsetof(tvo_chain_command_t, flags)};
    return mark;
}

static uint32_t chain_stamp_tick(const void *meas)
{
    return ((const tvo_chain_measurement_t *)meas)->stamp_tick;
}

static const tvo_real_t *chain_positions(const void *meas)
{
    return ((const tvo_chain_measurement_t *)meas)->y.d[0];
}

/* No refusal piece (the chain's refusals are final) and no rest piece (the held input is all its
 * state at rest; the filters restart from the gap). */
static const tvo_loop_plant_t chain_plant = {
    .controller_size = sizeof(tvo_chain_controller_t), .command_size = sizeof(tvo_chain_command_t),
    .state = chain_state, .state_of = chain_state_of, .period = chain_period, .held = chain_held, .mark = chain_mark,
    .stamp_tick = chain_stamp_tick, .positions = chain_positions,
    .check = chain_check, .refusal = NULL, .prepare = chain_prepare, .law = chain_law, .command = chain_command,
    .commit = chain_commit, .refuse = chain_refuse, .rest = NULL};

tvo_status_t tvo_chain_controller_step(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                       uint32_t apply_tick, tvo_chain_command_t *cmd)
{
    if (meas == NULL) {
        return tvo_chain_controller_miss(ctl, apply_tick, cmd); /* its period record in its own frame */
    }
    const tvo_status_t st = loop_ready(&chain_plant, ctl, cmd);
    return (st != TVO_OK) ? st : loop_period(&chain_plant, ctl, meas, apply_tick, cmd, 0u);
}

tvo_status_t tvo_chain_controller_miss(tvo_chain_controller_t *ctl, uint32_t apply_tick, tvo_chain_command_t *cmd)
{
    return loop_miss(&chain_plant, ctl, apply_tick, cmd);
}

tvo_status_t tvo_chain_controller_refuse(tvo_chain_controller_t *ctl, tvo_reason_t reason, tvo_chain_command_t *cmd)
{
    return loop_refuse_unplaced(&chain_plant, ctl, reason, cmd);
}

tvo_status_t tvo_chain_controller_check(const tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                        uint32_t apply_tick, tvo_reason_t *reason)
{
    return loop_check(&chain_plant, ctl, meas, apply_tick, reason);
}

tvo_status_t tvo_chain_controller_safe_stop(tvo_chain_controller_t *ctl, tvo_chain_command_t *cmd)
{
    return loop_safe_stop(&chain_plant, ctl, cmd);
}
