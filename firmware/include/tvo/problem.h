/*
 * A whole planning problem for N robots, assembled from a plain description: one tracking term per
 * robot, optional distance bounds, half-spaces, obstacle free spaces (all through one relaxed
 * barrier) and formation-offset equalities (through multipliers). It owns the storage of every term,
 * so an edge (LCM node, board) fills a tvo_problem_desc_t and gets an objective for the controller.
 */
#ifndef TVO_PROBLEM_H
#define TVO_PROBLEM_H

#include "tvo/barrier.h"
#include "tvo/constraints.h"
#include "tvo/equality.h"
#include "tvo/objective.h"
#include "tvo/target.h"
#include "tvo/tracking.h"

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TVO_MAX_DISTANCE_BOUNDS /* a size limit like those of tvo/config.h (TVO_LIMITS can raise it) */
#define TVO_MAX_DISTANCE_BOUNDS 6
#endif
#if TVO_MAX_DISTANCE_BOUNDS < 1 || TVO_MAX_DISTANCE_BOUNDS > 64
#error "TVO_MAX_DISTANCE_BOUNDS must be 1 .. 64"
#endif
#define TVO_MAX_HALFSPACES 4
#define TVO_MAX_OFFSET_EQUALITIES (TVO_MAX_EQUALITIES / 2)

typedef struct {
    uint8_t robot_a;
    uint8_t robot_b;
    tvo_real_t min_m;               /* minimum distance d_min(0); 0: no lower bound */
    tvo_real_t min_rate_mps;        /* d_min(t) = min_m + min_rate_mps t */
    tvo_real_t max_m;               /* maximum distance d_max(0); 0: no upper bound */
    tvo_real_t max_rate_mps;
} tvo_distance_bound_desc_t;

typedef struct {
    uint8_t robot;
    tvo_real_t normal[2];
    tvo_real_t normal_rate[2];
    tvo_real_t bound_m;
    tvo_real_t bound_rate_mps;
} tvo_halfspace_desc_t;

typedef struct {
    uint8_t robot_a;
    uint8_t robot_b;
    tvo_target_t offset;            /* d(t) in y_a - y_b = d(t) */
} tvo_offset_desc_t;

typedef struct {
    uint8_t robot_count;                              /* 1 .. TVO_MAX_ROBOTS */
    tvo_target_t target[TVO_MAX_ROBOTS];              /* tracking target per robot */
    tvo_real_t tracking_weight[TVO_MAX_ROBOTS][2];    /* diagonal W per robot, > 0 */
    tvo_barrier_config_t barrier;                     /* used when any inequality is present */
    uint8_t distance_count;
    tvo_distance_bound_desc_t distance[TVO_MAX_DISTANCE_BOUNDS];
    uint8_t halfspace_count;
    tvo_halfspace_desc_t halfspace[TVO_MAX_HALFSPACES];
    uint8_t obstacle_count;                           /* avoided by every robot */
    tvo_real_t robot_radius_m;
    tvo_disk_t obstacle[TVO_MAX_OBSTACLES];
    uint8_t offset_count;
    tvo_offset_desc_t offset[TVO_ARRAY_LEN(TVO_MAX_OFFSET_EQUALITIES)];
} tvo_problem_desc_t;

typedef struct {
    tvo_objective_t objective;
    tvo_barrier_t barrier;
    tvo_target_t target[TVO_MAX_ROBOTS];
    tvo_tracking_term_t tracking[TVO_MAX_ROBOTS];
    tvo_distance_term_t distance[2u * TVO_MAX_DISTANCE_BOUNDS];
    tvo_halfspace_term_t halfspace[TVO_MAX_HALFSPACES];
    tvo_free_space_term_t free_space[TVO_MAX_ROBOTS];
    tvo_target_t offset_function[TVO_ARRAY_LEN(TVO_MAX_OFFSET_EQUALITIES)];
    tvo_offset_equality_term_t offset[TVO_ARRAY_LEN(TVO_MAX_OFFSET_EQUALITIES)];
#if TVO_BLOCK_SOLVE
    tvo_solve_plan_t plan;          /* the block solve's, for three robots or more (objective.plan) */
#endif
    uint8_t distance_term_count;
    uint8_t has_inequalities;
    uint8_t slack_chosen;           /* s0 chosen: by the controller's step (the objective's start rule,
                                       in the first period it commits) or tvo_problem_choose_slack */
    uint8_t slack_pending;          /* the start rule chose s0 in the period in progress */
    uint8_t initialized;
} tvo_problem_t;

/** What tvo_problem_init refused: the part of the description and the entry in it. */
typedef struct {
    uint8_t part;  /* 0 robots/targets, 1 barrier, 2 distance, 3 half-space, 4 obstacles, 5 offsets */
    int16_t index; /* the refused entry of the part (a robot, a distance bound, a half-space, an obstacle
                      (the later of two that intersect), an offset); -1: the part as a whole (its count,
                      the barrier, the robot radius) */
} tvo_problem_culprit_t;

/** Empty description: no robots, no constraints, default barrier, unit tracking weights. */
tvo_status_t tvo_problem_desc_default(tvo_problem_desc_t *desc);

/**
 * Validates desc and builds the objective (primal dimension 2N, plus 2 multipliers per offset);
 * pass &problem->objective to the controller's init (the problem must outlive the controller). With
 * inequalities the objective carries the s0 rule as its start rule: the controller's step chooses s0
 * as tvo_problem_choose_slack(problem, y, 0) would, y the measured positions of the first period it
 * commits (a refused period keeps nothing of its choice).
 * relative_degree (k) is the controller's: 2 for tvo_controller_t, cfg.relative_degree for the
 * chain; it bounds the barrier's m_r from below (m_r >= k + 1). On TVO_ERR_PARAM (or another error)
 * *bad, if not NULL, names the culprit (tvo_problem_culprit_t); {0, -1} on success.
 */
tvo_status_t tvo_problem_init(tvo_problem_t *problem, const tvo_problem_desc_t *desc, uint8_t relative_degree,
                              tvo_problem_culprit_t *bad);

/**
 * Chooses the barrier slack s0 from the robots' positions at objective time t_s (the paper's rule,
 * from max_i f_i(y(0), 0)); later calls change nothing. No-op without inequalities. Optional: the
 * controller's step chooses s0 itself (tvo_problem_init); called before the first step with other
 * positions (y = x0, y0, x1, y1, ...) or another t_s, it chooses instead and the step does not.
 */
tvo_status_t tvo_problem_choose_slack(tvo_problem_t *problem, const tvo_real_t *y, tvo_real_t t_s);

/** Streamed targets: the robot's target, to feed with tvo_target_stream_update. */
tvo_target_t *tvo_problem_target(tvo_problem_t *problem, uint8_t robot);

#ifdef __cplusplus
}
#endif

#endif /* TVO_PROBLEM_H */
