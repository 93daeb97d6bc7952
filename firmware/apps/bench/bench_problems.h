/*
 * The bench's closed-loop problems, shared by bench.c (the step on a board or under callgrind) and
 * host/bench (the step against Ipopt on the same loop):
 *
 *   unicycle    one unicycle tracking an ellipse (the demo's problem)
 *   obstacles4  one disk unicycle among four disk obstacles (relaxed barrier, local free space)
 *   formation2  two unicycles with 1 <= |y1 - y2| <= 3 (4x4 Hessian, nonconvex bound)
 * and the scaling families (tools/bench's scaling table):
 *   formationN  N = 4, 8, 16, 32 unicycles on a turning circle, a ring of distance bounds between
 *               neighbours (half to one and a half times their spacing); with unicycle (N = 1) and formation2
 *   obstaclesN  N = 0, 8, 16 disk obstacles beside obstacles4's path; with obstacles4
 * A problem the build's limits cannot hold is TVO_ERR_DIMENSION (formation8 needs 8 robots, formation32 a
 * swarm's limits).
 *
 * A loop runs the unicycle controller against an exact-arc plant in lockstep: bench_loop_advance
 * moves the plant to period n's sampling instant and then to its apply instant, filling meas and
 * apply_tick; the caller then steps the controller (so a measurement brackets only the step).
 * BENCH_STEPS (steps per problem, CMake's TVO_BENCH_STEPS) comes with the library.
 */
#ifndef TVO_BENCH_PROBLEMS_H
#define TVO_BENCH_PROBLEMS_H

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    BENCH_UNICYCLE = 0,
    BENCH_OBSTACLES4,
    BENCH_FORMATION2,
    BENCH_FORMATION4,
    BENCH_FORMATION8,
    BENCH_OBSTACLES0,
    BENCH_OBSTACLES8,
    BENCH_OBSTACLES16,
    BENCH_FORMATION16,
    BENCH_FORMATION32,
    BENCH_UNICYCLE_PROBLEM_COUNT
} bench_unicycle_problem_t;

typedef struct {
    tvo_problem_t problem;
    union { /* one at a time (chain_k3 runs after the unicycle problems): the bench fits 16 KiB of RAM */
        tvo_controller_t controller;
        tvo_chain_controller_t chain;
    };
    tvo_controller_config_t cfg;
    tvo_pose_t pose[TVO_MAX_ROBOTS];      /* the plant */
    tvo_command_t cmd;                    /* the controller's output, applied by the plant */
    tvo_measurement_t meas;               /* period n's measurement (bench_loop_advance) */
    uint32_t apply_tick;                  /* period n's apply instant */
    uint32_t period;                      /* n: periods advanced so far */
    tvo_real_t half_period_s;
    uint8_t robots;
} bench_loop_t;

/** The problem's name ("unicycle", ...), or NULL for an unknown one. */
const char *bench_problem_name(bench_unicycle_problem_t which);

/** Fills desc and the robots' start poses (start: TVO_MAX_ROBOTS entries); *robots the count. */
tvo_status_t bench_problem_desc(bench_unicycle_problem_t which, tvo_problem_desc_t *desc, tvo_pose_t *start,
                                uint8_t *robots);

/**
 * Builds the problem and a controller with default settings, the plant at its start.
 * TVO_ERR_DIMENSION when the build's limits cannot hold the problem (formation2 on one robot).
 */
tvo_status_t bench_loop_init(bench_loop_t *loop, bench_unicycle_problem_t which);

/** Moves the plant through period n under the last command and fills meas and apply_tick. */
tvo_status_t bench_loop_advance(bench_loop_t *loop);

/**
 * Period n open loop: the plant is not moved; measured (one pose per robot, as bench_loop_advance
 * sampled them) is the measurement, and meas and apply_tick are filled as bench_loop_advance fills them.
 */
tvo_status_t bench_loop_replay(bench_loop_t *loop, const tvo_pose_t *measured);

/** FNV-1a (32-bit)'s offset basis: each problem's digest starts from it. */
#define BENCH_DIGEST_BASIS 2166136261u

/** digest with size bytes folded in (FNV-1a, 32-bit). */
uint32_t bench_digest_bytes(uint32_t digest, const void *bytes, size_t size);

/**
 * digest with a command folded in: the bytes of its speeds, turn rates (every robot slot) and flags.
 * Two builds of the core that compute the same commands bit for bit print the same digest.
 */
uint32_t bench_digest_command(uint32_t digest, const tvo_command_t *cmd);

#ifdef __cplusplus
}
#endif

#endif /* TVO_BENCH_PROBLEMS_H */
