/* Sampled-data controller of the integrator-chain testbed; see tvo/chain_controller.h. */
#include "tvo/chain_controller.h"

#include <string.h>

#include "law_step.h"
#include "sample_clock_kernel.h"
#include "shape.h"

tvo_status_t tvo_chain_config_default(tvo_chain_config_t *cfg)
{
    if (cfg == NULL) {
        return TVO_ERR_NULL;
    }
    memset(cfg, 0, sizeof(*cfg));
    cfg->tick_hz = 1000000u;
    cfg->period_ticks = 10000u;
    cfg->delay_ticks = 5000u;
    cfg->relative_degree = 2u;
    cfg->delay_compensation = 1u;
    cfg->filter_tf_s = TVO_R(0.05);
    cfg->gain[0] = TVO_R(2.56); /* (s + 1.6)^2 */
    cfg->gain[1] = TVO_R(3.2);
    cfg->input_max = TVO_R(1e3);
    cfg->watchdog_periods = 10u;
    return TVO_OK;
}

static tvo_param_t first_bad_param(const tvo_chain_config_t *cfg, const tvo_objective_t *objective)
{
    const tvo_param_t timing = tvo_sample_clock_check_timing(cfg->tick_hz, cfg->period_ticks, cfg->delay_ticks);
    if (timing != TVO_PARAM_NONE) {
        return timing;
    }
    if (cfg->relative_degree == 0u || cfg->relative_degree > TVO_MAX_RELATIVE_DEGREE ||
        tvo_law_check_sampling_reach(cfg->relative_degree, cfg->gain,
                                     tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz)) != TVO_OK) {
        return TVO_PARAM_GAINS;
    }
    if (cfg->filtered_derivatives && !(isfinite(cfg->filter_tf_s) && cfg->filter_tf_s > TVO_R(0.0))) {
        return TVO_PARAM_FILTER_TF;
    }
    if (!(isfinite(cfg->input_max) && cfg->input_max > TVO_R(0.0))) {
        return TVO_PARAM_ACCEL_MAX;
    }
    if (!tvo_sample_clock_watchdog_ok(cfg->period_ticks, cfg->watchdog_periods)) {
        return TVO_PARAM_WATCHDOG;
    }
    if (objective->dual_dim != 0u || objective->term_count == 0u) {
        return TVO_PARAM_OBJECTIVE;
    }
    return TVO_PARAM_NONE;
}

tvo_status_t tvo_chain_controller_init(tvo_chain_controller_t *ctl, const tvo_chain_config_t *cfg,
                                       const tvo_objective_t *objective, uint32_t epoch_tick, tvo_param_t *bad_param)
{
    if (bad_param != NULL) {
        *bad_param = TVO_PARAM_NONE;
    }
    if (ctl == NULL || cfg == NULL || objective == NULL) {
        return TVO_ERR_NULL;
    }
    memset(ctl, 0, sizeof(*ctl));
    tvo_param_t bad = first_bad_param(cfg, objective);
    tvo_status_t st = TVO_OK;
    if (bad == TVO_PARAM_NONE) {
        st = tvo_law_init(&ctl->law, cfg->relative_degree, objective->primal_dim, cfg->gain);
        bad = (st == TVO_OK) ? TVO_PARAM_NONE : TVO_PARAM_GAINS;
    }
    ctl->period_s = tvo_ticks_to_seconds32(cfg->period_ticks, cfg->tick_hz);
    for (uint8_t j = 0; bad == TVO_PARAM_NONE && j + 1u < cfg->relative_degree; ++j) {
        st = tvo_dirty_derivative_init(&ctl->filter[j], objective->primal_dim,
                                       cfg->filtered_derivatives ? cfg->filter_tf_s : TVO_R(1.0), ctl->period_s);
        bad = (st == TVO_OK) ? TVO_PARAM_NONE : TVO_PARAM_FILTER_TF;
    }
    if (bad != TVO_PARAM_NONE) {
        if (bad_param != NULL) {
            *bad_param = bad;
        }
        memset(ctl, 0, sizeof(*ctl));
        return TVO_ERR_PARAM;
    }
    ctl->cfg = *cfg;
    ctl->objective = objective;
    /* The timing was validated above: the clock cannot reject it. */
    (void)tvo_sample_clock_init(&ctl->clock, cfg->tick_hz, cfg->period_ticks, cfg->watchdog_periods, epoch_tick);
    ctl->initialized = 1;
    return TVO_OK;
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

/* y^(1..k-1) at the sample, from the filters (cascade; the step's working copies in `filter`,
 * kept only when the step succeeds) or as measured. */
static tvo_status_t derivatives_at_sample(const tvo_chain_controller_t *ctl, tvo_dirty_derivative_t *filter,
                                          const tvo_chain_measurement_t *meas, tvo_output_derivs_t *x)
{
    const uint8_t k = ctl->cfg.relative_degree;
    const uint8_t m = ctl->objective->primal_dim;
    *x = meas->y;
    if (!ctl->cfg.filtered_derivatives || k == 1u) {
        return TVO_OK;
    }
    tvo_status_t st = TVO_OK;
    const int primed = filter[0].primed;
    const tvo_real_t dt_s = primed ? ticks_to_seconds32(meas->stamp_tick - ctl->clock.last_stamp_tick, ctl->cfg.tick_hz)
                                   : TVO_R(0.0);
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

static tvo_status_t check_finite(const tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas)
{
    const uint8_t read = ctl->cfg.filtered_derivatives ? 1u : ctl->cfg.relative_degree;
    for (uint8_t j = 0; j < read; ++j) {
        for (uint8_t i = 0; i < ctl->objective->primal_dim; ++i) {
            if (!isfinite(meas->y.d[j][i])) {
                return TVO_ERR_NOT_FINITE;
            }
        }
    }
    return TVO_OK;
}

/* What a good step after the watchdog's gap takes as the input in force: the chain was stopped. */
static const tvo_real_t rest_input[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};

static void chain_stop_command(tvo_chain_command_t *cmd)
{
    memset(cmd, 0, sizeof(*cmd));
    cmd->flags = TVO_FLAG_SAFE_STOP;
}

static void chain_hold_command(const tvo_chain_controller_t *ctl, tvo_chain_command_t *cmd)
{
    *cmd = ctl->held;
    cmd->flags = TVO_FLAG_HOLDING;
}

/* A period counted without a good step (committed): held, or stopped once the watchdog expires. */
static tvo_status_t chain_miss_period(tvo_chain_controller_t *ctl, const tvo_period_t *period,
                                      tvo_chain_command_t *cmd)
{
    if (tvo_sample_clock_end(&ctl->clock, period, 0, 0u)) {
        memset(&ctl->held, 0, sizeof(ctl->held));
        chain_stop_command(cmd);
        return TVO_ERR_WATCHDOG;
    }
    chain_hold_command(ctl, cmd);
    return TVO_ERR_NO_MEASUREMENT;
}

/* A refused step, committing nothing: the command in force; or, when counting the period would expire
 * the watchdog, the period counted and the stop (as tvo_controller_step). */
static tvo_status_t chain_refuse_step(tvo_chain_controller_t *ctl, const tvo_period_t *period,
                                      tvo_status_t reason, tvo_chain_command_t *cmd)
{
    if (sample_clock_refusal_stops(&ctl->clock, period)) {
        return chain_miss_period(ctl, period, cmd);
    }
    chain_hold_command(ctl, cmd);
    return reason;
}

tvo_status_t tvo_chain_controller_check(const tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                        uint32_t apply_tick)
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
    const tvo_status_t st = (meas == NULL) ? TVO_ERR_NO_MEASUREMENT : check_finite(ctl, meas);
    return (st == TVO_OK) ? tvo_sample_clock_check_stamp(&ctl->clock, meas->stamp_tick, apply_tick) : st;
}

tvo_status_t tvo_chain_controller_safe_stop(tvo_chain_controller_t *ctl, tvo_chain_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    chain_stop_command(cmd);
    if (ctl == NULL || !ctl->initialized) {
        return (ctl == NULL) ? TVO_ERR_NULL : TVO_ERR_NOT_INITIALIZED;
    }
    (void)tvo_sample_clock_expire(&ctl->clock);
    memset(&ctl->held, 0, sizeof(ctl->held));
    return TVO_OK;
}

/* The step before the law, for a period the clock has begun: the measurement checked, the filters'
 * trial copies, the state carried to where the law is evaluated, its time; *flags. */
TVO_OFF_CHAIN_BODY tvo_status_t chain_step_before_law(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                                      uint32_t apply_tick, int from_rest, uint32_t *flags)
{
    tvo_chain_controller_work_t *work = &ctl->work;
    tvo_period_t *period = &work->period;
    tvo_status_t st = check_finite(ctl, meas);
    if (st == TVO_OK) {
        st = sample_clock_check_stamp(&ctl->clock, meas->stamp_tick, apply_tick);
    }
    tvo_output_derivs_t *x = &work->state;
    tvo_dirty_derivative_t *filter = work->filter; /* kept on success */
    if (st == TVO_OK) {
        for (uint8_t j = 0; j + 1u < TVO_MAX_RELATIVE_DEGREE; ++j) {
            filter[j] = ctl->filter[j];
            if (from_rest) {
                filter[j].primed = 0; /* the gap makes old filter state meaningless */
            }
        }
        st = derivatives_at_sample(ctl, filter, meas, x);
    }
    if (st != TVO_OK) {
        return st;
    }

    const uint8_t k = ctl->cfg.relative_degree;
    const uint8_t m = ctl->objective->primal_dim;
    /* Where the law is evaluated (the sample, the application instant, or the middle of the held
     * interval); the state is carried there with the held command. */
    sample_clock_locate(&ctl->clock, period, meas->stamp_tick, ctl->cfg.delay_compensation, ctl->cfg.zoh_aware);
    *flags = (period->carry_s > TVO_R(0.0)) ? TVO_FLAG_PREDICTED : 0u;
    if (period->carry_s > TVO_R(0.0)) {
        st = tvo_chain_predict(k, m, x, from_rest ? rest_input : ctl->held.u, period->carry_s, x);
    }
    time_jet_at_tick_time(&period->law_time, ctl->cfg.tick_hz, TVO_R(1.0), &work->time); /* valid times */
    return st;
}

/* The step after the law: the input's limit, and the period's commit. */
TVO_OFF_CHAIN_BODY tvo_status_t chain_step_after_law(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                                     tvo_chain_command_t *cmd, uint32_t flags)
{
    tvo_chain_controller_work_t *work = &ctl->work;
    const uint8_t m = ctl->objective->primal_dim;
    const tvo_real_t *u = work->input;
    tvo_chain_command_t *next = &work->command;
    memset(next, 0, sizeof(*next));
    next->flags = flags;
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
    sample_clock_end_good(&ctl->clock, &work->period, meas->stamp_tick);
    for (uint8_t j = 0; j + 1u < TVO_MAX_RELATIVE_DEGREE; ++j) {
        ctl->filter[j] = work->filter[j];
    }
    ctl->held = *next;
    *cmd = *next;
    return TVO_OK;
}

tvo_status_t tvo_chain_controller_step(tvo_chain_controller_t *ctl, const tvo_chain_measurement_t *meas,
                                       uint32_t apply_tick, tvo_chain_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    if (ctl == NULL || !ctl->initialized) {
        chain_stop_command(cmd);
        return (ctl == NULL) ? TVO_ERR_NULL : TVO_ERR_NOT_INITIALIZED;
    }
    if (meas == NULL) {
        return tvo_chain_controller_miss(ctl, apply_tick, cmd);
    }
    tvo_chain_controller_work_t *work = &ctl->work;
    if (sample_clock_begin(&ctl->clock, apply_tick, &work->period) != TVO_OK) {
        chain_hold_command(ctl, cmd);
        return TVO_ERR_OUT_OF_ORDER;
    }
    /* Before the law, the law, after it: only what crosses the law's call in this frame. */
    uint32_t flags = 0u;
    tvo_status_t st =
        chain_step_before_law(ctl, meas, apply_tick, ctl->clock.stopped, &flags);
    if (st == TVO_OK) {
        tvo_law_report_t *report = &work->report;
        report->gradient = NULL;
        report->gradient_rate = NULL;
        report->count = 0u;
        st = law_evaluate_report_unchecked(&ctl->law, ctl->objective, &work->state, &work->time, work->input, report,
                                           &work->law);
    }
    if (st != TVO_OK) {
        return chain_refuse_step(ctl, &work->period, st, cmd);
    }
    return chain_step_after_law(ctl, meas, cmd, flags);
}

tvo_status_t tvo_chain_controller_miss(tvo_chain_controller_t *ctl, uint32_t apply_tick, tvo_chain_command_t *cmd)
{
    if (cmd == NULL) {
        return TVO_ERR_NULL;
    }
    if (ctl == NULL || !ctl->initialized) {
        chain_stop_command(cmd);
        return (ctl == NULL) ? TVO_ERR_NULL : TVO_ERR_NOT_INITIALIZED;
    }
    tvo_period_t period;
    if (sample_clock_begin(&ctl->clock, apply_tick, &period) != TVO_OK) {
        chain_hold_command(ctl, cmd);
        return TVO_ERR_OUT_OF_ORDER;
    }
    return chain_miss_period(ctl, &period, cmd);
}
