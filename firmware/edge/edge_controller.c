/* The edge's controller tables: the unicycle and the integrator chain; see edge_controller.h. */
#include "edge_controller.h"

#include <string.h>

#include "wire_real.h"

/* The core's init's answer to a decoded START: a refusal names its culprit, as the START names it, in
 * *why (may be NULL). */
static tvo_status_t rejected_by_core(tvo_status_t st, tvo_session_param_t bad, tvo_session_reject_t *why)
{
    if (st != TVO_OK && why != NULL) {
        why->node = TVO_NODE_OK;
        why->status = st;
        why->param = bad;
    }
    return st;
}

/*
 * The core's sampled-data loop behind the edge's unions: the same eight operations for every plant,
 * written once and stamped out per plant (member: the unions' member and the session codec's suffix,
 * api: the core's prefix, with the plant's configuration and parameter types). init decodes a START
 * into the plant's configuration and hands it to the core's init; the step, the miss and the safe
 * stop are the core's own public calls (its loop decides hold, refusal and stop), and so is refuse (a
 * sample the node refused: the core answers with the command in force or its watchdog's stop); mark
 * reads what the core's command says (its flags, outcome and reason); clock is the clock the node rebases.
 */
#define EDGE_LOOP_OPS(member, api, config_type, param_type, param_none)                                        \
    static tvo_status_t member##_init(tvo_edge_controller_t *ctl, const tvo_lcm_session_t *msg,               \
                                      const tvo_objective_t *objective, uint32_t epoch_tick,                  \
                                      tvo_session_reject_t *why)                                              \
    {                                                                                                          \
        config_type cfg;                                                                                       \
        param_type bad = param_none;                                                                           \
        tvo_status_t st = tvo_session_decode_##member(msg, &cfg, why);                                        \
        if (st == TVO_OK) {                                                                                    \
            st = api##_init(&ctl->u.member, &cfg, objective, epoch_tick, &bad);                                \
            st = rejected_by_core(st, tvo_session_param_of_##member(bad), why);                               \
        }                                                                                                      \
        return st;                                                                                             \
    }                                                                                                          \
    static tvo_status_t member##_step(tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas,         \
                                      uint32_t apply_tick, tvo_edge_command_t *cmd)                           \
    {                                                                                                          \
        return api##_step(&ctl->u.member, &meas->member, apply_tick, &cmd->member);                          \
    }                                                                                                          \
    static tvo_status_t member##_miss(tvo_edge_controller_t *ctl, uint32_t apply_tick,                        \
                                      tvo_edge_command_t *cmd)                                                \
    {                                                                                                          \
        return api##_miss(&ctl->u.member, apply_tick, &cmd->member);                                         \
    }                                                                                                          \
    static tvo_status_t member##_safe_stop(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)               \
    {                                                                                                          \
        return api##_safe_stop(&ctl->u.member, &cmd->member);                                                \
    }                                                                                                          \
    static tvo_status_t member##_check(const tvo_edge_controller_t *ctl, const tvo_edge_measurement_t *meas,  \
                                       uint32_t apply_tick, tvo_reason_t *reason)                             \
    {                                                                                                          \
        return api##_check(&ctl->u.member, &meas->member, apply_tick, reason);                               \
    }                                                                                                          \
    static tvo_status_t member##_refuse(tvo_edge_controller_t *ctl, tvo_edge_command_t *cmd)                  \
    {                                                                                                          \
        return api##_refuse(&ctl->u.member, TVO_REASON_REFUSED, &cmd->member);                               \
    }                                                                                                          \
    static tvo_edge_mark_t member##_mark(const tvo_edge_command_t *cmd)                                       \
    {                                                                                                          \
        const tvo_edge_mark_t mark = {cmd->member.flags, (tvo_outcome_t)cmd->member.outcome,                   \
                                      (tvo_reason_t)cmd->member.reason};                                       \
        return mark;                                                                                           \
    }                                                                                                          \
    static tvo_sample_clock_t *member##_clock(tvo_edge_controller_t *ctl)                                     \
    {                                                                                                          \
        return &ctl->u.member.internal.loop.clock;                                                             \
    }

/* The eight in a table's initialiser. */
#define EDGE_LOOP_ENTRIES(member)                                                                              \
    .init = member##_init, .step = member##_step, .miss = member##_miss, .safe_stop = member##_safe_stop,      \
    .refuse = member##_refuse, .check = member##_check, .mark = member##_mark, .clock = member##_clock

EDGE_LOOP_OPS(unicycle, tvo_controller, tvo_controller_config_t, tvo_param_t, TVO_PARAM_NONE)
EDGE_LOOP_OPS(chain, tvo_chain_controller, tvo_chain_config_t, tvo_chain_param_t, TVO_CHAIN_PARAM_NONE)

/* ---- unicycle (controller.h) ---------------------------------------------------------------- */

static uint8_t unicycle_relative_degree(const tvo_lcm_session_t *msg)
{
    (void)msg;
    return 2u;
}

static tvo_node_status_t unicycle_measurement(const tvo_edge_controller_t *ctl, const tvo_edge_samples_t *samples,
                                              uint8_t robot_count, uint32_t stamp_tick, tvo_edge_measurement_t *meas)
{
    (void)ctl; /* the core's check says which fields its configuration needs (heading_valid) */
    return (tvo_step_unicycle_measurement(samples->unicycle, robot_count, stamp_tick, &meas->unicycle) == TVO_OK)
               ? TVO_NODE_OK
               : TVO_NODE_WRONG_ROBOT; /* no rows, or a count the build cannot hold (the session's never is) */
}

static int unicycle_encode_command(const tvo_edge_command_t *cmd, const tvo_step_stamp_t *stamp, int32_t robot,
                                   uint8_t *buffer, uint32_t capacity)
{
    tvo_lcm_unicycle_command_t msg;
    tvo_step_unicycle_command(&cmd->unicycle, stamp, robot, &msg);
    return tvo_lcm_unicycle_command_t_encode(buffer, 0, (int)capacity, &msg);
}

static uint64_t unicycle_digest(const tvo_edge_command_t *cmd, uint8_t robot_count)
{
    return tvo_step_unicycle_digest(&cmd->unicycle, robot_count);
}

static void unicycle_rows(const tvo_edge_command_t *cmd, uint8_t robot_count, double *speed_mps, double *turn_rate_radps)
{
    for (uint8_t r = 0; r < robot_count && r < TVO_MAX_ROBOTS; ++r) {
        speed_mps[r] = (double)tvo_wire_float(cmd->unicycle.speed_mps[r]); /* what the plant applies */
        turn_rate_radps[r] = (double)tvo_wire_float(cmd->unicycle.turn_rate_radps[r]);
    }
}

static void unicycle_telemetry_to_lcm(const tvo_edge_controller_t *ctl, const tvo_problem_t *problem, uint8_t robot,
                                      tvo_lcm_telemetry_t *msg)
{
    const tvo_controller_t *unicycle = &ctl->u.unicycle;
    tvo_step_telemetry_to_lcm(&unicycle->telemetry, robot, unicycle->internal.speed_state_mps, problem, msg);
}

static const tvo_edge_controller_ops_t unicycle_ops = {
    .name = "unicycle", .sample_channel = TVO_NODE_CH_SAMPLE, .command_channel = TVO_NODE_CH_COMMAND,
    EDGE_LOOP_ENTRIES(unicycle), .relative_degree = unicycle_relative_degree, .measurement = unicycle_measurement,
    .encode_command = unicycle_encode_command, .digest = unicycle_digest, .rows = unicycle_rows,
    .telemetry_to_lcm = unicycle_telemetry_to_lcm};

/* ---- integrator chain (chain_controller.h) ---------------------------------------------------- */

static uint8_t chain_relative_degree(const tvo_lcm_session_t *msg)
{
    /* Checked by tvo_session_decode_chain before the problem is built; clamp for the cast only. */
    const int32_t k = msg->chain_relative_degree;
    return (k >= 1 && k <= TVO_MAX_RELATIVE_DEGREE) ? (uint8_t)k : 1u;
}

static tvo_node_status_t chain_measurement(const tvo_edge_controller_t *ctl, const tvo_edge_samples_t *samples,
                                           uint8_t robot_count, uint32_t stamp_tick, tvo_edge_measurement_t *meas)
{
    if (robot_count != 1u || tvo_step_chain_measurement(samples->chain, stamp_tick, &meas->chain) != TVO_OK) {
        return TVO_NODE_WRONG_ROBOT; /* a chain session has one robot (session_codec.c) */
    }
    /* The core's chain measurement has no validity flag: y' (and y'') read as measured must be. */
    const tvo_chain_config_t *cfg = &ctl->u.chain.cfg;
    const int has_derivatives = (samples->chain->has & TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES) != 0;
    if (!has_derivatives && cfg->relative_degree >= 2u && !cfg->filtered_derivatives) {
        return TVO_NODE_MISSING_DERIVATIVES;
    }
    return TVO_NODE_OK;
}

static int chain_encode_command(const tvo_edge_command_t *cmd, const tvo_step_stamp_t *stamp, int32_t robot,
                                uint8_t *buffer, uint32_t capacity)
{
    (void)robot; /* one robot */
    tvo_lcm_chain_command_t msg;
    tvo_step_chain_command(&cmd->chain, stamp, &msg);
    return tvo_lcm_chain_command_t_encode(buffer, 0, (int)capacity, &msg);
}

static uint64_t chain_digest(const tvo_edge_command_t *cmd, uint8_t robot_count)
{
    (void)robot_count; /* one robot */
    return tvo_step_chain_digest(&cmd->chain);
}

static void chain_rows(const tvo_edge_command_t *cmd, uint8_t robot_count, double *speed_mps, double *turn_rate_radps)
{
    (void)robot_count; /* one robot: u in the place of speed and turn rate */
    speed_mps[0] = (double)tvo_wire_float(cmd->chain.u[0]);
    turn_rate_radps[0] = (double)tvo_wire_float(cmd->chain.u[1]);
}

static void chain_telemetry_to_lcm(const tvo_edge_controller_t *ctl, const tvo_problem_t *problem, uint8_t robot,
                                   tvo_lcm_telemetry_t *msg)
{
    (void)ctl; /* the chain keeps no per-step telemetry: the header and digest say it all */
    (void)problem;
    (void)robot;
    (void)msg;
}

static const tvo_edge_controller_ops_t chain_ops = {
    .name = "chain", .sample_channel = TVO_NODE_CH_CHAIN_SAMPLE, .command_channel = TVO_NODE_CH_CHAIN_COMMAND,
    EDGE_LOOP_ENTRIES(chain), .relative_degree = chain_relative_degree, .measurement = chain_measurement,
    .encode_command = chain_encode_command, .digest = chain_digest, .rows = chain_rows,
    .telemetry_to_lcm = chain_telemetry_to_lcm};

void tvo_edge_controller_clear_scratch(tvo_edge_controller_t *ctl)
{
    if (ctl == NULL) {
        return;
    }
    if (ctl->ops == &unicycle_ops) {
        memset(&ctl->u.unicycle.internal.work, 0, sizeof(ctl->u.unicycle.internal.work));
    } else if (ctl->ops == &chain_ops) {
        memset(&ctl->u.chain.internal.work, 0, sizeof(ctl->u.chain.internal.work));
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
