/*
 * The C side of the `tvo` module's bit-identity test (test_bit_identical.py): the closed loop of
 * tvo.UnicycleController.run, written in C against the core (the firmware's host build of the
 * precision) and the module's plant (src/plant.c), printing every period's result as raw bits.
 *
 * Usage: closed_loop_ref CASE STEPS KP KD ZOH
 *   CASE 0: one robot, ellipse target, an obstacle in the way (barrier), start (-1, -2, 0)
 *   CASE 1: two robots, polynomial targets, a minimum distance and a half-space, measured speeds
 * Output: per period "k outcome reason flags" then per robot the speed and turn rate's bits (hex) and the
 * plant's pose bits at the apply instant.
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "plant.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#if TVO_USE_DOUBLE
typedef uint64_t real_bits_t;
#define REAL_BITS_FMT "%016" PRIx64
#else
typedef uint32_t real_bits_t;
#define REAL_BITS_FMT "%08" PRIx32
#endif

static real_bits_t real_bits(tvo_real_t x)
{
    real_bits_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

static uint64_t double_bits(double x)
{
    uint64_t b;
    memcpy(&b, &x, sizeof b);
    return b;
}

static int fail(const char *what, tvo_status_t st)
{
    fprintf(stderr, "closed_loop_ref: %s: %s\n", what, tvo_status_str(st));
    return 1;
}

/* The problems of test_bit_identical.py, value for value (doubles rounded to tvo_real_t as cffi does). */
static tvo_status_t make_problem(int which, tvo_problem_t *problem, double start[][3], uint8_t *robots)
{
    tvo_problem_desc_t desc;
    tvo_status_t st = tvo_problem_desc_default(&desc);
    if (st != TVO_OK) {
        return st;
    }
    if (which == 0) {
        *robots = 1u;
        desc.robot_count = 1u;
        tvo_target_ellipse_t e;
        memset(&e, 0, sizeof e);
        e.center_m[0] = (tvo_real_t)0.0;
        e.center_m[1] = (tvo_real_t)0.0;
        e.semi_axis_m[0] = (tvo_real_t)3.0;
        e.semi_axis_m[1] = (tvo_real_t)1.5;
        e.omega_radps = (tvo_real_t)0.6283185307179586;
        e.phase_rad = (tvo_real_t)0.0;
        e.rotation_rad = (tvo_real_t)0.0;
        e.rate_turns_q64 = tvo_target_turns_q64(0.6283185307179586);
        st = tvo_target_init_ellipse(&desc.target[0], &e);
        desc.obstacle_count = 1u;
        desc.robot_radius_m = (tvo_real_t)0.2;
        desc.obstacle[0].center_m[0] = (tvo_real_t)2.0;
        desc.obstacle[0].center_m[1] = (tvo_real_t)-1.0;
        desc.obstacle[0].radius_m = (tvo_real_t)0.5;
        start[0][0] = -1.0;
        start[0][1] = -2.0;
        start[0][2] = 0.0;
    } else {
        *robots = 2u;
        desc.robot_count = 2u;
        const double c[2][2][3] = {{{-2.0, 0.5, 0.01}, {0.0, 0.2, -0.005}}, {{2.0, -0.5, 0.0}, {0.5, 0.1, 0.002}}};
        for (size_t r = 0; r < 2u && st == TVO_OK; ++r) {
            tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1];
            memset(coeff, 0, sizeof coeff);
            for (size_t axis = 0; axis < 2u; ++axis) {
                for (size_t j = 0; j < 3u; ++j) {
                    coeff[axis][j] = (tvo_real_t)c[r][axis][j];
                }
            }
            st = tvo_target_init_polynomial(&desc.target[r], (const tvo_real_t(*)[TVO_POLY_MAX_DEGREE + 1])coeff);
        }
        desc.tracking_weight[1][0] = (tvo_real_t)2.0;
        desc.tracking_weight[1][1] = (tvo_real_t)0.5;
        desc.distance_count = 1u;
        desc.distance[0].robot_a = 0u;
        desc.distance[0].robot_b = 1u;
        desc.distance[0].min_m = (tvo_real_t)0.8;
        desc.distance[0].min_rate_mps = (tvo_real_t)0.0;
        desc.distance[0].max_m = (tvo_real_t)0.0;
        desc.distance[0].max_rate_mps = (tvo_real_t)0.0;
        desc.halfspace_count = 1u;
        desc.halfspace[0].robot = 1u;
        desc.halfspace[0].normal[0] = (tvo_real_t)0.0;
        desc.halfspace[0].normal[1] = (tvo_real_t)1.0;
        desc.halfspace[0].normal_rate[0] = (tvo_real_t)0.0;
        desc.halfspace[0].normal_rate[1] = (tvo_real_t)0.0;
        desc.halfspace[0].bound_m = (tvo_real_t)1.5;
        desc.halfspace[0].bound_rate_mps = (tvo_real_t)0.0;
        desc.barrier.c0 = (tvo_real_t)2.0;
        const double s[2][3] = {{-2.5, -0.5, 0.3}, {2.2, 0.0, 2.8}};
        memcpy(start, s, sizeof s);
    }
    if (st != TVO_OK) {
        return st;
    }
    tvo_problem_culprit_t part;
    return tvo_problem_init(problem, &desc, 2u, &part);
}

int main(int argc, char **argv)
{
    if (argc != 6) {
        fprintf(stderr, "usage: closed_loop_ref CASE STEPS KP KD ZOH\n");
        return 2;
    }
    const int which = atoi(argv[1]);
    const long steps = atol(argv[2]);
    static tvo_problem_t problem;
    double pose[TVO_MAX_ROBOTS][3];
    uint8_t robots = 0u;
    tvo_status_t st = make_problem(which, &problem, pose, &robots);
    if (st != TVO_OK) {
        return fail("problem", st);
    }
    tvo_controller_config_t cfg;
    (void)tvo_controller_config_default(&cfg);
    cfg.robot_count = robots;
    cfg.tick_hz = 1000000u;
    cfg.period_ticks = 10000u;
    cfg.delay_ticks = 5000u;
    cfg.gain_kp = (tvo_real_t)strtod(argv[3], NULL);
    cfg.gain_kd = (tvo_real_t)strtod(argv[4], NULL);
    cfg.zoh_aware = (uint8_t)atoi(argv[5]);
    static tvo_controller_t ctl;
    tvo_param_t bad = TVO_PARAM_NONE;
    st = tvo_controller_init(&ctl, &cfg, &problem.objective, 0u, &bad);
    if (st != TVO_OK) {
        return fail(tvo_param_str(bad), st);
    }
    const int measure_speed = which == 1;
    double held_v[TVO_MAX_ROBOTS] = {0.0};
    double held_w[TVO_MAX_ROBOTS] = {0.0};
    int slack_chosen = 0;
    for (long k = 0; k < steps; ++k) {
        const uint32_t apply = (uint32_t)(k + 1) * cfg.period_ticks;
        for (uint8_t r = 0; r < robots; ++r) {
            tvo_py_unicycle_arc(pose[r], held_v[r], held_w[r], cfg.period_ticks - cfg.delay_ticks, cfg.tick_hz);
        }
        tvo_measurement_t m;
        memset(&m, 0, sizeof m);
        m.stamp_tick = apply - cfg.delay_ticks;
        for (uint8_t r = 0; r < robots; ++r) {
            m.position_m[r][0] = (tvo_real_t)pose[r][0];
            m.position_m[r][1] = (tvo_real_t)pose[r][1];
            m.heading_rad[r] = (tvo_real_t)pose[r][2];
            m.speed_mps[r] = (tvo_real_t)held_v[r];
        }
        m.heading_valid = 1u;
        m.speed_valid = (uint8_t)measure_speed;
        for (uint8_t r = 0; r < robots; ++r) {
            tvo_py_unicycle_arc(pose[r], held_v[r], held_w[r], cfg.delay_ticks, cfg.tick_hz);
        }
        if (!slack_chosen) {
            tvo_real_t y[TVO_MAX_OUTPUT_DIM] = {0};
            for (uint8_t r = 0; r < robots; ++r) {
                y[2 * r] = m.position_m[r][0];
                y[2 * r + 1] = m.position_m[r][1];
            }
            (void)tvo_problem_choose_slack(&problem, y, (tvo_real_t)0.0);
            slack_chosen = 1;
        }
        tvo_command_t cmd;
        st = tvo_controller_step(&ctl, &m, apply, &cmd);
        if (st != TVO_OK) {
            return fail("step", st); /* a call error: the module raises there */
        }
        printf("%ld %d %d %" PRIu32, k, (int)cmd.outcome, (int)cmd.reason, cmd.flags);
        for (uint8_t r = 0; r < robots; ++r) {
            held_v[r] = (double)cmd.speed_mps[r];
            held_w[r] = (double)cmd.turn_rate_radps[r];
            printf(" " REAL_BITS_FMT " " REAL_BITS_FMT " %016" PRIx64 " %016" PRIx64 " %016" PRIx64, real_bits(cmd.speed_mps[r]),
                   real_bits(cmd.turn_rate_radps[r]), double_bits(pose[r][0]), double_bits(pose[r][1]),
                   double_bits(pose[r][2]));
        }
        printf("\n");
    }
    return 0;
}
