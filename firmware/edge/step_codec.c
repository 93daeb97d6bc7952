/* One period's messages <-> the core; see step_codec.h. */
#include "step_codec.h"

#include <string.h>

#include "wire_real.h"
#include "internal/barrier.h"

/* Every per-period message holds TVO_WIRE_MAX_ROBOTS robots and their outputs; the codec's loops stop
 * at the smaller of that and the build's limit. */
#define WIRE_ROBOTS_OF(type, member, values_per_robot) (sizeof(((type *)0)->member) / (sizeof(double) * (values_per_robot)))
_Static_assert(WIRE_ROBOTS_OF(tvo_lcm_command_t, speed_mps, 1) == TVO_WIRE_MAX_ROBOTS, "command_t: the wire's robots");
_Static_assert(WIRE_ROBOTS_OF(tvo_lcm_command_t, input, 2) == TVO_WIRE_MAX_ROBOTS, "command_t.input: 2 per robot");
_Static_assert(WIRE_ROBOTS_OF(tvo_lcm_target_t, position_m, 2) == TVO_WIRE_MAX_ROBOTS, "target_t: the wire's robots");
_Static_assert(WIRE_ROBOTS_OF(tvo_lcm_telemetry_t, speed_state_mps, 1) == TVO_WIRE_MAX_ROBOTS, "telemetry_t: the wire's robots");
_Static_assert(WIRE_ROBOTS_OF(tvo_lcm_telemetry_t, gradient, 2) == TVO_WIRE_MAX_ROBOTS, "telemetry_t: 2 outputs per robot");

/* The wire's numbers of the core's call errors, the core's reasons and the edge's statuses: every
 * status a command, telemetry or ack carries comes from these three tables (lcm_types/README.md). */
#define WIRE(name) TVO_LCM_COMMAND_T_STATUS_##name
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
    [TVO_ERR_CLOCK_STARTED] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_ERR_NOT_POSITIVE_DEFINITE] = WIRE(ERR_NOT_POSITIVE_DEFINITE),
    [TVO_ERR_NUMERIC] = WIRE(ERR_NUMERIC),
    [TVO_ERR_STALE] = WIRE(ERR_STALE),
    [TVO_ERR_FUTURE_STAMP] = WIRE(ERR_FUTURE_STAMP),
    [TVO_ERR_STAMP_NOT_NEWER] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_ERR_TARGET_NOT_READY] = WIRE(ERR_TARGET_NOT_READY),
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
    [TVO_REASON_SPEED_MISMATCH] = WIRE(OK), /* the measurement was taken: the stop is its flag */
    [TVO_REASON_STOP_REQUESTED] = WIRE(ERR_WATCHDOG),
};
static const int8_t wire_of_node[TVO_NODE_STATUS_COUNT] = {
    [TVO_NODE_OK] = WIRE(OK),
    [TVO_NODE_WRONG_ROBOT_COUNT] = WIRE(ERR_DIMENSION),
    [TVO_NODE_IMPLAUSIBLE_STAMP] = WIRE(ERR_IMPLAUSIBLE_STAMP),
    [TVO_NODE_NOT_LATER_PERIOD] = WIRE(ERR_OUT_OF_ORDER),
    [TVO_NODE_STALE] = WIRE(ERR_STALE),
    [TVO_NODE_MISSING_DERIVATIVES] = WIRE(ERR_MISSING_FIELD),
    [TVO_NODE_REFUSAL_STREAK] = WIRE(ERR_WATCHDOG),
    [TVO_NODE_SESSION_CONFLICT] = WIRE(ERR_SESSION_CONFLICT),
    [TVO_NODE_NO_SESSION] = WIRE(ERR_NO_SESSION),
    [TVO_NODE_UNKNOWN_ACTION] = WIRE(ERR_PARAM),
};
#undef WIRE

int32_t tvo_step_wire_status(const tvo_step_why_t *why)
{
    if (why == NULL) {
        return TVO_LCM_COMMAND_T_STATUS_ERR_NULL;
    }
    if (why->node != TVO_NODE_OK) {
        return ((uint32_t)why->node < TVO_NODE_STATUS_COUNT) ? wire_of_node[why->node]
                                                             : TVO_LCM_COMMAND_T_STATUS_ERR_PARAM;
    }
    if (why->error != TVO_OK) {
        return ((uint32_t)why->error < TVO_STATUS_COUNT) ? wire_of_error[why->error]
                                                         : TVO_LCM_COMMAND_T_STATUS_ERR_PARAM;
    }
    return ((uint32_t)why->reason < TVO_REASON_COUNT) ? wire_of_reason[why->reason]
                                                      : TVO_LCM_COMMAND_T_STATUS_ERR_PARAM;
}

uint32_t tvo_step_wire_flags(uint32_t flags, tvo_outcome_t outcome)
{
    const uint32_t shaping = flags & ~(uint32_t)(TVO_LCM_COMMAND_T_FLAG_HOLDING | TVO_LCM_COMMAND_T_FLAG_SAFE_STOP);
    return shaping | (outcome == TVO_OUTCOME_HELD ? (uint32_t)TVO_LCM_COMMAND_T_FLAG_HOLDING : 0u) |
           (outcome == TVO_OUTCOME_STOPPED ? (uint32_t)TVO_LCM_COMMAND_T_FLAG_SAFE_STOP : 0u);
}

/* A robot count from the wire against the session's (at most the build's). */
static int robot_count_matches(int32_t wire_count, uint8_t robot_count)
{
    return robot_count <= TVO_MAX_ROBOTS && wire_count == (int32_t)robot_count;
}

void tvo_step_measurement_from_wire(const tvo_lcm_measurement_t *msg, tvo_step_measurement_t *out)
{
    if (msg == NULL || out == NULL) {
        return;
    }
    memset(out, 0, sizeof(*out));
    out->utime = msg->utime;
    out->session_id = msg->session_id;
    out->sequence = msg->sequence;
    out->robot_count = (msg->robot_count >= 0 && msg->robot_count <= TVO_WIRE_SESSION_ROBOTS) ? msg->robot_count : -1;
    out->heading_valid = msg->heading_valid ? 1u : 0u;
    out->speed_valid = msg->speed_valid ? 1u : 0u;
    out->derivatives_valid = msg->derivatives_valid ? 1u : 0u;
    for (int32_t r = 0; r < out->robot_count; ++r) {
        tvo_step_robot_sample_t *robot = &out->robot[r];
        robot->heading_rad = msg->heading_rad[r];
        robot->speed_mps = msg->speed_mps[r];
        for (size_t axis = 0; axis < 2; ++axis) {
            robot->position_m[axis] = msg->position_m[r][axis];
            robot->output_rate_mps[axis] = msg->output_rate_mps[r][axis];
            robot->output_accel_mps2[axis] = msg->output_accel_mps2[r][axis];
        }
    }
}

/* What every measurement decoding starts with: the arguments, the core's measurement (`size` bytes)
 * zeroed, and the robot count. */
static tvo_status_t measurement_start(const tvo_step_measurement_t *msg, void *meas, size_t size, uint8_t robot_count)
{
    if (msg == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    memset(meas, 0, size);
    return robot_count_matches(msg->robot_count, robot_count) ? TVO_OK : TVO_ERR_DIMENSION;
}

tvo_status_t tvo_step_unicycle_measurement(const tvo_step_measurement_t *msg, uint8_t robot_count, uint32_t stamp_tick,
                                           tvo_measurement_t *meas)
{
    const tvo_status_t st = measurement_start(msg, meas, sizeof(*meas), robot_count);
    if (st != TVO_OK) {
        return st;
    }
    meas->stamp_tick = stamp_tick;
    for (size_t r = 0; r < robot_count; ++r) {
        meas->position_m[r][0] = tvo_wire_real(msg->robot[r].position_m[0]);
        meas->position_m[r][1] = tvo_wire_real(msg->robot[r].position_m[1]);
        meas->heading_rad[r] = tvo_wire_real(msg->robot[r].heading_rad);
        meas->speed_mps[r] = tvo_wire_real(msg->robot[r].speed_mps);
    }
    meas->heading_valid = msg->heading_valid;
    meas->speed_valid = msg->speed_valid;
    return TVO_OK;
}

tvo_status_t tvo_step_chain_measurement(const tvo_step_measurement_t *msg, uint8_t robot_count, uint32_t stamp_tick,
                                        tvo_chain_measurement_t *meas)
{
    const tvo_status_t st = measurement_start(msg, meas, sizeof(*meas), robot_count);
    if (st != TVO_OK) {
        return st;
    }
    meas->stamp_tick = stamp_tick;
    for (size_t r = 0; r < robot_count; ++r) {
        for (size_t axis = 0; axis < 2; ++axis) {
            const size_t i = 2u * r + axis;
            meas->y.d[0][i] = tvo_wire_real(msg->robot[r].position_m[axis]);
            if (msg->derivatives_valid) {
                meas->y.d[1][i] = tvo_wire_real(msg->robot[r].output_rate_mps[axis]);
#if TVO_MAX_RELATIVE_DEGREE >= 3
                meas->y.d[2][i] = tvo_wire_real(msg->robot[r].output_accel_mps2[axis]);
#endif
            }
        }
    }
    return TVO_OK;
}

/* The stamp fields a command and the telemetry that follows it both carry under the same names (the
 * LCM types share no header struct): one mapping for both. */
#define SET_STEP_STAMP(msg, stamp, wire_flags)                     \
    do {                                                           \
        (msg)->utime = (stamp)->utime;                             \
        (msg)->session_id = (stamp)->session_id;                   \
        (msg)->measurement_sequence = (stamp)->sequence;           \
        (msg)->status = tvo_step_wire_status(&(stamp)->why);       \
        (msg)->flags = (int32_t)(wire_flags);                      \
    } while (0)

static void command_stamp(const tvo_step_stamp_t *stamp, uint32_t flags, uint8_t outcome, tvo_lcm_command_t *msg)
{
    memset(msg, 0, sizeof(*msg));
    SET_STEP_STAMP(msg, stamp, tvo_step_wire_flags(flags, (tvo_outcome_t)outcome));
    msg->robot_count = stamp->robot_count;
}

void tvo_step_command_to_lcm(const tvo_command_t *cmd, const tvo_step_stamp_t *stamp, tvo_lcm_command_t *msg)
{
    if (cmd == NULL || stamp == NULL || msg == NULL) {
        return;
    }
    command_stamp(stamp, cmd->flags, cmd->outcome, msg);
    for (size_t r = 0; r < stamp->robot_count && r < TVO_WIRE_SESSION_ROBOTS; ++r) {
        msg->speed_mps[r] = (double)cmd->speed_mps[r];
        msg->turn_rate_radps[r] = (double)cmd->turn_rate_radps[r];
    }
}

void tvo_step_chain_command_to_lcm(const tvo_chain_command_t *cmd, const tvo_step_stamp_t *stamp,
                                   tvo_lcm_command_t *msg)
{
    if (cmd == NULL || stamp == NULL || msg == NULL) {
        return;
    }
    command_stamp(stamp, cmd->flags, cmd->outcome, msg);
    for (size_t i = 0; i < 2u * (size_t)stamp->robot_count && i < 2u * TVO_WIRE_SESSION_ROBOTS; ++i) {
        msg->input[i] = (double)cmd->u[i];
    }
}

void tvo_step_telemetry_stamp(const tvo_step_stamp_t *stamp, uint32_t wire_flags, tvo_lcm_telemetry_t *msg)
{
    if (stamp == NULL || msg == NULL) {
        return;
    }
    SET_STEP_STAMP(msg, stamp, wire_flags);
}

void tvo_step_telemetry_to_lcm(const tvo_controller_telemetry_t *tel, uint8_t robot_count,
                               const tvo_real_t *speed_state_mps, const tvo_problem_t *problem,
                               tvo_lcm_telemetry_t *msg)
{
    if (tel == NULL || speed_state_mps == NULL || problem == NULL || msg == NULL) {
        return;
    }
    /* A session of more robots than the message carries (a fleet's) has no vectors in it: dim 0. */
    const size_t dim = robot_count <= TVO_WIRE_SESSION_ROBOTS ? 2u * (size_t)robot_count : 0u;
    msg->objective_time_s = (double)tel->objective_time_s;
    msg->dim = (int32_t)dim;
    for (size_t i = 0; i < dim; ++i) {
        msg->gradient[i] = (double)tel->gradient[i];
        msg->gradient_rate[i] = (double)tel->gradient_rate[i];
        msg->output_m[i] = (double)tel->output_m[i];
        msg->output_rate_mps[i] = (double)tel->output_rate_mps[i];
        msg->output_accel_mps2[i] = (double)tel->output_accel_mps2[i];
    }
    for (size_t r = 0; 2u * r < dim; ++r) {
        msg->speed_state_mps[r] = (double)speed_state_mps[r];
    }
    const size_t multipliers = problem->objective.dual_dim;
    for (size_t q = 0; q < multipliers && q < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES) && q < 4u; ++q) {
        msg->multiplier[q] = (double)tel->multiplier[q];
    }
    msg->regularization = (double)tel->regularization;
    if (problem->has_inequalities) {
        tvo_real_t c = TVO_R(0.0);
        tvo_real_t slack = TVO_R(0.0);
        tvo_real_t delta = TVO_R(0.0);
        const tvo_real_t t_s = tel->objective_time_s >= TVO_R(0.0) ? tel->objective_time_s : TVO_R(0.0);
        if (tvo_barrier_schedule(&problem->barrier, t_s, &c, &slack, &delta) == TVO_OK) {
            msg->barrier_c = (double)c;
            msg->barrier_slack = (double)slack;
        }
    }
}

tvo_status_t tvo_step_target_from_lcm(const tvo_lcm_target_t *msg, uint8_t robot_count, uint64_t objective_ticks,
                                      tvo_problem_t *problem)
{
    return tvo_step_target_from_lcm_carried(msg, robot_count, objective_ticks, 0.0, problem);
}

tvo_status_t tvo_step_target_from_lcm_carried(const tvo_lcm_target_t *msg, uint8_t robot_count,
                                              uint64_t objective_ticks, double carry_s, tvo_problem_t *problem)
{
    if (msg == NULL || problem == NULL) {
        return TVO_ERR_NULL;
    }
    if (!(carry_s >= 0.0 && carry_s <= 1.0)) {
        return TVO_ERR_PARAM;
    }
    if (!robot_count_matches(msg->robot_count, robot_count) || robot_count > TVO_WIRE_SESSION_ROBOTS) {
        return TVO_ERR_DIMENSION;
    }
    /* Every robot's target must take the sample: check all before feeding any (nothing half-kept). */
    for (uint8_t r = 0; r < robot_count; ++r) {
        const tvo_target_t *target = tvo_problem_target(problem, r);
        if (target == NULL) {
            return TVO_ERR_NOT_INITIALIZED;
        }
        if (target->kind != TVO_TARGET_STREAMED) {
            return TVO_ERR_PARAM;
        }
        for (size_t axis = 0; axis < 2; ++axis) {
            if (!isfinite(tvo_wire_real(msg->position_m[r][axis])) ||
                !isfinite(tvo_wire_real(msg->velocity_mps[r][axis])) ||
                !isfinite(tvo_wire_real(msg->acceleration_mps2[r][axis])) ||
                !isfinite(tvo_wire_real(msg->jerk_mps3[r][axis]))) {
                return TVO_ERR_NOT_FINITE;
            }
        }
    }
    tvo_status_t st = TVO_OK;
    for (uint8_t r = 0; st == TVO_OK && r < robot_count; ++r) {
        tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2];
        for (size_t axis = 0; axis < 2; ++axis) {
            const double p = msg->position_m[r][axis], v = msg->velocity_mps[r][axis];
            const double a = msg->acceleration_mps2[r][axis], j = msg->jerk_mps3[r][axis];
            const double dt = carry_s;
            deriv[0][axis] = tvo_wire_real(p + dt * (v + dt * (a / 2.0 + dt * j / 6.0)));
            deriv[1][axis] = tvo_wire_real(v + dt * (a + dt * j / 2.0));
            deriv[2][axis] = tvo_wire_real(a + dt * j);
            deriv[3][axis] = tvo_wire_real(j);
        }
        st = tvo_target_stream_update(tvo_problem_target(problem, r), objective_ticks,
                                      (const tvo_real_t(*)[2])deriv); /* adds const only (C11) */
    }
    return st;
}
