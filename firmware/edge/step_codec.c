/* One period's messages <-> the core; see step_codec.h. */
#include "step_codec.h"

#include <string.h>

#include "wire_real.h"

/* The per-period messages carry one robot, two outputs each. */
_Static_assert(sizeof(((tvo_lcm_chain_command_t *)0)->input) == 2 * sizeof(float), "chain_command_t: one robot's u");
_Static_assert(sizeof(((tvo_lcm_telemetry_t *)0)->gradient) == 2 * sizeof(float), "telemetry_t: one robot's rows");

/* The wire's numbers of the core's call errors, the core's reasons and the edge's statuses: every
 * status a command, telemetry or ack carries comes from these three tables (lcm_types/README.md). */
#define WIRE(name) TVO_LCM_COMMAND_HEADER_T_STATUS_##name
static const int8_t wire_of_error[TVO_STATUS_COUNT] = {
    [TVO_OK] = WIRE(OK),
    [TVO_ERR_NULL] = WIRE(ERR_NULL),
    [TVO_ERR_NOT_FINITE] = WIRE(ERR_NOT_FINITE),
    [TVO_ERR_DIMENSION] = WIRE(ERR_DIMENSION),
    [TVO_ERR_PARAM] = WIRE(ERR_PARAM),
    [TVO_ERR_CAPACITY] = WIRE(ERR_CAPACITY),
    [TVO_ERR_NOT_INITIALIZED] = WIRE(ERR_NOT_INITIALIZED),
    [TVO_ERR_TICK_NOT_ADVANCING] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_ERR_BEFORE_EPOCH] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_ERR_NOT_POSITIVE_DEFINITE] = WIRE(ERR_NOT_POSITIVE_DEFINITE),
    [TVO_ERR_NUMERIC] = WIRE(ERR_NUMERIC),
};
static const int8_t wire_of_reason[TVO_REASON_COUNT] = {
    [TVO_REASON_NONE] = WIRE(OK),
    [TVO_REASON_NOT_FINITE] = WIRE(ERR_NOT_FINITE),
    [TVO_REASON_IMPLAUSIBLE_MEASUREMENT] = WIRE(ERR_IMPLAUSIBLE_MEASUREMENT),
    [TVO_REASON_STALE] = WIRE(ERR_STALE),
    [TVO_REASON_FUTURE_STAMP] = WIRE(ERR_FUTURE_STAMP),
    [TVO_REASON_STAMP_NOT_NEWER] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_REASON_MISSING_FIELD] = WIRE(ERR_MISSING_FIELD),
    [TVO_REASON_SOURCE_NOT_LINKED] = WIRE(ERR_NOT_INITIALIZED),
    [TVO_REASON_TARGET_NOT_READY] = WIRE(ERR_TARGET_NOT_READY),
    [TVO_REASON_NUMERIC] = WIRE(ERR_NUMERIC),
    [TVO_REASON_NOT_POSITIVE_DEFINITE] = WIRE(ERR_NOT_POSITIVE_DEFINITE),
    [TVO_REASON_NO_MEASUREMENT] = WIRE(ERR_NO_MEASUREMENT),
    [TVO_REASON_WATCHDOG] = WIRE(ERR_WATCHDOG),
    [TVO_REASON_SPEED_MISMATCH] = WIRE(OK), /* the sample was taken: the stop is its flag */
    [TVO_REASON_STOP_REQUESTED] = WIRE(ERR_WATCHDOG),
    [TVO_REASON_REFUSED] = WIRE(ERR_IMPLAUSIBLE_MEASUREMENT), /* the node's own status says which check */
};
static const int8_t wire_of_node[TVO_NODE_STATUS_COUNT] = {
    [TVO_NODE_OK] = WIRE(OK),
    [TVO_NODE_WRONG_ROBOT] = WIRE(ERR_DIMENSION),
    [TVO_NODE_IMPLAUSIBLE_STAMP] = WIRE(ERR_IMPLAUSIBLE_STAMP),
    [TVO_NODE_NOT_LATER_PERIOD] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_NODE_STALE] = WIRE(ERR_STALE),
    [TVO_NODE_MISSING_DERIVATIVES] = WIRE(ERR_MISSING_FIELD),
    [TVO_NODE_SESSION_CONFLICT] = WIRE(ERR_SESSION_CONFLICT),
    [TVO_NODE_NO_SESSION] = WIRE(ERR_NO_SESSION),
    [TVO_NODE_UNKNOWN_ACTION] = WIRE(ERR_PARAM),
    [TVO_NODE_ROBOT_UNHEARD] = WIRE(ERR_NO_MEASUREMENT),
    [TVO_NODE_WRONG_PLANT] = WIRE(ERR_PARAM),
    [TVO_NODE_NOT_FINITE] = WIRE(ERR_NOT_FINITE),
};
#undef WIRE

int32_t tvo_step_wire_status(const tvo_step_why_t *why)
{
    if (why == NULL) {
        return TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NULL;
    }
    if (why->node != TVO_NODE_OK) {
        return ((uint32_t)why->node < TVO_NODE_STATUS_COUNT) ? wire_of_node[why->node]
                                                             : TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM;
    }
    if (why->error != TVO_OK) {
        return ((uint32_t)why->error < TVO_STATUS_COUNT) ? wire_of_error[why->error]
                                                         : TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM;
    }
    return ((uint32_t)why->reason < TVO_REASON_COUNT) ? wire_of_reason[why->reason]
                                                      : TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_PARAM;
}

uint32_t tvo_step_wire_flags(uint32_t flags, tvo_outcome_t outcome)
{
    const uint32_t wire_bits = (uint32_t)(TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP);
    const uint32_t shaping = flags & ~wire_bits & 0x7fffu; /* the core's bits (channels.c: they fit the int16) */
    return shaping | (outcome == TVO_OUTCOME_HELD ? (uint32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING : 0u) |
           (outcome == TVO_OUTCOME_STOPPED ? (uint32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP : 0u);
}

/* ---- samples -> the core ------------------------------------------------------------------------ */

void tvo_step_state_of(const tvo_lcm_unicycle_sample_t *sample, tvo_step_robot_state_t *state)
{
    if (sample == NULL || state == NULL) {
        return;
    }
    state->position_m[0] = sample->position_m[0];
    state->position_m[1] = sample->position_m[1];
    state->heading_rad = (sample->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING) ? (double)sample->heading_rad : 0.0;
    state->speed_mps = (sample->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED) ? (double)sample->speed_mps : 0.0;
    state->sequence = sample->header.sequence;
}

int tvo_step_unicycle_sample_finite(const tvo_lcm_unicycle_sample_t *sample)
{
    return sample != NULL && isfinite(sample->position_m[0]) && isfinite(sample->position_m[1]) &&
           (!(sample->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING) || isfinite(sample->heading_rad)) &&
           (!(sample->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED) || isfinite(sample->speed_mps));
}

tvo_status_t tvo_step_unicycle_measurement(const tvo_step_period_t *period, uint8_t robot_count, uint32_t stamp_tick,
                                           tvo_measurement_t *meas)
{
    if (period == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    memset(meas, 0, sizeof(*meas));
    if (robot_count < 1u || robot_count > TVO_MAX_ROBOTS) {
        return TVO_ERR_DIMENSION;
    }
    meas->stamp_tick = stamp_tick;
    meas->heading_valid = 1u;
    meas->speed_valid = 1u;
    for (uint8_t r = 0; r < robot_count; ++r) {
        const tvo_lcm_unicycle_sample_t *s = period->sample[r];
        if (s != NULL) {
            meas->position_m[r][0] = tvo_wire_measured(s->position_m[0]);
            meas->position_m[r][1] = tvo_wire_measured(s->position_m[1]);
            const int has_heading = (s->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_HEADING) != 0;
            const int has_speed = (s->has & TVO_LCM_UNICYCLE_SAMPLE_T_HAS_SPEED) != 0;
            meas->heading_rad[r] = has_heading ? (tvo_real_t)s->heading_rad : TVO_R(0.0); /* unread when absent */
            meas->speed_mps[r] = has_speed ? (tvo_real_t)s->speed_mps : TVO_R(0.0);
            meas->heading_valid = has_heading ? meas->heading_valid : 0u;
            meas->speed_valid = has_speed ? meas->speed_valid : 0u;
        } else {
            const tvo_step_robot_state_t *p = &period->predicted[r];
            meas->position_m[r][0] = tvo_wire_real(p->position_m[0]);
            meas->position_m[r][1] = tvo_wire_real(p->position_m[1]);
            meas->heading_rad[r] = tvo_wire_real(p->heading_rad);
            meas->speed_mps[r] = tvo_wire_real(p->speed_mps);
        }
    }
    return TVO_OK;
}

tvo_status_t tvo_step_chain_measurement(const tvo_lcm_chain_sample_t *sample, uint32_t stamp_tick,
                                        tvo_chain_measurement_t *meas)
{
    if (sample == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    memset(meas, 0, sizeof(*meas));
    meas->stamp_tick = stamp_tick;
    const int has_derivatives = (sample->has & TVO_LCM_CHAIN_SAMPLE_T_HAS_DERIVATIVES) != 0;
    for (size_t axis = 0; axis < 2; ++axis) {
        meas->y.d[0][axis] = tvo_wire_measured(sample->position_m[axis]);
        if (has_derivatives) {
            meas->y.d[1][axis] = (tvo_real_t)sample->output_rate_mps[axis];
#if TVO_MAX_RELATIVE_DEGREE >= 3
            meas->y.d[2][axis] = (tvo_real_t)sample->output_accel_mps2[axis];
#endif
        }
    }
    return TVO_OK;
}

/* ---- commands and telemetry --------------------------------------------------------------------- */

void tvo_step_header(const tvo_step_stamp_t *stamp, uint32_t wire_flags, int32_t robot, tvo_lcm_command_header_t *out)
{
    if (stamp == NULL || out == NULL) {
        return;
    }
    memset(out, 0, sizeof(*out));
    out->utime = stamp->utime;
    out->session_id = stamp->session_id;
    out->measurement_sequence = stamp->sequence;
    out->robot = (int8_t)robot;
    out->status = (int8_t)tvo_step_wire_status(&stamp->why);
    out->flags = (int16_t)(wire_flags & 0x7fffu);
}

void tvo_step_unicycle_command(const tvo_command_t *cmd, const tvo_step_stamp_t *stamp, int32_t robot,
                               tvo_lcm_unicycle_command_t *msg)
{
    if (cmd == NULL || stamp == NULL || msg == NULL || robot < 0 || robot >= TVO_MAX_ROBOTS) {
        return;
    }
    memset(msg, 0, sizeof(*msg));
    tvo_step_header(stamp, tvo_step_wire_flags(cmd->flags, (tvo_outcome_t)cmd->outcome), robot, &msg->header);
    msg->speed_mps = tvo_wire_float(cmd->speed_mps[robot]);
    msg->turn_rate_radps = tvo_wire_float(cmd->turn_rate_radps[robot]);
}

void tvo_step_chain_command(const tvo_chain_command_t *cmd, const tvo_step_stamp_t *stamp,
                            tvo_lcm_chain_command_t *msg)
{
    if (cmd == NULL || stamp == NULL || msg == NULL) {
        return;
    }
    memset(msg, 0, sizeof(*msg));
    tvo_step_header(stamp, tvo_step_wire_flags(cmd->flags, (tvo_outcome_t)cmd->outcome), 0, &msg->header);
    msg->input[0] = tvo_wire_float(cmd->u[0]);
    msg->input[1] = tvo_wire_float(cmd->u[1]);
}

uint64_t tvo_step_unicycle_digest(const tvo_command_t *cmd, uint8_t robot_count)
{
    double speed[TVO_MAX_ROBOTS];
    double turn[TVO_MAX_ROBOTS];
    if (cmd == NULL || robot_count > TVO_MAX_ROBOTS) {
        return 0u;
    }
    for (uint8_t r = 0; r < robot_count; ++r) {
        speed[r] = (double)tvo_wire_float(cmd->speed_mps[r]);
        turn[r] = (double)tvo_wire_float(cmd->turn_rate_radps[r]);
    }
    return tvo_joint_digest(speed, turn, (int32_t)robot_count);
}

uint64_t tvo_step_chain_digest(const tvo_chain_command_t *cmd)
{
    if (cmd == NULL) {
        return 0u;
    }
    const double u0 = (double)tvo_wire_float(cmd->u[0]);
    const double u1 = (double)tvo_wire_float(cmd->u[1]);
    return tvo_joint_digest(&u0, &u1, 1);
}

void tvo_step_telemetry_to_lcm(const tvo_controller_telemetry_t *tel, uint8_t robot, const tvo_real_t *speed_state_mps,
                               const tvo_problem_t *problem, tvo_lcm_telemetry_t *msg)
{
    if (tel == NULL || speed_state_mps == NULL || problem == NULL || msg == NULL || robot >= TVO_MAX_ROBOTS) {
        return;
    }
    /* t in whole microseconds from the epoch (the law's own time, rounded; a wire time's range, 2^60 us). */
    const double t_us = (double)tel->objective_time_s * 1e6;
    msg->objective_time_us = isnan(t_us)              ? 0
                             : (t_us >= 0x1p60)       ? ((int64_t)1 << 60)
                             : (t_us <= -0x1p60)      ? -((int64_t)1 << 60)
                                                      : (int64_t)llround(t_us);
    for (size_t axis = 0; axis < 2; ++axis) {
        const size_t i = 2u * (size_t)robot + axis;
        msg->output_m[axis] = (double)tel->output_m[i];
        msg->output_rate_mps[axis] = tvo_wire_float(tel->output_rate_mps[i]);
        msg->output_accel_mps2[axis] = tvo_wire_float(tel->output_accel_mps2[i]);
        msg->gradient[axis] = tvo_wire_float(tel->gradient[i]);
        msg->gradient_rate[axis] = tvo_wire_float(tel->gradient_rate[i]);
    }
    msg->speed_state_mps = tvo_wire_float(speed_state_mps[robot]);
    msg->regularization = tvo_wire_float(tel->regularization);
    if (problem->has_inequalities) {
        msg->barrier_c = tvo_wire_float(tel->barrier_c);
        msg->barrier_slack = tvo_wire_float(tel->barrier_slack);
    }
}

/* ---- streamed targets --------------------------------------------------------------------------- */

tvo_status_t tvo_step_target_from_lcm_carried(const tvo_lcm_target_t *msg, uint8_t robot_count,
                                              uint64_t objective_ticks, double carry_s, tvo_problem_t *problem)
{
    if (msg == NULL || problem == NULL) {
        return TVO_ERR_NULL;
    }
    if (!(carry_s >= 0.0 && carry_s <= 1.0)) {
        return TVO_ERR_PARAM;
    }
    const int32_t robot = msg->header.robot;
    if (robot < 0 || robot >= (int32_t)robot_count || robot_count > TVO_MAX_ROBOTS) {
        return TVO_ERR_DIMENSION;
    }
    tvo_target_t *target = tvo_problem_target(problem, (uint8_t)robot);
    if (target == NULL) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (target->kind != TVO_TARGET_STREAMED) {
        return TVO_ERR_PARAM;
    }
    tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2];
    for (size_t axis = 0; axis < 2; ++axis) {
        const double p = msg->position_m[axis], v = (double)msg->velocity_mps[axis];
        const double a = (double)msg->acceleration_mps2[axis], j = (double)msg->jerk_mps3[axis];
        if (!isfinite(p) || !isfinite(v) || !isfinite(a) || !isfinite(j)) {
            return TVO_ERR_NOT_FINITE;
        }
        const double dt = carry_s;
        deriv[0][axis] = tvo_wire_measured(p + dt * (v + dt * (a / 2.0 + dt * j / 6.0)));
        deriv[1][axis] = tvo_wire_measured(v + dt * (a + dt * j / 2.0));
        deriv[2][axis] = tvo_wire_measured(a + dt * j);
        deriv[3][axis] = tvo_wire_measured(j);
    }
    return tvo_target_stream_update(target, objective_ticks, (const tvo_real_t(*)[2])deriv); /* adds const only (C11) */
}
