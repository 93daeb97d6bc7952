/* A whole planning problem assembled from a plain description; see tvo/problem.h. */
#include "tvo/problem.h"

#include "internal/barrier.h"
#include "internal/block_solve.h"
#include "internal/constraints.h"
#include "internal/equality.h"
#include "internal/objective.h"

#include <stddef.h>
#include <string.h>

enum {
    PART_ROBOTS = 0,
    PART_BARRIER = 1,
    PART_DISTANCE = 2,
    PART_HALFSPACE = 3,
    PART_OBSTACLES = 4,
    PART_OFFSETS = 5
};

tvo_status_t tvo_problem_desc_default(tvo_problem_desc_t *desc)
{
    if (desc == NULL) {
        return TVO_ERR_NULL;
    }
    memset(desc, 0, sizeof(*desc));
    for (uint8_t r = 0; r < TVO_MAX_ROBOTS; ++r) {
        desc->tracking_weight[r][0] = TVO_R(1.0);
        desc->tracking_weight[r][1] = TVO_R(1.0);
    }
    return tvo_barrier_config_default(&desc->barrier);
}

/* A bound's sides as terms, the minimum first: each side its own term, or, for three robots or more (the
 * block plan's problems), both sides of a bound as one term (its two distance terms in a row:
 * tvo_distance_pair_gradient_hessian). */
static tvo_status_t add_distance_bound(tvo_problem_t *problem, const tvo_distance_bound_desc_t *d, uint8_t robots)
{
    const uint8_t first = problem->distance_term_count;
    uint8_t count = 0u;
    tvo_status_t st = TVO_OK;
    for (uint8_t side = 0; st == TVO_OK && side < 2u; ++side) {
        const tvo_real_t bound_m = side == 0u ? d->min_m : d->max_m;
        if (!(bound_m > TVO_R(0.0))) {
            continue; /* that side is not asked for */
        }
        if ((unsigned)first + count >= 2u * TVO_MAX_DISTANCE_BOUNDS) {
            return TVO_ERR_CAPACITY;
        }
        st = tvo_distance_term_init(&problem->distance[first + count], &problem->barrier,
                                    side == 0u ? TVO_DISTANCE_MIN : TVO_DISTANCE_MAX, d->robot_a, d->robot_b, bound_m,
                                    side == 0u ? d->min_rate_mps : d->max_rate_mps);
        count++;
    }
#if !TVO_BLOCK_SOLVE
    (void)robots;
#else
    if (st == TVO_OK && count == 2u && robots >= 3u) {
        const tvo_term_t spec = {tvo_distance_pair_gradient_jet, tvo_distance_pair_gradient_hessian,
                                 tvo_distance_pair_constraint_max, &problem->distance[first], TVO_TERM_GENERAL};
        st = tvo_objective_add(&problem->objective, &spec);
        count = st == TVO_OK ? count : 0u;
    } else
#endif
    {
        for (uint8_t k = 0; st == TVO_OK && k < count; ++k) {
            const tvo_term_t spec = {tvo_distance_gradient_jet, tvo_distance_gradient_hessian,
                                     tvo_distance_constraint_max, &problem->distance[first + k], TVO_TERM_GENERAL};
            st = tvo_objective_add(&problem->objective, &spec);
        }
    }
    if (st == TVO_OK) {
        problem->distance_term_count = (uint8_t)(first + count);
    }
    return st;
}

static tvo_status_t build_constraints(tvo_problem_t *problem, const tvo_problem_desc_t *desc,
                                      tvo_problem_culprit_t *culprit)
{
    const uint8_t n = desc->robot_count;
    tvo_status_t st = TVO_OK;
    culprit->part = PART_DISTANCE;
    if (desc->distance_count > TVO_MAX_DISTANCE_BOUNDS) {
        return TVO_ERR_CAPACITY;
    }
    for (uint8_t i = 0; st == TVO_OK && i < desc->distance_count; ++i) {
        culprit->index = (int16_t)i;
        const tvo_distance_bound_desc_t *d = &desc->distance[i];
        if (d->robot_a >= n || d->robot_b >= n || !isfinite(d->min_m) || !isfinite(d->max_m) || d->min_m < TVO_R(0.0) ||
            d->max_m < TVO_R(0.0) || (d->min_m == TVO_R(0.0) && d->max_m == TVO_R(0.0)) ||
            (d->max_m > TVO_R(0.0) && d->min_m >= d->max_m)) {
            return TVO_ERR_PARAM;
        }
        st = add_distance_bound(problem, d, n);
    }
    if (st != TVO_OK) {
        return st;
    }
    culprit->part = PART_HALFSPACE;
    culprit->index = -1;
    if (desc->halfspace_count > TVO_MAX_HALFSPACES) {
        return TVO_ERR_CAPACITY;
    }
    for (uint8_t i = 0; st == TVO_OK && i < desc->halfspace_count; ++i) {
        culprit->index = (int16_t)i;
        const tvo_halfspace_desc_t *h = &desc->halfspace[i];
        if (h->robot >= n) {
            return TVO_ERR_PARAM;
        }
        st = tvo_halfspace_term_init(&problem->halfspace[i], &problem->barrier, h->robot, h->normal, h->normal_rate,
                                     h->bound_m, h->bound_rate_mps);
        if (st == TVO_OK) {
            const tvo_term_t spec = {tvo_halfspace_gradient_jet, tvo_halfspace_gradient_hessian,
                                     tvo_halfspace_constraint_max, &problem->halfspace[i], TVO_TERM_GENERAL};
            st = tvo_objective_add(&problem->objective, &spec);
        }
    }
    if (st != TVO_OK) {
        return st;
    }
    culprit->part = PART_OBSTACLES;
    culprit->index = -1;
    if (desc->obstacle_count > TVO_MAX_OBSTACLES) {
        return TVO_ERR_CAPACITY;
    }
    for (uint8_t r = 0; st == TVO_OK && desc->obstacle_count > 0u && r < n; ++r) {
        st = tvo_free_space_term_init(&problem->free_space[r], &problem->barrier, r, desc->robot_radius_m,
                                      desc->obstacle, desc->obstacle_count, &culprit->index);
        if (st == TVO_OK) {
            const tvo_term_t spec = {tvo_free_space_gradient_jet, tvo_free_space_gradient_hessian,
                                     tvo_free_space_constraint_max, &problem->free_space[r], TVO_TERM_GENERAL};
            st = tvo_objective_add(&problem->objective, &spec);
        }
    }
    return st;
}

/* The objective's start rule (tvo/objective.h): in a controller's period whose measurement passed its
 * checks, s0 from its positions at t = 0 unless already chosen; y NULL, that period was then refused:
 * what it chose taken back (s0 to 0,
 * as tvo_barrier_init left it; the choice writes nothing else). slack_pending: chosen by the period
 * in progress (0 again after a refusal, so a refused period leaves the problem as it was). */
static void problem_start_rule(const tvo_objective_t *objective, const tvo_real_t *y)
{
    /* The objective is the problem's own (the problem is not const: the controller only reads it). */
    tvo_problem_t *problem = (tvo_problem_t *)((uintptr_t)objective - offsetof(tvo_problem_t, objective));
    if (y == NULL) {
        if (problem->slack_pending) {
            problem->barrier.slack0 = TVO_R(0.0);
            problem->slack_chosen = 0u;
        }
    } else if (!problem->slack_chosen) {
        (void)tvo_problem_choose_slack(problem, y, TVO_R(0.0)); /* the step judges y */
        problem->slack_pending = problem->slack_chosen;
        return;
    }
    problem->slack_pending = 0u;
}

#if TVO_BLOCK_SOLVE
/* The law's solve follows the problem's coupling from three robots on (two are cheaper dense): a distance
 * bound couples its robots, a formation offset each of its robots to its multipliers (tvo/linsolve.h). A
 * plan that cannot be made leaves the dense solve. */
static void choose_solve_plan(tvo_problem_t *problem, const tvo_problem_desc_t *desc)
{
    const uint8_t robots = desc->robot_count;
    if (robots < 3u) {
        return;
    }
    uint8_t pairs[2u * (TVO_MAX_DISTANCE_BOUNDS + 2u * TVO_MAX_OFFSET_EQUALITIES)];
    uint8_t count = 0u;
    for (uint8_t i = 0; i < desc->distance_count && i < TVO_MAX_DISTANCE_BOUNDS; ++i) {
        pairs[2u * count] = desc->distance[i].robot_a;
        pairs[2u * count + 1u] = desc->distance[i].robot_b;
        count++;
    }
    for (uint8_t i = 0; i < desc->offset_count && i < TVO_MAX_OFFSET_EQUALITIES; ++i) {
        for (uint8_t end = 0; end < 2u; ++end) {
            pairs[2u * count] = end == 0u ? desc->offset[i].robot_a : desc->offset[i].robot_b;
            pairs[2u * count + 1u] = (uint8_t)(robots + i);
            count++;
        }
    }
    if (tvo_solve_plan_build(&problem->plan, robots, desc->offset_count, problem->objective.primal_dim, pairs, count) ==
        TVO_OK) {
        problem->objective.plan = &problem->plan;
    }
}
#endif

tvo_status_t tvo_problem_init(tvo_problem_t *problem, const tvo_problem_desc_t *desc, uint8_t relative_degree,
                              tvo_problem_culprit_t *bad)
{
    tvo_problem_culprit_t culprit = {PART_ROBOTS, -1};
    if (bad != NULL) {
        *bad = culprit;
    }
    if (problem == NULL || desc == NULL) {
        return TVO_ERR_NULL;
    }
    memset(problem, 0, sizeof(*problem));
    const uint8_t n = desc->robot_count;
    tvo_status_t st = (n == 0u || n > TVO_MAX_ROBOTS) ? TVO_ERR_DIMENSION : TVO_OK;
    if (st == TVO_OK) {
        st = tvo_objective_init(&problem->objective, (uint8_t)(2u * n));
    }
    for (uint8_t r = 0; st == TVO_OK && r < n; ++r) {
        culprit.index = (int16_t)r;
        problem->target[r] = desc->target[r];
        st = tvo_tracking_init(&problem->tracking[r], &problem->target[r], desc->tracking_weight[r], (uint8_t)(2u * r));
        if (st == TVO_OK) {
            const tvo_term_t spec = {NULL, NULL, NULL, &problem->tracking[r], TVO_TERM_TRACKING};
            st = tvo_objective_add(&problem->objective, &spec);
        }
    }
    const uint8_t any_inequality = (uint8_t)(desc->distance_count > 0u || desc->halfspace_count > 0u ||
                                             desc->obstacle_count > 0u);
    if (st == TVO_OK && any_inequality) {
        culprit.part = PART_BARRIER;
        culprit.index = -1;
        st = tvo_barrier_init(&problem->barrier, &desc->barrier, relative_degree);
        if (st == TVO_OK) {
            st = build_constraints(problem, desc, &culprit);
        }
    }
    if (st == TVO_OK) {
        culprit.part = PART_OFFSETS;
        culprit.index = -1;
        if (desc->offset_count > TVO_MAX_OFFSET_EQUALITIES) {
            st = TVO_ERR_CAPACITY;
        }
    }
    for (uint8_t i = 0; st == TVO_OK && i < desc->offset_count; ++i) {
        culprit.index = (int16_t)i;
        const tvo_offset_desc_t *o = &desc->offset[i];
        if (o->robot_a >= n || o->robot_b >= n) {
            st = TVO_ERR_PARAM;
            break;
        }
        problem->offset_function[i] = o->offset;
        st = tvo_offset_equality_add(&problem->offset[i], &problem->objective, &problem->offset_function[i],
                                     o->robot_a, o->robot_b);
    }
    if (st != TVO_OK) {
        if (bad != NULL) {
            *bad = culprit;
        }
        memset(problem, 0, sizeof(*problem));
        return st;
    }
    problem->has_inequalities = any_inequality;
    if (any_inequality) {
        problem->objective.start_rule = problem_start_rule;
    }
#if TVO_BLOCK_SOLVE
    choose_solve_plan(problem, desc);
#endif
    problem->initialized = 1;
    return TVO_OK;
}

tvo_status_t tvo_problem_choose_slack(tvo_problem_t *problem, const tvo_real_t *y, tvo_real_t t_s)
{
    if (problem == NULL || y == NULL) {
        return TVO_ERR_NULL;
    }
    if (!problem->initialized) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (!problem->has_inequalities || problem->slack_chosen) {
        return TVO_OK;
    }
    tvo_real_t max_value = TVO_R(0.0);
    uint8_t has_constraints = 0;
    tvo_status_t st = tvo_objective_constraint_max(&problem->objective, y, t_s, &max_value, &has_constraints);
    if (st == TVO_OK && has_constraints) {
        st = tvo_barrier_choose_slack(&problem->barrier, max_value);
    }
    if (st == TVO_OK) {
        problem->slack_chosen = 1;
    }
    return st;
}

tvo_target_t *tvo_problem_target(tvo_problem_t *problem, uint8_t robot)
{
    if (problem == NULL || !problem->initialized || robot >= problem->objective.primal_dim / 2u) {
        return NULL;
    }
    return &problem->target[robot];
}
