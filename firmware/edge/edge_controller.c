/* The edge's controller tables: the unicycle and the integrator chain; see edge_controller.h. */
#include "edge_controller.h"

#include <string.h>

/* ---- unicycle (controller.h) ---------------------------------------------------------------- */

static uint8_t unicycle_relative_degree(const tvo_lcm_session_t *msg)
{
    (void)msg;
    return 2u;
}

static tvo_status_t unicycle_init(tvo_edge_controller_t *ctl, const tvo_lcm_session_t *msg,
                                  const tvo_objective_t *objective, uint32_t epoch_tick, tvo_session_reject_t *why)
{
    tvo_controller_config_t cfg;
    tvo_status_t st = tvo_session_decode_unicycle(msg, &cfg, why);
    if (st == TVO_OK) {
        tvo_param_t bad = TVO_PARAM_NONE;
        st = tvo_controller_init(&ctl->u.unicycle, &cfg, objective, epoch_tick, &bad);
        if (st != TVO_OK && why != NULL) {
            why->status = st;
            why->param = bad;
        }
    }
    return st;
}

static tvo_status_t unicycle_measurement(const tvo_edge_controller_t *ctl, const tvo_lcm_measurement_t *msg,
                                         uint8_t robot_count, uint32_t stamp_tick, tvo_edge_measurement_t *meas)
{
    (void)ctl; /* the core's check says which fields its configuration needs (heading_valid) */
    return tvo_step_measurement_from_lcm(msg, robot_count, stamp_tick, &meas->unicycle);
}

static void unicycle_positions(const tvo_edge_measurement_t *meas, uint8_t robot_count, tvo_real_t *y)
{
    for (uint8_t r = 0; r < robot_count && r < TVO_MAX_ROBOTS; ++r) {
        y[2u * r] = meas->unicycle.position_m[r][0];
        y[2u * r + 1u] = meas->unicycle.position_m[r][1];
    }
}


static tvo_status_t unicycle_step(tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas, uint32_t apply_tick,
                                  tvo_edge_command_t *cmd)
{
    return tvo_controller_step(&ctl->u.unicycle, &meas->unicycle, apply_tick, &cmd->unicycle);
}

static tvo_status_t unicycle_miss(tvo_edge_controller_t *ctl, uint32_t apply_tick, tvo_edge_command_t *cmd)
{
    return tvo_controller_miss(&ctl->u.unicycle, apply_tick, &cmd->unicycle);
}

static tvo_status_t unicycle_safe_stop(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)
{
    return tvo_controller_safe_stop(&ctl->u.unicycle, &cmd->unicycle);
}

static void unicycle_holding(const tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)
{
    cmd->unicycle = ctl->u.unicycle.held;
    cmd->unicycle.flags = TVO_FLAG_HOLDING;
}

static uint32_t unicycle_flags(const tvo_edge_command_t *cmd)
{
    return cmd->unicycle.flags;
}

static void unicycle_command_to_lcm(const tvo_edge_command_t *cmd, const tvo_step_stamp_t *stamp,
                                    tvo_lcm_command_t *msg)
{
    tvo_step_command_to_lcm(&cmd->unicycle, stamp, msg);
}

static void unicycle_telemetry_to_lcm(const tvo_edge_controller_t *ctl, const tvo_problem_t *problem,
                                      tvo_lcm_telemetry_t *msg)
{
    tvo_step_telemetry_to_lcm(&ctl->u.unicycle, problem, msg);
}

static tvo_sample_clock_t *unicycle_clock(tvo_edge_controller_t *ctl)
{
    return &ctl->u.unicycle.clock;
}

static const tvo_edge_controller_ops_t unicycle_ops = {
    .name = "unicycle",
    .relative_degree = unicycle_relative_degree,
    .init = unicycle_init,
    .measurement = unicycle_measurement,
    .positions = unicycle_positions,
    .step = unicycle_step,
    .miss = unicycle_miss,
    .safe_stop = unicycle_safe_stop,
    .holding = unicycle_holding,
    .flags = unicycle_flags,
    .command_to_lcm = unicycle_command_to_lcm,
    .telemetry_to_lcm = unicycle_telemetry_to_lcm,
    .clock = unicycle_clock};

/* ---- integrator chain (chain_controller.h) ---------------------------------------------------- */

static uint8_t chain_relative_degree(const tvo_lcm_session_t *msg)
{
    /* Checked by tvo_session_decode_chain before the problem is built; clamp for the cast only. */
    const int32_t k = msg->chain_relative_degree;
    return (k >= 1 && k <= TVO_MAX_RELATIVE_DEGREE) ? (uint8_t)k : 1u;
}

static tvo_status_t chain_init(tvo_edge_controller_t *ctl, const tvo_lcm_session_t *msg,
                               const tvo_objective_t *objective, uint32_t epoch_tick, tvo_session_reject_t *why)
{
    tvo_chain_config_t cfg;
    tvo_status_t st = tvo_session_decode_chain(msg, &cfg, why);
    if (st == TVO_OK) {
        tvo_param_t bad = TVO_PARAM_NONE;
        st = tvo_chain_controller_init(&ctl->u.chain, &cfg, objective, epoch_tick, &bad);
        if (st != TVO_OK && why != NULL) {
            why->status = st;
            why->param = bad;
        }
    }
    return st;
}

static tvo_status_t chain_measurement(const tvo_edge_controller_t *ctl, const tvo_lcm_measurement_t *msg,
                                      uint8_t robot_count, uint32_t stamp_tick, tvo_edge_measurement_t *meas)
{
    const tvo_status_t st = tvo_step_chain_measurement_from_lcm(msg, robot_count, stamp_tick, &meas->chain);
    /* The core's chain measurement has no validity flag: y' (and y'') read as measured must be. */
    const tvo_chain_config_t *cfg = &ctl->u.chain.cfg;
    if (st == TVO_OK && !msg->derivatives_valid && cfg->relative_degree >= 2u && !cfg->filtered_derivatives) {
        return TVO_ERR_MISSING_FIELD;
    }
    return st;
}

static void chain_positions(const tvo_edge_measurement_t *meas, uint8_t robot_count, tvo_real_t *y)
{
    for (size_t i = 0; i < 2u * (size_t)robot_count && i < TVO_MAX_OUTPUT_DIM; ++i) {
        y[i] = meas->chain.y.d[0][i];
    }
}


static tvo_status_t chain_step(tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas, uint32_t apply_tick,
                               tvo_edge_command_t *cmd)
{
    return tvo_chain_controller_step(&ctl->u.chain, &meas->chain, apply_tick, &cmd->chain);
}

static tvo_status_t chain_miss(tvo_edge_controller_t *ctl, uint32_t apply_tick, tvo_edge_command_t *cmd)
{
    return tvo_chain_controller_miss(&ctl->u.chain, apply_tick, &cmd->chain);
}

static tvo_status_t chain_safe_stop(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)
{
    return tvo_chain_controller_safe_stop(&ctl->u.chain, &cmd->chain);
}

static void chain_holding(const tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)
{
    cmd->chain = ctl->u.chain.held;
    cmd->chain.flags = TVO_FLAG_HOLDING;
}

static uint32_t chain_flags(const tvo_edge_command_t *cmd)
{
    return cmd->chain.flags;
}

static void chain_command_to_lcm(const tvo_edge_command_t *cmd, const tvo_step_stamp_t *stamp, tvo_lcm_command_t *msg)
{
    tvo_step_chain_command_to_lcm(&cmd->chain, stamp, msg);
}

static void chain_telemetry_to_lcm(const tvo_edge_controller_t *ctl, const tvo_problem_t *problem,
                                   tvo_lcm_telemetry_t *msg)
{
    (void)ctl; /* the chain keeps no per-step telemetry: the stamp fields and counters say it all */
    (void)problem;
    (void)msg;
}

static tvo_sample_clock_t *chain_clock(tvo_edge_controller_t *ctl)
{
    return &ctl->u.chain.clock;
}

static const tvo_edge_controller_ops_t chain_ops = {
    .name = "chain",
    .relative_degree = chain_relative_degree,
    .init = chain_init,
    .measurement = chain_measurement,
    .positions = chain_positions,
    .step = chain_step,
    .miss = chain_miss,
    .safe_stop = chain_safe_stop,
    .holding = chain_holding,
    .flags = chain_flags,
    .command_to_lcm = chain_command_to_lcm,
    .telemetry_to_lcm = chain_telemetry_to_lcm,
    .clock = chain_clock};

void tvo_edge_controller_clear_scratch(tvo_edge_controller_t *ctl)
{
    if (ctl == NULL) {
        return;
    }
    if (ctl->ops == &unicycle_ops) {
        memset(&ctl->u.unicycle.work, 0, sizeof(ctl->u.unicycle.work));
    } else if (ctl->ops == &chain_ops) {
        memset(&ctl->u.chain.work, 0, sizeof(ctl->u.chain.work));
    }
}

const tvo_edge_controller_ops_t *tvo_edge_controller_ops(int32_t plant_kind)
{
    switch (plant_kind) {
    case TVO_LCM_SESSION_T_PLANT_UNICYCLE: return &unicycle_ops;
    case TVO_LCM_SESSION_T_PLANT_CHAIN: return &chain_ops;
    default: return NULL;
    }
}
