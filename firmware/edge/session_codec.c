/* START message -> core configuration, and the session ack; see session_codec.h. */
#include "session_codec.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "tvo/sample_clock.h"
#include "step_codec.h"
#include "tvo_lcm_node_status_t.h"
#include "wire_real.h"

/* The wire's fixed arrays must hold what the core can use (the reverse is checked per count). */
_Static_assert(TVO_LCM_PATH_T_MAX_COEFFS >= TVO_POLY_MAX_DEGREE + 1, "path_t.coeff holds the core's polynomials");
_Static_assert(TVO_LCM_SESSION_T_MAX_ROBOTS >= TVO_MAX_ROBOTS, "session_t.robot holds every robot");
_Static_assert(TVO_SESSION_EPOCH_SPAN_US == (int64_t)(TVO_MAX_TICK_SPAN / 2u), "the epoch span is half the clock span");

/* The session's parameters are the wire's numbers (session_ack_t.PARAM_*). */
#define SESSION_PARAM_ON_WIRE(name) \
    _Static_assert(TVO_SESSION_PARAM_##name == TVO_LCM_SESSION_ACK_T_PARAM_##name, "session_ack_t.PARAM_" #name)
SESSION_PARAM_ON_WIRE(NONE); SESSION_PARAM_ON_WIRE(TICK_HZ); SESSION_PARAM_ON_WIRE(PERIOD); SESSION_PARAM_ON_WIRE(DELAY);
SESSION_PARAM_ON_WIRE(FILTER_TF); SESSION_PARAM_ON_WIRE(GAINS); SESSION_PARAM_ON_WIRE(OMEGA_MAX);
SESSION_PARAM_ON_WIRE(ACCEL_MAX); SESSION_PARAM_ON_WIRE(SPEED_MAX); SESSION_PARAM_ON_WIRE(MIN_SPEED);
SESSION_PARAM_ON_WIRE(WATCHDOG); SESSION_PARAM_ON_WIRE(ROBOT_COUNT); SESSION_PARAM_ON_WIRE(OBJECTIVE);
SESSION_PARAM_ON_WIRE(VELOCITY_SOURCE); SESSION_PARAM_ON_WIRE(INITIAL_SPEED); SESSION_PARAM_ON_WIRE(EPOCH);
SESSION_PARAM_ON_WIRE(CLOCK_SOURCE); SESSION_PARAM_ON_WIRE(PLANT_KIND); SESSION_PARAM_ON_WIRE(SESSION_ID);
SESSION_PARAM_ON_WIRE(PROTOCOL_VERSION); SESSION_PARAM_ON_WIRE(TELEMETRY_EVERY);

/* Each configuration's fields onto the START's (the wire's ids), one table each. */
static const uint8_t session_param_of_unicycle[TVO_PARAM_COUNT] = {
    [TVO_PARAM_NONE] = TVO_SESSION_PARAM_NONE, [TVO_PARAM_TICK_HZ] = TVO_SESSION_PARAM_TICK_HZ,
    [TVO_PARAM_PERIOD] = TVO_SESSION_PARAM_PERIOD, [TVO_PARAM_DELAY] = TVO_SESSION_PARAM_DELAY,
    [TVO_PARAM_FILTER_TF] = TVO_SESSION_PARAM_FILTER_TF, [TVO_PARAM_GAINS] = TVO_SESSION_PARAM_GAINS,
    [TVO_PARAM_OMEGA_MAX] = TVO_SESSION_PARAM_OMEGA_MAX, [TVO_PARAM_ACCEL_MAX] = TVO_SESSION_PARAM_ACCEL_MAX,
    [TVO_PARAM_SPEED_MAX] = TVO_SESSION_PARAM_SPEED_MAX, [TVO_PARAM_MIN_SPEED] = TVO_SESSION_PARAM_MIN_SPEED,
    [TVO_PARAM_WATCHDOG] = TVO_SESSION_PARAM_WATCHDOG, [TVO_PARAM_ROBOT_COUNT] = TVO_SESSION_PARAM_ROBOT_COUNT,
    [TVO_PARAM_OBJECTIVE] = TVO_SESSION_PARAM_OBJECTIVE, [TVO_PARAM_VELOCITY_SOURCE] = TVO_SESSION_PARAM_VELOCITY_SOURCE,
    [TVO_PARAM_INITIAL_SPEED] = TVO_SESSION_PARAM_INITIAL_SPEED};

static const uint8_t session_param_of_chain[TVO_CHAIN_PARAM_COUNT] = {
    [TVO_CHAIN_PARAM_NONE] = TVO_SESSION_PARAM_NONE, [TVO_CHAIN_PARAM_TICK_HZ] = TVO_SESSION_PARAM_TICK_HZ,
    [TVO_CHAIN_PARAM_PERIOD] = TVO_SESSION_PARAM_PERIOD, [TVO_CHAIN_PARAM_DELAY] = TVO_SESSION_PARAM_DELAY,
    [TVO_CHAIN_PARAM_RELATIVE_DEGREE] = TVO_SESSION_PARAM_GAINS, [TVO_CHAIN_PARAM_GAIN] = TVO_SESSION_PARAM_GAINS,
    [TVO_CHAIN_PARAM_FILTER_TF] = TVO_SESSION_PARAM_FILTER_TF, [TVO_CHAIN_PARAM_INPUT_MAX] = TVO_SESSION_PARAM_ACCEL_MAX,
    [TVO_CHAIN_PARAM_WATCHDOG] = TVO_SESSION_PARAM_WATCHDOG, [TVO_CHAIN_PARAM_OBJECTIVE] = TVO_SESSION_PARAM_OBJECTIVE};

tvo_session_param_t tvo_session_param_of_unicycle(tvo_param_t param)
{
    return ((uint32_t)param < TVO_PARAM_COUNT) ? (tvo_session_param_t)session_param_of_unicycle[param]
                                               : TVO_SESSION_PARAM_NONE;
}

tvo_session_param_t tvo_session_param_of_chain(tvo_chain_param_t param)
{
    return ((uint32_t)param < TVO_CHAIN_PARAM_COUNT) ? (tvo_session_param_t)session_param_of_chain[param]
                                                     : TVO_SESSION_PARAM_NONE;
}

static tvo_status_t reject(tvo_session_reject_t *why, tvo_status_t status, tvo_session_param_t param, int32_t part,
                           int32_t index)
{
    if (why != NULL) {
        why->node = TVO_NODE_OK;
        why->status = status;
        why->param = param;
        why->part = part;
        why->index = index;
    }
    return status;
}

static tvo_status_t reject_param(tvo_session_reject_t *why, tvo_session_param_t param)
{
    return reject(why, TVO_ERR_PARAM, param, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
}

static tvo_status_t reject_part(tvo_session_reject_t *why, tvo_status_t status, int32_t part, int32_t index)
{
    return reject(why, status, TVO_SESSION_PARAM_OBJECTIVE, part, index);
}

static int wire_time_ok(int64_t t)
{
    return t >= 0 && t <= TVO_WIRE_TIME_MAX_US;
}

tvo_status_t tvo_session_decode_timing(const tvo_lcm_session_t *msg, tvo_session_timing_t *timing,
                                       tvo_session_reject_t *why)
{
    (void)reject(why, TVO_OK, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    if (msg == NULL || timing == NULL) {
        return reject(why, TVO_ERR_NULL, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    }
    memset(timing, 0, sizeof(*timing));
    if (msg->protocol_version != TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION) {
        return reject_param(why, TVO_SESSION_PARAM_PROTOCOL_VERSION); /* its fields may mean something else */
    }
    if (msg->session_id < 0) {
        return reject_param(why, TVO_SESSION_PARAM_SESSION_ID); /* -1 means "none" in acks and commands */
    }
    if (!wire_time_ok(msg->utime) || !wire_time_ok(msg->epoch_utime)) {
        return reject_param(why, TVO_SESSION_PARAM_EPOCH);
    }
    /* The controller's clock reaches 2^30-1 ticks from the epoch on its first step: half of that for
     * the epoch's distance from the START, half for the plant's first sample after it. */
    const int64_t epoch_lead = msg->epoch_utime - msg->utime;
    if (epoch_lead < -TVO_SESSION_EPOCH_SPAN_US || epoch_lead > TVO_SESSION_EPOCH_SPAN_US) {
        return reject_param(why, TVO_SESSION_PARAM_EPOCH);
    }
    if (msg->clock_source != TVO_LCM_SESSION_T_CLOCK_PLANT && msg->clock_source != TVO_LCM_SESSION_T_CLOCK_NODE) {
        return reject_param(why, TVO_SESSION_PARAM_CLOCK_SOURCE);
    }
    if (msg->period_us < 1 || msg->period_us > (int64_t)TVO_MAX_TICK_SPAN) {
        return reject_param(why, TVO_SESSION_PARAM_PERIOD);
    }
    if (msg->delay_us < 0 || msg->delay_us > msg->period_us) {
        return reject_param(why, TVO_SESSION_PARAM_DELAY);
    }
    if (msg->watchdog_periods < 1) {
        return reject_param(why, TVO_SESSION_PARAM_WATCHDOG); /* its span: the core's init (TVO_PARAM_WATCHDOG) */
    }
    if (msg->robot_count < 1 || msg->robot_count > TVO_MAX_ROBOTS) {
        return reject_param(why, TVO_SESSION_PARAM_ROBOT_COUNT);
    }
    if (msg->plant_kind != TVO_LCM_SESSION_T_PLANT_UNICYCLE && msg->plant_kind != TVO_LCM_SESSION_T_PLANT_CHAIN) {
        return reject_param(why, TVO_SESSION_PARAM_PLANT_KIND);
    }
    if (msg->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN && msg->robot_count != 1) {
        return reject_param(why, TVO_SESSION_PARAM_ROBOT_COUNT); /* chain_sample_t, chain_command_t: one robot */
    }
    if (msg->telemetry_every < 0 || msg->telemetry_every > TVO_SESSION_TELEMETRY_EVERY_MAX) {
        return reject_param(why, TVO_SESSION_PARAM_TELEMETRY_EVERY);
    }
    /* 0: the fewest periods that span the default interval (period_us >= 1 here: no division by 0). */
    const int64_t default_every = (TVO_SESSION_TELEMETRY_DEFAULT_US + msg->period_us - 1) / msg->period_us;
    timing->telemetry_every = (uint32_t)(msg->telemetry_every > 0 ? (int64_t)msg->telemetry_every : default_every);
    timing->clock_source = msg->clock_source;
    timing->epoch_utime = msg->epoch_utime;
    timing->period_us = msg->period_us;
    timing->delay_us = msg->delay_us;
    timing->watchdog_periods = (uint32_t)msg->watchdog_periods;
    timing->robot_count = (uint8_t)msg->robot_count;
    timing->plant_kind = msg->plant_kind;
    return TVO_OK;
}

/* The sampled-data settings the unicycle's and the chain's configurations both carry under the same
 * names (tvo/controller.h, tvo/chain_controller.h), from the START and its checked timing: one
 * mapping for both types. */
#define SET_SAMPLED_DATA_CONFIG(cfg, msg, timing)                              \
    do {                                                                       \
        (cfg)->tick_hz = TVO_EDGE_TICK_HZ;                                     \
        (cfg)->period_ticks = (uint32_t)(timing)->period_us;                   \
        (cfg)->delay_ticks = (uint32_t)(timing)->delay_us;                     \
        (cfg)->delay_compensation = (msg)->delay_compensation ? 1u : 0u;       \
        (cfg)->zoh_aware = (msg)->zoh_aware ? 1u : 0u;                         \
        (cfg)->filter_tf_s = tvo_wire_real((msg)->filter_tf_s);                \
        (cfg)->watchdog_periods = (timing)->watchdog_periods;                  \
        /* lockstep: the plant's samples are the only clock, so refusals count */ \
        (cfg)->watchdog_counts_refusals =                                      \
            ((timing)->clock_source == TVO_LCM_SESSION_T_CLOCK_PLANT) ? 1u : 0u; \
    } while (0)

static tvo_status_t unicycle_config(const tvo_lcm_session_t *msg, const tvo_session_timing_t *timing,
                                    tvo_controller_config_t *cfg, tvo_session_reject_t *why)
{
    if (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSE) {
        cfg->velocity_source = TVO_VELOCITY_FROM_POSE;
    } else if (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION) {
        cfg->velocity_source = TVO_VELOCITY_FROM_POSITION;
    } else {
        return reject_param(why, TVO_SESSION_PARAM_VELOCITY_SOURCE);
    }
    SET_SAMPLED_DATA_CONFIG(cfg, msg, timing);
    cfg->robot_count = timing->robot_count;
    cfg->gain_kp = tvo_wire_real(msg->gain_kp);
    cfg->gain_kd = tvo_wire_real(msg->gain_kd);
    cfg->omega_max_radps = tvo_wire_real(msg->omega_max_radps);
    cfg->accel_max_mps2 = tvo_wire_real(msg->accel_max_mps2);
    cfg->speed_max_mps = tvo_wire_real(msg->speed_max_mps);
    cfg->min_speed_mps = tvo_wire_real(msg->min_speed_mps);
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        cfg->initial_speed_mps[r] = (r < timing->robot_count) ? tvo_wire_real(msg->robot[r].initial_speed_mps) : TVO_R(0.0);
    }
    return TVO_OK;
}

static tvo_status_t chain_config(const tvo_lcm_session_t *msg, const tvo_session_timing_t *timing,
                                 tvo_chain_config_t *cfg, tvo_session_reject_t *why)
{
    if (msg->chain_relative_degree < 1 || msg->chain_relative_degree > TVO_MAX_RELATIVE_DEGREE) {
        return reject_param(why, TVO_SESSION_PARAM_GAINS);
    }
    if (msg->velocity_source != TVO_LCM_SESSION_T_VELOCITY_FROM_POSE &&
        msg->velocity_source != TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION) {
        return reject_param(why, TVO_SESSION_PARAM_VELOCITY_SOURCE);
    }
    SET_SAMPLED_DATA_CONFIG(cfg, msg, timing);
    cfg->relative_degree = (uint8_t)msg->chain_relative_degree;
    cfg->filtered_derivatives = (msg->velocity_source == TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION) ? 1u : 0u;
    for (size_t i = 0; i < TVO_MAX_RELATIVE_DEGREE; ++i) {
        cfg->gain[i] = tvo_wire_real(msg->chain_gains[i]);
    }
    cfg->input_max = tvo_wire_real(msg->chain_input_max);
    return TVO_OK;
}

/* A controller's configuration, the unicycle's or the chain's (the other NULL; both NULL: TVO_ERR_NULL): the arguments, the
 * START's timing and the core's defaults first, then the plant's own settings. */
static tvo_status_t decode_controller(const tvo_lcm_session_t *msg, tvo_controller_config_t *unicycle,
                                      tvo_chain_config_t *chain, tvo_session_reject_t *why)
{
    if (msg == NULL || (unicycle == NULL && chain == NULL)) {
        return reject(why, TVO_ERR_NULL, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    }
    tvo_session_timing_t timing;
    tvo_status_t st = tvo_session_decode_timing(msg, &timing, why);
    if (st == TVO_OK) {
        st = (unicycle != NULL) ? tvo_controller_config_default(unicycle) : tvo_chain_config_default(chain);
    }
    if (st != TVO_OK) {
        return st;
    }
    return (unicycle != NULL) ? unicycle_config(msg, &timing, unicycle, why) : chain_config(msg, &timing, chain, why);
}

tvo_status_t tvo_session_decode_unicycle(const tvo_lcm_session_t *msg, tvo_controller_config_t *cfg,
                                         tvo_session_reject_t *why)
{
    return decode_controller(msg, cfg, NULL, why);
}

tvo_status_t tvo_session_decode_chain(const tvo_lcm_session_t *msg, tvo_chain_config_t *cfg,
                                      tvo_session_reject_t *why)
{
    return decode_controller(msg, NULL, cfg, why);
}

tvo_status_t tvo_session_decode_path(const tvo_lcm_path_t *path, tvo_target_t *target)
{
    if (path == NULL || target == NULL) {
        return TVO_ERR_NULL;
    }
    switch (path->kind) {
    case TVO_LCM_PATH_T_KIND_POLYNOMIAL: {
        tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
        for (size_t axis = 0; axis < 2; ++axis) {
            for (size_t j = 0; j < (size_t)TVO_LCM_PATH_T_MAX_COEFFS; ++j) {
                if (j <= TVO_POLY_MAX_DEGREE) {
                    coeff[axis][j] = tvo_wire_real(path->coeff[axis][j]);
                } else if (path->coeff[axis][j] != 0.0) {
                    return TVO_ERR_CAPACITY; /* a degree this build's limits cannot evaluate */
                }
            }
        }
        /* C11 does not convert T (*)[n] to const T (*)[n] implicitly: the cast only adds const. */
        return tvo_target_init_polynomial(target, (const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])coeff);
    }
    case TVO_LCM_PATH_T_KIND_CIRCLE:
    case TVO_LCM_PATH_T_KIND_ELLIPSE: {
        /* A circle is an ellipse with equal semi-axes (radius in semi_axis_m[0]) and no rotation. */
        const int circle = path->kind == TVO_LCM_PATH_T_KIND_CIRCLE;
        tvo_target_ellipse_t ellipse;
        for (size_t axis = 0; axis < 2; ++axis) {
            ellipse.center_m[axis] = tvo_wire_real(path->center_m[axis]);
            ellipse.semi_axis_m[axis] = tvo_wire_real(path->semi_axis_m[circle ? 0 : axis]);
        }
        ellipse.omega_radps = tvo_wire_real(path->omega_radps);
        ellipse.phase_rad = tvo_wire_real(path->phase_rad);
        ellipse.rotation_rad = circle ? TVO_R(0.0) : tvo_wire_real(path->rotation_rad);
        /* omega multiplies hours of time: its phase rate keeps the wire's double precision. */
        ellipse.rate_turns_q64 = tvo_target_turns_q64(path->omega_radps);
        tvo_status_t st = tvo_target_init_ellipse(target, &ellipse);
        if (st == TVO_OK && !(fabs(path->omega_radps) <= (double)TVO_TARGET_MAX_OMEGA_RADPS)) {
            st = TVO_ERR_PARAM; /* the bound on the wire's value, not on its rounding to tvo_real_t */
        }
        if (st == TVO_OK && circle) {
            target->kind = TVO_TARGET_CIRCLE;
        }
        return st;
    }
    case TVO_LCM_PATH_T_KIND_STREAMED:
        return tvo_target_init_streamed(target);
    default:
        return TVO_ERR_PARAM;
    }
}

/* A part's count from the wire: 0 .. both the message's and the core's capacity, narrowed once checked. */
static tvo_status_t decode_count(int32_t count, int32_t wire_max, int32_t core_max, int32_t part, uint8_t *decoded,
                                 tvo_session_reject_t *why)
{
    if (count < 0 || count > wire_max || count > core_max) {
        return reject_part(why, TVO_ERR_CAPACITY, part, -1);
    }
    *decoded = (uint8_t)count;
    return TVO_OK;
}

/* A robot index from the wire: 0 .. robot_count - 1 (checked before narrowing to uint8_t). */
static int robot_ok(int32_t robot, uint8_t robot_count)
{
    return robot >= 0 && robot < (int32_t)robot_count;
}

/* The two robots of a pairwise entry (a distance bound, an offset), narrowed once both are checked. */
static int decode_robot_pair(int32_t robot_a, int32_t robot_b, uint8_t robot_count, uint8_t *a, uint8_t *b)
{
    if (!robot_ok(robot_a, robot_count) || !robot_ok(robot_b, robot_count)) {
        return 0;
    }
    *a = (uint8_t)robot_a;
    *b = (uint8_t)robot_b;
    return 1;
}

static tvo_status_t decode_robots(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc, tvo_session_reject_t *why)
{
    if (msg->robot_count < 1 || msg->robot_count > TVO_MAX_ROBOTS) {
        return reject_param(why, TVO_SESSION_PARAM_ROBOT_COUNT);
    }
    desc->robot_count = (uint8_t)msg->robot_count;
    for (uint8_t r = 0; r < desc->robot_count; ++r) {
        desc->tracking_weight[r][0] = tvo_wire_real(msg->robot[r].tracking_weight[0]);
        desc->tracking_weight[r][1] = tvo_wire_real(msg->robot[r].tracking_weight[1]);
        const tvo_status_t st = tvo_session_decode_path(&msg->robot[r].target, &desc->target[r]);
        if (st != TVO_OK) {
            return reject_part(why, st, TVO_LCM_SESSION_ACK_T_PART_ROBOTS, (int32_t)r);
        }
    }
    return TVO_OK;
}

static tvo_status_t decode_barrier(const tvo_lcm_barrier_t *wire, tvo_barrier_config_t *cfg,
                                   tvo_session_reject_t *why)
{
    if (wire->relaxation_degree < 0 || wire->relaxation_degree > (int32_t)UINT8_MAX) {
        return reject_part(why, TVO_ERR_PARAM, TVO_LCM_SESSION_ACK_T_PART_BARRIER, -1);
    }
    cfg->c0 = tvo_wire_real(wire->c0);
    cfg->alpha_c_per_s = tvo_wire_real(wire->alpha_c_per_s);
    cfg->c_max = tvo_wire_real(wire->c_max);
    cfg->delta0 = tvo_wire_real(wire->delta0);
    cfg->alpha_s_per_s = tvo_wire_real(wire->alpha_s_per_s);
    cfg->slack_margin = tvo_wire_real(wire->slack_margin);
    cfg->relaxation_degree = (uint8_t)wire->relaxation_degree;
    return TVO_OK; /* ranges: tvo_barrier_init, through tvo_problem_init */
}

static tvo_status_t decode_distances(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                     tvo_session_reject_t *why)
{
    const int32_t part = TVO_LCM_SESSION_ACK_T_PART_DISTANCE;
    const tvo_status_t st = decode_count(msg->distance_count, TVO_LCM_SESSION_T_MAX_DISTANCE_BOUNDS,
                                         TVO_MAX_DISTANCE_BOUNDS, part, &desc->distance_count, why);
    for (uint8_t i = 0; st == TVO_OK && i < desc->distance_count; ++i) {
        const tvo_lcm_distance_bound_t *w = &msg->distance[i];
        tvo_distance_bound_desc_t *d = &desc->distance[i];
        if (!decode_robot_pair(w->robot_a, w->robot_b, desc->robot_count, &d->robot_a, &d->robot_b)) {
            return reject_part(why, TVO_ERR_PARAM, part, (int32_t)i);
        }
        d->min_m = tvo_wire_real(w->min_m);
        d->min_rate_mps = tvo_wire_real(w->min_rate_mps);
        d->max_m = tvo_wire_real(w->max_m);
        d->max_rate_mps = tvo_wire_real(w->max_rate_mps);
    }
    return st;
}

static tvo_status_t decode_halfspaces(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                      tvo_session_reject_t *why)
{
    const int32_t part = TVO_LCM_SESSION_ACK_T_PART_HALFSPACE;
    const tvo_status_t st = decode_count(msg->halfspace_count, TVO_LCM_SESSION_T_MAX_HALFSPACES, TVO_MAX_HALFSPACES,
                                         part, &desc->halfspace_count, why);
    for (uint8_t i = 0; st == TVO_OK && i < desc->halfspace_count; ++i) {
        const tvo_lcm_halfspace_t *w = &msg->halfspace[i];
        if (!robot_ok(w->robot, desc->robot_count)) {
            return reject_part(why, TVO_ERR_PARAM, part, (int32_t)i);
        }
        tvo_halfspace_desc_t *h = &desc->halfspace[i];
        h->robot = (uint8_t)w->robot;
        for (size_t axis = 0; axis < 2; ++axis) {
            h->normal[axis] = tvo_wire_real(w->normal[axis]);
            h->normal_rate[axis] = tvo_wire_real(w->normal_rate[axis]);
        }
        h->bound_m = tvo_wire_real(w->bound_m);
        h->bound_rate_mps = tvo_wire_real(w->bound_rate_mps);
    }
    return st;
}

static tvo_status_t decode_obstacles(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                     tvo_session_reject_t *why)
{
    const tvo_status_t st = decode_count(msg->obstacle_count, TVO_LCM_SESSION_T_MAX_OBSTACLES, TVO_MAX_OBSTACLES,
                                         TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, &desc->obstacle_count, why);
    if (st != TVO_OK) {
        return st;
    }
    desc->robot_radius_m = tvo_wire_real(msg->robot_radius_m);
    for (uint8_t i = 0; i < desc->obstacle_count; ++i) {
        desc->obstacle[i].center_m[0] = tvo_wire_real(msg->obstacle[i].center_m[0]);
        desc->obstacle[i].center_m[1] = tvo_wire_real(msg->obstacle[i].center_m[1]);
        desc->obstacle[i].radius_m = tvo_wire_real(msg->obstacle[i].radius_m);
    }
    return TVO_OK; /* radii, disjointness: tvo_free_space_term_init */
}

static tvo_status_t decode_offsets(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc, tvo_session_reject_t *why)
{
    const int32_t part = TVO_LCM_SESSION_ACK_T_PART_OFFSETS;
    const tvo_status_t st = decode_count(msg->offset_count, TVO_LCM_SESSION_T_MAX_OFFSETS, TVO_MAX_OFFSET_EQUALITIES,
                                         part, &desc->offset_count, why);
    for (uint8_t i = 0; st == TVO_OK && i < desc->offset_count; ++i) {
        const tvo_lcm_offset_t *w = &msg->offset[i];
        tvo_offset_desc_t *o = &desc->offset[i];
        /* d(t) has no stream of its own on the wire: only on-board time functions. */
        if (!decode_robot_pair(w->robot_a, w->robot_b, desc->robot_count, &o->robot_a, &o->robot_b) ||
            w->offset.kind == TVO_LCM_PATH_T_KIND_STREAMED) {
            return reject_part(why, TVO_ERR_PARAM, part, (int32_t)i);
        }
        const tvo_status_t path_st = tvo_session_decode_path(&w->offset, &o->offset);
        if (path_st != TVO_OK) {
            return reject_part(why, path_st, part, (int32_t)i);
        }
    }
    return st;
}

tvo_status_t tvo_session_decode_problem(const tvo_lcm_session_t *msg, tvo_problem_desc_t *desc,
                                        tvo_session_reject_t *why)
{
    (void)reject(why, TVO_OK, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    if (msg == NULL || desc == NULL) {
        return reject(why, TVO_ERR_NULL, TVO_SESSION_PARAM_NONE, TVO_LCM_SESSION_ACK_T_PART_NONE, -1);
    }
    tvo_status_t st = tvo_problem_desc_default(desc);
    if (st == TVO_OK) {
        st = decode_robots(msg, desc, why);
    }
    if (st == TVO_OK) {
        st = decode_barrier(&msg->barrier, &desc->barrier, why);
    }
    if (st == TVO_OK) {
        st = decode_distances(msg, desc, why);
    }
    if (st == TVO_OK) {
        st = decode_halfspaces(msg, desc, why);
    }
    if (st == TVO_OK) {
        st = decode_obstacles(msg, desc, why);
    }
    if (st == TVO_OK) {
        st = decode_offsets(msg, desc, why);
    }
    return st;
}

int32_t tvo_session_part_from_problem(uint8_t problem_part)
{
    static const int32_t parts[] = {
        TVO_LCM_SESSION_ACK_T_PART_ROBOTS,    TVO_LCM_SESSION_ACK_T_PART_BARRIER,
        TVO_LCM_SESSION_ACK_T_PART_DISTANCE,  TVO_LCM_SESSION_ACK_T_PART_HALFSPACE,
        TVO_LCM_SESSION_ACK_T_PART_OBSTACLES, TVO_LCM_SESSION_ACK_T_PART_OFFSETS};
    return problem_part < sizeof(parts) / sizeof(parts[0]) ? parts[problem_part] : TVO_LCM_SESSION_ACK_T_PART_NONE;
}

uint64_t tvo_session_content_hash(const uint8_t *data, uint32_t length)
{
    /* Encoded session_t: 8-byte fingerprint, then utime (8 bytes), then the content. 64-bit FNV-1a:
     * two different STARTs of one id colliding is not a practical concern. */
    const uint32_t skip = 16u;
    uint64_t hash = 14695981039346656037u;
    for (uint32_t i = skip; data != NULL && i < length; ++i) {
        hash = (hash ^ data[i]) * 1099511628211u;
    }
    return hash;
}

void tvo_session_ack(const tvo_lcm_session_t *msg, const tvo_session_reject_t *why, int32_t running_session_id,
                     int64_t boot_id, int8_t own_robot, tvo_lcm_session_ack_t *ack)
{
    if (ack == NULL) {
        return;
    }
    memset(ack, 0, sizeof(*ack));
    if (msg != NULL) {
        ack->utime = msg->utime;
        ack->session_id = msg->session_id;
        ack->action = msg->action;
    }
    const tvo_step_why_t answer = {(why != NULL) ? why->node : TVO_NODE_OK, (why != NULL) ? why->status : TVO_OK,
                                   TVO_REASON_NONE};
    ack->boot_id = boot_id;
    ack->own_robot = own_robot;
    ack->status = (int8_t)tvo_step_wire_status(&answer);
    ack->bad_param = (why != NULL) ? (int32_t)why->param : 0;
    ack->bad_part = (why != NULL) ? why->part : TVO_LCM_SESSION_ACK_T_PART_NONE;
    ack->bad_index = (why != NULL) ? why->index : -1;
    ack->running_session_id = running_session_id;
}
