/* LCM <-> control-core conversions of the firmware node; see lcm_edge.h. */
#include "lcm_edge.h"

#include <float.h>
#include <string.h>

/* Stride of one robot's block in session_t.target_params (circle, ellipse). */
#define EDGE_TARGET_STRIDE 8
/* Stride of one robot's and one axis's block for polynomial targets. */
#define EDGE_POLY_ROBOT_STRIDE 16
#define EDGE_POLY_AXIS_STRIDE 8

/* A wire double as the core's scalar. Out of float range becomes +-infinity, which the core rejects
 * as not finite (a plain conversion of such a value to float is undefined behaviour in C). */
static tvo_real_t edge_real(double value)
{
#if !TVO_USE_DOUBLE
    if (value > (double)FLT_MAX) {
        return INFINITY;
    }
    if (value < -(double)FLT_MAX) {
        return -INFINITY;
    }
#endif
    return (tvo_real_t)value;
}

static tvo_status_t edge_reject(tvo_param_t param, tvo_param_t *bad_param)
{
    if (bad_param != NULL) {
        *bad_param = param;
    }
    return TVO_ERR_PARAM;
}

/* One robot's on-board target from the session's parameter block. */
static tvo_status_t edge_target_init(tvo_target_t *target, int32_t kind, const double *params, uint8_t robot)
{
    const double *p = params + (size_t)robot * EDGE_TARGET_STRIDE;
    switch (kind) {
    case TVO_LCM_SESSION_T_TARGET_POLYNOMIAL: {
        tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
        const double *q = params + (size_t)robot * EDGE_POLY_ROBOT_STRIDE;
        for (size_t axis = 0; axis < 2; ++axis) {
            for (size_t j = 0; j <= TVO_POLY_MAX_DEGREE; ++j) {
                coeff[axis][j] = edge_real(q[axis * EDGE_POLY_AXIS_STRIDE + j]);
            }
        }
        /* C11 does not convert T (*)[n] to const T (*)[n] implicitly: the cast only adds const. */
        return tvo_target_init_polynomial(target, (const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])coeff);
    }
    case TVO_LCM_SESSION_T_TARGET_CIRCLE: {
        const tvo_real_t center_m[2] = {edge_real(p[0]), edge_real(p[1])};
        return tvo_target_init_circle(target, center_m, edge_real(p[2]), edge_real(p[3]), edge_real(p[4]));
    }
    case TVO_LCM_SESSION_T_TARGET_ELLIPSE: {
        tvo_target_ellipse_t ellipse;
        ellipse.center_m[0] = edge_real(p[0]);
        ellipse.center_m[1] = edge_real(p[1]);
        ellipse.semi_axis_m[0] = edge_real(p[2]);
        ellipse.semi_axis_m[1] = edge_real(p[3]);
        ellipse.omega_radps = edge_real(p[4]);
        ellipse.phase_rad = edge_real(p[5]);
        ellipse.rotation_rad = edge_real(p[6]);
        return tvo_target_init_ellipse(target, &ellipse);
    }
    case TVO_LCM_SESSION_T_TARGET_STREAMED:
        return tvo_target_init_streamed(target);
    default:
        return TVO_ERR_PARAM;
    }
}

/* Timing values that would wrap when narrowed to the core's unsigned fields are rejected here (both
 * controllers); the core validates the rest of the ranges. */
static tvo_status_t edge_timing_ok(const tvo_lcm_session_t *msg, tvo_param_t *bad_param)
{
    if (msg->period_us <= 0 || msg->period_us > (int64_t)UINT32_MAX) {
        return edge_reject(TVO_PARAM_PERIOD, bad_param);
    }
    if (msg->delay_us < 0 || msg->delay_us > (int64_t)UINT32_MAX) {
        return edge_reject(TVO_PARAM_DELAY, bad_param);
    }
    if (msg->watchdog_periods < 0) {
        return edge_reject(TVO_PARAM_WATCHDOG, bad_param);
    }
    return TVO_OK;
}

/* Controller configuration from the session; the core validates ranges, the edge only casts safely. */
static tvo_status_t edge_config_from_session(const tvo_lcm_session_t *msg, tvo_controller_config_t *cfg,
                                             tvo_param_t *bad_param)
{
    tvo_status_t st = tvo_controller_config_default(cfg);
    if (st != TVO_OK) {
        return st;
    }
    st = edge_timing_ok(msg, bad_param);
    if (st != TVO_OK) {
        return st;
    }
    if (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSE) {
        cfg->velocity_source = TVO_VELOCITY_FROM_POSE;
    } else if (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION) {
        cfg->velocity_source = TVO_VELOCITY_FROM_POSITION;
    } else {
        return edge_reject(TVO_PARAM_VELOCITY_SOURCE, bad_param);
    }
    cfg->tick_hz = TVO_EDGE_TICK_HZ;
    cfg->period_ticks = (uint32_t)msg->period_us;
    cfg->delay_ticks = (uint32_t)msg->delay_us;
    cfg->robot_count = (uint8_t)msg->robot_count;
    cfg->delay_compensation = msg->delay_compensation ? 1u : 0u;
    cfg->zoh_aware = msg->zoh_aware ? 1u : 0u;
    cfg->filter_tf_s = edge_real(msg->filter_tf_s);
    cfg->gain_kp = edge_real(msg->gain_kp);
    cfg->gain_kd = edge_real(msg->gain_kd);
    cfg->omega_max_radps = edge_real(msg->omega_max_radps);
    cfg->accel_max_mps2 = edge_real(msg->accel_max_mps2);
    cfg->speed_max_mps = edge_real(msg->speed_max_mps);
    cfg->min_speed_mps = edge_real(msg->min_speed_mps);
    cfg->watchdog_periods = (uint32_t)msg->watchdog_periods;
    for (size_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        cfg->initial_speed_mps[r] = edge_real(msg->initial_speed_mps[r]);
    }
    return TVO_OK;
}

/* Parts of the problem named in a rejection (session_ack_t.PART_*), from tvo_problem_init's index. */
static int32_t edge_part_from_problem(uint8_t problem_part)
{
    static const int32_t parts[] = {
        TVO_LCM_SESSION_ACK_T_PART_ROBOTS,    TVO_LCM_SESSION_ACK_T_PART_BARRIER,
        TVO_LCM_SESSION_ACK_T_PART_DISTANCE,  TVO_LCM_SESSION_ACK_T_PART_HALFSPACE,
        TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, TVO_LCM_SESSION_ACK_T_PART_OFFSETS};
    return problem_part < sizeof(parts) / sizeof(parts[0]) ? parts[problem_part] : TVO_LCM_SESSION_ACK_T_PART_NONE;
}

/* A count from the wire, 0 .. max; anything else would index past the message's arrays. */
static int edge_count_ok(int32_t count, int32_t max)
{
    return count >= 0 && count <= max;
}

/* A robot index from the wire: 0 .. robot_count - 1 (checked before narrowing to uint8_t). */
static int edge_robot_ok(int32_t robot, uint8_t robot_count)
{
    return robot >= 0 && robot < (int32_t)robot_count;
}

static tvo_status_t edge_barrier_from_session(const tvo_lcm_session_t *msg, tvo_barrier_config_t *cfg)
{
    if (msg->barrier_relaxation_degree < 0 || msg->barrier_relaxation_degree > (int32_t)UINT8_MAX) {
        return TVO_ERR_PARAM;
    }
    cfg->c0 = edge_real(msg->barrier_c0);
    cfg->alpha_c_per_s = edge_real(msg->barrier_alpha_c_per_s);
    cfg->c_max = edge_real(msg->barrier_c_max);
    cfg->delta0 = edge_real(msg->barrier_delta0);
    cfg->alpha_s_per_s = edge_real(msg->barrier_alpha_s_per_s);
    cfg->slack_margin = edge_real(msg->barrier_slack_margin);
    cfg->relaxation_degree = (uint8_t)msg->barrier_relaxation_degree;
    return TVO_OK;  /* ranges: tvo_barrier_init, through tvo_problem_init */
}

static tvo_status_t edge_distances_from_session(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc)
{
    if (!edge_count_ok(msg->distance_count, TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS) ||
        msg->distance_count > TVO_MAX_DISTANCE_BOUNDS) {
        return TVO_ERR_CAPACITY;
    }
    desc->distance_count = (uint8_t)msg->distance_count;
    for (size_t i = 0; i < desc->distance_count; ++i) {
        if (!edge_robot_ok(msg->distance_robot_a[i], desc->robot_count) ||
            !edge_robot_ok(msg->distance_robot_b[i], desc->robot_count)) {
            return TVO_ERR_PARAM;
        }
        tvo_distance_bound_desc_t *d = &desc->distance[i];
        d->robot_a = (uint8_t)msg->distance_robot_a[i];
        d->robot_b = (uint8_t)msg->distance_robot_b[i];
        d->min_m = edge_real(msg->distance_min_m[i]);
        d->min_rate_mps = edge_real(msg->distance_min_rate_mps[i]);
        d->max_m = edge_real(msg->distance_max_m[i]);
        d->max_rate_mps = edge_real(msg->distance_max_rate_mps[i]);
    }
    return TVO_OK;
}

static tvo_status_t edge_halfspaces_from_session(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc)
{
    if (!edge_count_ok(msg->halfspace_count, TVO_LCM_SESSION_T_MAX_HALFSPACES) ||
        msg->halfspace_count > TVO_MAX_HALFSPACES) {
        return TVO_ERR_CAPACITY;
    }
    desc->halfspace_count = (uint8_t)msg->halfspace_count;
    for (size_t i = 0; i < desc->halfspace_count; ++i) {
        if (!edge_robot_ok(msg->halfspace_robot[i], desc->robot_count)) {
            return TVO_ERR_PARAM;
        }
        tvo_halfspace_desc_t *h = &desc->halfspace[i];
        h->robot = (uint8_t)msg->halfspace_robot[i];
        for (size_t axis = 0; axis < 2; ++axis) {
            h->normal[axis] = edge_real(msg->halfspace_normal[i][axis]);
            h->normal_rate[axis] = edge_real(msg->halfspace_normal_rate[i][axis]);
        }
        h->bound_m = edge_real(msg->halfspace_bound_m[i]);
        h->bound_rate_mps = edge_real(msg->halfspace_bound_rate_mps[i]);
    }
    return TVO_OK;
}

static tvo_status_t edge_obstacles_from_session(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc)
{
    if (!edge_count_ok(msg->obstacle_count, TVO_LCM_SESSION_T_MAX_OBSTACLES) ||
        msg->obstacle_count > TVO_MAX_OBSTACLES) {
        return TVO_ERR_CAPACITY;
    }
    desc->obstacle_count = (uint8_t)msg->obstacle_count;
    desc->robot_radius_m = edge_real(msg->robot_radius_m);
    for (size_t i = 0; i < desc->obstacle_count; ++i) {
        desc->obstacle[i].center_m[0] = edge_real(msg->obstacle_center_m[i][0]);
        desc->obstacle[i].center_m[1] = edge_real(msg->obstacle_center_m[i][1]);
        desc->obstacle[i].radius_m = edge_real(msg->obstacle_radius_m[i]);
    }
    return TVO_OK;  /* radii, disjointness: tvo_free_space_term_init */
}

static tvo_status_t edge_offsets_from_session(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc)
{
    if (!edge_count_ok(msg->offset_count, TVO_LCM_SESSION_T_MAX_OFFSETS) ||
        msg->offset_count > TVO_MAX_OFFSET_EQUALITIES) {
        return TVO_ERR_CAPACITY;
    }
    desc->offset_count = (uint8_t)msg->offset_count;
    for (size_t i = 0; i < desc->offset_count; ++i) {
        /* d(t) has no stream of its own on the wire: only on-board time functions. */
        if (!edge_robot_ok(msg->offset_robot_a[i], desc->robot_count) ||
            !edge_robot_ok(msg->offset_robot_b[i], desc->robot_count) ||
            msg->offset_kind[i] == TVO_LCM_SESSION_T_TARGET_STREAMED) {
            return TVO_ERR_PARAM;
        }
        tvo_offset_desc_t *o = &desc->offset[i];
        o->robot_a = (uint8_t)msg->offset_robot_a[i];
        o->robot_b = (uint8_t)msg->offset_robot_b[i];
        const tvo_status_t st = edge_target_init(&o->offset, msg->offset_kind[i], msg->offset_params[i], 0u);
        if (st != TVO_OK) {
            return st;
        }
    }
    return TVO_OK;
}

/* The problem description from the session; *bad_part names the first part the wire got wrong. */
static tvo_status_t edge_problem_desc_from_session(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                                   int32_t *bad_part)
{
    tvo_status_t st = tvo_problem_desc_default(desc);
    if (st != TVO_OK) {
        return st;
    }
    desc->robot_count = (uint8_t)msg->robot_count;  /* 1 .. TVO_MAX_ROBOTS, checked by the caller */
    *bad_part = TVO_LCM_SESSION_ACK_T_PART_ROBOTS;
    for (uint8_t r = 0; st == TVO_OK && r < desc->robot_count; ++r) {
        desc->tracking_weight[r][0] = edge_real(msg->tracking_weight[r][0]);
        desc->tracking_weight[r][1] = edge_real(msg->tracking_weight[r][1]);
        st = edge_target_init(&desc->target[r], msg->target_kind, msg->target_params, r);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_BARRIER;
        st = edge_barrier_from_session(msg, &desc->barrier);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_DISTANCE;
        st = edge_distances_from_session(msg, desc);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_HALFSPACE;
        st = edge_halfspaces_from_session(msg, desc);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_OBSTACLES;
        st = edge_obstacles_from_session(msg, desc);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_OFFSETS;
        st = edge_offsets_from_session(msg, desc);
    }
    if (st == TVO_OK) {
        *bad_part = TVO_LCM_SESSION_ACK_T_PART_NONE;
    }
    return st;
}

/* The chain controller's configuration (session PLANT_CHAIN); the core validates ranges. */
static tvo_status_t edge_chain_config_from_session(const tvo_lcm_session_t *msg, tvo_chain_config_t *cfg,
                                                   tvo_param_t *bad_param)
{
    tvo_status_t st = tvo_chain_config_default(cfg);
    if (st != TVO_OK) {
        return st;
    }
    st = edge_timing_ok(msg, bad_param);
    if (st != TVO_OK) {
        return st;
    }
    if (msg->chain_relative_degree < 1 || msg->chain_relative_degree > TVO_MAX_RELATIVE_DEGREE) {
        return edge_reject(TVO_PARAM_GAINS, bad_param);
    }
    cfg->tick_hz = TVO_EDGE_TICK_HZ;
    cfg->period_ticks = (uint32_t)msg->period_us;
    cfg->delay_ticks = (uint32_t)msg->delay_us;
    cfg->relative_degree = (uint8_t)msg->chain_relative_degree;
    cfg->delay_compensation = msg->delay_compensation ? 1u : 0u;
    cfg->zoh_aware = msg->zoh_aware ? 1u : 0u;
    cfg->filtered_derivatives = (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION) ? 1u : 0u;
    cfg->filter_tf_s = edge_real(msg->filter_tf_s);
    for (size_t i = 0; i < TVO_MAX_RELATIVE_DEGREE; ++i) {
        cfg->gain[i] = edge_real(msg->chain_gains[i]);
    }
    cfg->input_max = edge_real(msg->chain_input_max);
    cfg->watchdog_periods = (uint32_t)msg->watchdog_periods;
    return TVO_OK;
}

/* The problem: the edge's wire checks, then the core's (which names its own part). */
static tvo_status_t edge_problem_from_session(tvo_edge_session_t *session, const tvo_lcm_session_t *msg,
                                              tvo_param_t *bad_param, int32_t *bad_part)
{
    tvo_problem_desc_t desc;
    tvo_status_t st = edge_problem_desc_from_session(msg, &desc, bad_part);
    if (st == TVO_OK) {
        uint8_t problem_part = 0;
        /* The flat output's relative degree bounds the barrier's m_r below: 2 for the unicycle. */
        const uint8_t k = session->plant_chain ? (uint8_t)msg->chain_relative_degree : 2u;
        st = tvo_problem_init(&session->problem, &desc, k, &problem_part);
        if (st != TVO_OK) {
            *bad_part = edge_part_from_problem(problem_part);
        }
    }
    if (st != TVO_OK && bad_param != NULL) {
        *bad_param = TVO_PARAM_OBJECTIVE;
    }
    return st;
}

const char *tvo_edge_part_str(int32_t part)
{
    switch (part) {
    case TVO_LCM_SESSION_ACK_T_PART_NONE: return "none";
    case TVO_LCM_SESSION_ACK_T_PART_ROBOTS: return "robots/targets";
    case TVO_LCM_SESSION_ACK_T_PART_BARRIER: return "barrier";
    case TVO_LCM_SESSION_ACK_T_PART_DISTANCE: return "distance bounds";
    case TVO_LCM_SESSION_ACK_T_PART_HALFSPACE: return "half-spaces";
    case TVO_LCM_SESSION_ACK_T_PART_OBSTACLES: return "obstacles";
    case TVO_LCM_SESSION_ACK_T_PART_OFFSETS: return "formation offsets";
    default: return "unknown part";
    }
}

tvo_status_t tvo_edge_session_start(tvo_edge_session_t *session, const tvo_lcm_session_t *msg,
                                    tvo_param_t *bad_param, int32_t *bad_part)
{
    int32_t part = TVO_LCM_SESSION_ACK_T_PART_NONE;
    if (bad_part != NULL) {
        *bad_part = part;
    }
    if (session == NULL || msg == NULL) {
        return TVO_ERR_NULL;
    }
    if (bad_param != NULL) {
        *bad_param = TVO_PARAM_NONE;
    }
    session->active = 0;
    session->has_sequence = 0;
    session->session_id = msg->session_id;
    if (msg->robot_count < 1 || msg->robot_count > TVO_MAX_ROBOTS) {
        return edge_reject(TVO_PARAM_ROBOT_COUNT, bad_param);
    }
    session->robot_count = (uint8_t)msg->robot_count;
    session->period_us = msg->period_us;
    session->delay_us = msg->delay_us;
    if (msg->plant_kind != TVO_LCM_SESSION_T_PLANT_UNICYCLE && msg->plant_kind != TVO_LCM_SESSION_T_PLANT_CHAIN) {
        return edge_reject(TVO_PARAM_OBJECTIVE, bad_param);
    }
    session->plant_chain = (msg->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN) ? 1u : 0u;
    if (session->plant_chain) {
        tvo_chain_config_t chain_cfg;
        tvo_status_t chain_st = edge_chain_config_from_session(msg, &chain_cfg, bad_param);
        if (chain_st == TVO_OK) {
            chain_st = edge_problem_from_session(session, msg, bad_param, &part);
        }
        if (chain_st == TVO_OK) {
            chain_st = tvo_chain_controller_init(&session->chain, &chain_cfg, &session->problem.objective,
                                                 (uint32_t)msg->epoch_utime, bad_param);
        }
        if (bad_part != NULL) {
            *bad_part = part;
        }
        session->active = (chain_st == TVO_OK) ? 1u : 0u;
        return chain_st;
    }

    tvo_controller_config_t cfg;
    tvo_status_t st = edge_config_from_session(msg, &cfg, bad_param);
    if (st == TVO_OK) {
        st = edge_problem_from_session(session, msg, bad_param, &part);
    }
    if (st == TVO_OK) {
        st = tvo_controller_init(&session->controller, &cfg, &session->problem.objective,
                                 (uint32_t)msg->epoch_utime, bad_param);
    }
    if (bad_part != NULL) {
        *bad_part = part;
    }
    session->active = (st == TVO_OK) ? 1u : 0u;
    return st;
}

tvo_status_t tvo_edge_choose_slack(tvo_edge_session_t *session, const tvo_measurement_t *meas)
{
    if (session == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    tvo_real_t y[TVO_MAX_OUTPUT_DIM];
    for (size_t r = 0; r < session->robot_count; ++r) {
        y[2u * r] = meas->position_m[r][0];
        y[2u * r + 1u] = meas->position_m[r][1];
        if (!isfinite(y[2u * r]) || !isfinite(y[2u * r + 1u])) {
            return TVO_ERR_NOT_FINITE;  /* the controller rejects this sample too; wait for a good one */
        }
    }
    /* s0 from f_i(y(0), 0): the first usable sample stands for the state at the objective's t = 0. */
    return tvo_problem_choose_slack(&session->problem, y, TVO_R(0.0));
}

tvo_status_t tvo_edge_measurement_from_lcm(const tvo_lcm_measurement_t *msg, uint8_t robot_count,
                                           tvo_measurement_t *meas)
{
    if (msg == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    memset(meas, 0, sizeof(*meas));
    if (msg->robot_count != (int32_t)robot_count) {
        return TVO_ERR_DIMENSION;
    }
    meas->stamp_tick = (uint32_t)msg->utime;
    for (size_t r = 0; r < robot_count; ++r) {
        meas->position_m[r][0] = edge_real(msg->position_m[r][0]);
        meas->position_m[r][1] = edge_real(msg->position_m[r][1]);
        meas->heading_rad[r] = edge_real(msg->heading_rad[r]);
        meas->speed_mps[r] = edge_real(msg->speed_mps[r]);
    }
    meas->heading_valid = msg->heading_valid ? 1u : 0u;
    meas->speed_valid = msg->speed_valid ? 1u : 0u;
    return TVO_OK;
}

tvo_status_t tvo_edge_chain_measurement_from_lcm(const tvo_lcm_measurement_t *msg, uint8_t robot_count,
                                                 tvo_chain_measurement_t *meas)
{
    if (msg == NULL || meas == NULL) {
        return TVO_ERR_NULL;
    }
    memset(meas, 0, sizeof(*meas));
    if (msg->robot_count != (int32_t)robot_count) {
        return TVO_ERR_DIMENSION;
    }
    meas->stamp_tick = (uint32_t)msg->utime;
    for (size_t r = 0; r < robot_count; ++r) {
        for (size_t axis = 0; axis < 2; ++axis) {
            const size_t i = 2u * r + axis;
            meas->y.d[0][i] = edge_real(msg->position_m[r][axis]);
            if (msg->derivatives_valid) {
                meas->y.d[1][i] = edge_real(msg->output_rate_mps[r][axis]);
#if TVO_MAX_RELATIVE_DEGREE >= 3
                meas->y.d[2][i] = edge_real(msg->output_accel_mps2[r][axis]);
#endif
            }
        }
    }
    return TVO_OK;
}

void tvo_edge_chain_command_to_lcm(const tvo_chain_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                                   int64_t sequence, uint8_t robot_count, tvo_lcm_command_t *msg)
{
    memset(msg, 0, sizeof(*msg));
    msg->utime = apply_utime;
    msg->measurement_sequence = sequence;
    msg->robot_count = robot_count;
    for (size_t i = 0; i < 2u * (size_t)robot_count && i < TVO_MAX_OUTPUT_DIM && i < 8u; ++i) {
        msg->input[i] = (double)cmd->u[i];
    }
    msg->status = (int32_t)status;
    msg->flags = (int32_t)cmd->flags;
}

void tvo_edge_command_to_lcm(const tvo_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                             int64_t sequence, uint8_t robot_count, tvo_lcm_command_t *msg)
{
    memset(msg, 0, sizeof(*msg));
    msg->utime = apply_utime;
    msg->measurement_sequence = sequence;
    msg->robot_count = robot_count;
    for (size_t r = 0; r < robot_count && r < TVO_MAX_ROBOTS; ++r) {
        msg->speed_mps[r] = (double)cmd->speed_mps[r];
        msg->turn_rate_radps[r] = (double)cmd->turn_rate_radps[r];
    }
    msg->status = (int32_t)status;
    msg->flags = (int32_t)cmd->flags;
}

void tvo_edge_telemetry_to_lcm(const tvo_edge_session_t *session, tvo_status_t status, uint32_t flags,
                               int64_t apply_utime, int64_t sequence, tvo_lcm_telemetry_t *msg)
{
    memset(msg, 0, sizeof(*msg));
    const tvo_controller_t *ctl = &session->controller;
    const tvo_controller_telemetry_t *tel = &ctl->telemetry;
    const size_t dim = 2u * (size_t)ctl->cfg.robot_count;
    msg->utime = apply_utime;
    msg->measurement_sequence = sequence;
    msg->status = (int32_t)status;
    msg->flags = (int32_t)flags;
    msg->objective_time_s = (double)tel->objective_time_s;
    msg->dim = (int32_t)dim;
    for (size_t i = 0; i < dim && i < TVO_MAX_OUTPUT_DIM; ++i) {
        msg->gradient[i] = (double)tel->gradient[i];
        msg->gradient_rate[i] = (double)tel->gradient_rate[i];
        msg->output_m[i] = (double)tel->output_m[i];
        msg->output_rate_mps[i] = (double)tel->output_rate_mps[i];
        msg->output_accel_mps2[i] = (double)tel->output_accel_mps2[i];
    }
    for (size_t r = 0; r < ctl->cfg.robot_count && r < TVO_MAX_ROBOTS; ++r) {
        msg->speed_state_mps[r] = (double)ctl->speed_state_mps[r];
    }
    const size_t multipliers = session->problem.objective.dual_dim;
    for (size_t q = 0; q < multipliers && q < TVO_MAX_EQUALITIES && q < 4u; ++q) {
        msg->multiplier[q] = (double)tel->multiplier[q];
    }
    msg->regularization = (double)tel->regularization;
    if (session->problem.has_inequalities) {
        tvo_real_t c = TVO_R(0.0);
        tvo_real_t slack = TVO_R(0.0);
        tvo_real_t delta = TVO_R(0.0);
        const tvo_real_t t_s = tel->objective_time_s >= TVO_R(0.0) ? tel->objective_time_s : TVO_R(0.0);
        if (tvo_barrier_schedule(&session->problem.barrier, t_s, &c, &slack, &delta) == TVO_OK) {
            msg->barrier_c = (double)c;
            msg->barrier_slack = (double)slack;
        }
    }
}

tvo_status_t tvo_edge_target_update(tvo_edge_session_t *session, const tvo_lcm_target_t *msg)
{
    if (session == NULL || msg == NULL) {
        return TVO_ERR_NULL;
    }
    if (!session->active) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (msg->robot_count != (int32_t)session->robot_count) {
        return TVO_ERR_DIMENSION;
    }
    uint64_t stamp_ticks = 0;
    tvo_status_t st = tvo_controller_objective_ticks(&session->controller, (uint32_t)msg->utime, &stamp_ticks);
    for (uint8_t r = 0; st == TVO_OK && r < session->robot_count; ++r) {
        tvo_target_t *target = tvo_problem_target(&session->problem, r);
        if (target == NULL) {
            return TVO_ERR_NOT_INITIALIZED;
        }
        if (target->kind != TVO_TARGET_STREAMED) {
            return TVO_ERR_PARAM;
        }
        tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2];
        for (size_t axis = 0; axis < 2; ++axis) {
            deriv[0][axis] = edge_real(msg->position_m[r][axis]);
            deriv[1][axis] = edge_real(msg->velocity_mps[r][axis]);
            deriv[2][axis] = edge_real(msg->acceleration_mps2[r][axis]);
            deriv[3][axis] = edge_real(msg->jerk_mps3[r][axis]);
        }
        st = tvo_target_stream_update(target, stamp_ticks,
                                      (const tvo_real_t(*)[2])deriv);  /* adds const only (C11) */
    }
    return st;
}

void tvo_edge_ack_to_lcm(int64_t utime, int64_t session_id, int8_t action, tvo_status_t status,
                         tvo_param_t bad_param, int32_t bad_part, tvo_lcm_session_ack_t *msg)
{
    memset(msg, 0, sizeof(*msg));
    msg->utime = utime;
    msg->session_id = session_id;
    msg->action = action;
    msg->status = (int32_t)status;
    msg->bad_param = (int32_t)bad_param;
    msg->bad_part = bad_part;
}
