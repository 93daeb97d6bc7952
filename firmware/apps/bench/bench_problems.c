/* The bench's closed-loop problems; see bench_problems.h. */
#include "bench_problems.h"
#include "internal/objective.h"
#include "internal/unicycle.h"

#include <math.h>
#include <string.h>

#define BENCH_PI 3.14159265358979f

static void polynomial_target(tvo_target_t *target, float x0, float vx, float y0, float vy)
{
    tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
    memset(coeff, 0, sizeof(coeff));
    coeff[0][0] = x0;
    coeff[0][1] = vx;
    coeff[1][0] = y0;
    coeff[1][1] = vy;
    (void)tvo_target_init_polynomial(target, (const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])coeff);
}

const char *bench_problem_name(bench_unicycle_problem_t which)
{
    static const char *const names[BENCH_UNICYCLE_PROBLEM_COUNT] = {
        "unicycle",   "obstacles4", "formation2",  "formation4",  "formation8",
        "obstacles0", "obstacles8", "obstacles16", "formation16", "formation32"};
    return ((unsigned)which < (unsigned)BENCH_UNICYCLE_PROBLEM_COUNT) ? names[which] : NULL;
}

static void unicycle_desc(tvo_problem_desc_t *desc, tvo_pose_t *start)
{
    const tvo_target_ellipse_t ellipse = {{TVO_R(0.0), TVO_R(0.0)}, {TVO_R(3.0), TVO_R(1.5)},
                                          2.0f * BENCH_PI / 10.0f, TVO_R(0.0), TVO_R(0.0), 0u};
    (void)tvo_target_init_ellipse(&desc->target[0], &ellipse);
    const tvo_pose_t pose = {{TVO_R(-1.0), TVO_R(-2.0)}, TVO_R(0.0)};
    start[0] = pose;
}

static void obstacles4_desc(tvo_problem_desc_t *desc, tvo_pose_t *start)
{
    polynomial_target(&desc->target[0], -5.0f, 0.8f, -5.0f, 0.6f);
    desc->obstacle_count = 4u;
    desc->robot_radius_m = TVO_R(0.2);
    const float centers[4][2] = {{-3.0f, -3.5f}, {-1.0f, -1.0f}, {1.5f, -2.5f}, {2.0f, 1.0f}};
    const float radii[4] = {0.6f, 1.0f, 0.8f, 0.7f};
    for (uint8_t i = 0; i < 4u; ++i) {
        desc->obstacle[i].center_m[0] = centers[i][0];
        desc->obstacle[i].center_m[1] = centers[i][1];
        desc->obstacle[i].radius_m = radii[i];
    }
    const tvo_pose_t pose = {{TVO_R(-6.0), TVO_R(-4.2)}, TVO_R(-10.0)};
    start[0] = pose;
}

/* N robots on a circle of radius 2 m turning at 0.2 rad/s, each tracking its own point; distance bounds
 * between neighbours in a ring (one bound for two); each starts 0.3 m off its point, at rest. */
static tvo_status_t ring_formation_desc(tvo_problem_desc_t *desc, tvo_pose_t *start, uint8_t robots)
{
    const uint8_t bounds = (robots == 2u) ? 1u : robots;
    if (robots > TVO_MAX_ROBOTS || bounds > TVO_MAX_DISTANCE_BOUNDS) {
        return TVO_ERR_DIMENSION; /* the build's limits cannot hold it */
    }
    const float radius_m = 2.0f;
    const float spacing_m = 2.0f * radius_m * sinf(BENCH_PI / (float)robots);
    const tvo_real_t center[2] = {TVO_R(0.0), TVO_R(0.0)};
    for (uint8_t r = 0; r < robots; ++r) {
        const float phase = 2.0f * BENCH_PI * (float)r / (float)robots;
        (void)tvo_target_init_circle(&desc->target[r], center, radius_m, TVO_R(0.2), phase);
        start[r].position_m[0] = (radius_m + 0.3f) * cosf(phase);
        start[r].position_m[1] = (radius_m + 0.3f) * sinf(phase);
        start[r].heading_rad = phase + 0.5f * BENCH_PI;
    }
    desc->distance_count = bounds;
    for (uint8_t b = 0; b < bounds; ++b) {
        desc->distance[b].robot_a = b;
        desc->distance[b].robot_b = (uint8_t)((b + 1u) % robots);
        desc->distance[b].min_m = 0.5f * spacing_m;
        desc->distance[b].max_m = 1.5f * spacing_m;
    }
    return TVO_OK;
}

/* obstacles4's robot and path with N disks of radius 0.35 m, alternately 1 m left and right of it,
 * 0.9 m apart along it from 1.5 m ahead of the target's start (the robot starts 1 m off the path). */
static tvo_status_t obstacles_row_desc(tvo_problem_desc_t *desc, tvo_pose_t *start, uint8_t obstacles)
{
    if (obstacles > TVO_MAX_OBSTACLES) {
        return TVO_ERR_DIMENSION; /* the build's limits cannot hold it */
    }
    polynomial_target(&desc->target[0], -5.0f, 0.8f, -5.0f, 0.6f);
    desc->obstacle_count = obstacles;
    desc->robot_radius_m = TVO_R(0.2);
    for (uint8_t i = 0; i < obstacles; ++i) {
        const float along_m = 1.5f + 0.9f * (float)i;
        const float side_m = (i % 2u == 0u) ? 1.0f : -1.0f;
        desc->obstacle[i].center_m[0] = -5.0f + 0.8f * along_m - 0.6f * side_m;
        desc->obstacle[i].center_m[1] = -5.0f + 0.6f * along_m + 0.8f * side_m;
        desc->obstacle[i].radius_m = TVO_R(0.35);
    }
    const tvo_pose_t pose = {{TVO_R(-5.6), TVO_R(-4.2)}, TVO_R(0.6)};
    start[0] = pose;
    return TVO_OK;
}

static tvo_status_t formation2_desc(tvo_problem_desc_t *desc, tvo_pose_t *start)
{
#if TVO_MAX_ROBOTS >= 2
    polynomial_target(&desc->target[0], -5.0f, 1.0f, -3.0f, 0.0f);
    polynomial_target(&desc->target[1], -2.0f, 0.2f, -3.0f, 0.0f);
    desc->distance_count = 1u;
    desc->distance[0].robot_b = 1u;
    desc->distance[0].min_m = TVO_R(1.0);
    desc->distance[0].max_m = TVO_R(3.0);
    const tvo_pose_t poses[2] = {{{TVO_R(-4.9), TVO_R(-4.2)}, TVO_R(0.5)}, {{TVO_R(-2.1), TVO_R(-4.3)}, TVO_R(-0.5)}};
    start[0] = poses[0];
    start[1] = poses[1];
    return TVO_OK;
#else
    (void)desc;
    (void)start;
    return TVO_ERR_DIMENSION; /* built for one robot */
#endif
}

tvo_status_t bench_problem_desc(bench_unicycle_problem_t which, tvo_problem_desc_t *desc, tvo_pose_t *start,
                                uint8_t *robots)
{
    if (desc == NULL || start == NULL || robots == NULL) {
        return TVO_ERR_NULL;
    }
    tvo_status_t st = tvo_problem_desc_default(desc);
    if (st != TVO_OK) {
        return st;
    }
    *robots = 1u;
    switch (which) {
    case BENCH_UNICYCLE:
        unicycle_desc(desc, start);
        break;
    case BENCH_OBSTACLES4:
        obstacles4_desc(desc, start);
        break;
    case BENCH_FORMATION2:
        *robots = 2u;
        st = formation2_desc(desc, start);
        break;
    case BENCH_FORMATION4:
    case BENCH_FORMATION8:
    case BENCH_FORMATION16:
    case BENCH_FORMATION32:
        *robots = which == BENCH_FORMATION4 ? 4u : which == BENCH_FORMATION8 ? 8u : which == BENCH_FORMATION16 ? 16u : 32u;
        st = ring_formation_desc(desc, start, *robots);
        break;
    case BENCH_OBSTACLES0:
        st = obstacles_row_desc(desc, start, 0u);
        break;
    case BENCH_OBSTACLES8:
        st = obstacles_row_desc(desc, start, 8u);
        break;
    case BENCH_OBSTACLES16:
        st = obstacles_row_desc(desc, start, 16u);
        break;
    case BENCH_UNICYCLE_PROBLEM_COUNT:
    default:
        st = TVO_ERR_PARAM;
        break;
    }
    desc->robot_count = *robots;
    return st;
}

tvo_status_t bench_loop_init(bench_loop_t *loop, bench_unicycle_problem_t which)
{
    if (loop == NULL) {
        return TVO_ERR_NULL;
    }
    memset(loop, 0, sizeof(*loop));
    tvo_problem_desc_t desc;
    tvo_problem_culprit_t part;
    tvo_param_t bad = TVO_PARAM_NONE;
    tvo_status_t st = bench_problem_desc(which, &desc, loop->pose, &loop->robots);
    if (st == TVO_OK) {
        st = tvo_problem_init(&loop->problem, &desc, 2u, &part);
    }
    if (st == TVO_OK) {
        st = tvo_controller_config_default(&loop->cfg);
    }
    if (st == TVO_OK) {
        loop->cfg.robot_count = loop->robots;
        st = tvo_controller_init(&loop->controller, &loop->cfg, &loop->problem.objective, 0u, &bad);
    }
    loop->half_period_s = TVO_R(0.5) * tvo_ticks_to_seconds(loop->cfg.period_ticks, loop->cfg.tick_hz);
    return st;
}

static void plant_half_period(bench_loop_t *loop)
{
    for (uint8_t r = 0; r < loop->robots && r < TVO_MAX_ROBOTS; ++r) {
        tvo_unicycle_predict(&loop->pose[r], loop->cmd.speed_mps[r], loop->cmd.turn_rate_radps[r],
                                   loop->half_period_s, &loop->pose[r]);
    }
}

/* Period n's measurement from the plant's pose, and the slack chosen from it in period 0. */
static tvo_status_t sample(bench_loop_t *loop)
{
    const uint32_t n = loop->period;
    const uint32_t period_ticks = loop->cfg.period_ticks;
    memset(&loop->meas, 0, sizeof(loop->meas));
    for (uint8_t r = 0; r < loop->robots && r < TVO_MAX_ROBOTS; ++r) {
        loop->meas.position_m[r][0] = loop->pose[r].position_m[0];
        loop->meas.position_m[r][1] = loop->pose[r].position_m[1];
        loop->meas.heading_rad[r] = loop->pose[r].heading_rad;
    }
    loop->meas.heading_valid = 1u;
    loop->meas.stamp_tick = n * period_ticks + period_ticks - loop->cfg.delay_ticks;
    tvo_status_t st = TVO_OK;
    if (n == 0u) {
        tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
        for (uint8_t r = 0; r < loop->robots && r < TVO_MAX_ROBOTS; ++r) {
            y[2u * r] = loop->pose[r].position_m[0];
            y[2u * r + 1u] = loop->pose[r].position_m[1];
        }
        st = tvo_problem_choose_slack(&loop->problem, y, TVO_R(0.0));
    }
    return st;
}

static void finish_period(bench_loop_t *loop)
{
    loop->apply_tick = (loop->period + 1u) * loop->cfg.period_ticks;
    loop->period += 1u;
}

tvo_status_t bench_loop_advance(bench_loop_t *loop)
{
    if (loop == NULL) {
        return TVO_ERR_NULL;
    }
    plant_half_period(loop);
    const tvo_status_t st = sample(loop);
    plant_half_period(loop);
    finish_period(loop);
    return st;
}

tvo_status_t bench_loop_replay(bench_loop_t *loop, const tvo_pose_t *measured)
{
    if (loop == NULL || measured == NULL) {
        return TVO_ERR_NULL;
    }
    for (uint8_t r = 0; r < loop->robots && r < TVO_MAX_ROBOTS; ++r) {
        loop->pose[r] = measured[r];
    }
    const tvo_status_t st = sample(loop);
    finish_period(loop);
    return st;
}

uint32_t bench_digest_bytes(uint32_t digest, const void *bytes, size_t size)
{
    const unsigned char *p = (const unsigned char *)bytes;
    for (size_t i = 0; i < size; ++i) {
        digest = (digest ^ p[i]) * 16777619u;
    }
    return digest;
}

uint32_t bench_digest_command(uint32_t digest, const tvo_command_t *cmd)
{
    digest = bench_digest_bytes(digest, &cmd->speed_mps, sizeof(cmd->speed_mps));
    digest = bench_digest_bytes(digest, &cmd->turn_rate_radps, sizeof(cmd->turn_rate_radps));
    return bench_digest_bytes(digest, &cmd->flags, sizeof(cmd->flags));
}
