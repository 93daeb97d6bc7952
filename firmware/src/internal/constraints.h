/*
 * Internal: constraints's functions (the types are in tvo/constraints.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_CONSTRAINTS_H
#define TVO_INTERNAL_CONSTRAINTS_H

#include "tvo/constraints.h"
#include "internal/assert.h"
#include "internal/barrier.h"
#include "internal/objective.h"

#ifdef __cplusplus
extern "C" {
#endif

/*
 * A constraint term kind's entries, its tvo_term_t (tvo/objective.h): gradient_jet; gradient_hessian, its
 * closed form (the same gradient jets plus the Hessian); constraint_max, the largest constraint value at y.
 */
#define TVO_CONSTRAINT_TERM_ENTRIES(kind)                                                                      \
    tvo_status_t tvo_##kind##_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim,                 \
                                           const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad);          \
    tvo_status_t tvo_##kind##_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim,             \
                                               const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,       \
                                               tvo_hessian_t *hessian);                                       \
    tvo_status_t tvo_##kind##_constraint_max(const void *term, const tvo_real_t *y, uint8_t primal_dim,       \
                                             tvo_real_t t_s, tvo_real_t *max_value)

/** robot_a != robot_b, both < TVO_MAX_ROBOTS; bound_m > 0 and finite. */
tvo_status_t tvo_distance_term_init(tvo_distance_term_t *term, const tvo_barrier_t *barrier, tvo_distance_kind_t kind,
                                    uint8_t robot_a, uint8_t robot_b, tvo_real_t bound_m, tvo_real_t bound_rate_mps);

TVO_CONSTRAINT_TERM_ENTRIES(distance);

#if TVO_BLOCK_SOLVE
/**
 * A distance bound's two sides as one term: term points to two tvo_distance_term_t in a row, the minimum
 * then the maximum of one pair of robots (tvo_problem_init's terms where its problem has a block plan).
 * The sum of the two single terms, evaluated together: their difference, direction and schedule once, one
 * gradient (sum_side 2 sign w(tau)) D(tau), their Hessians as one 2 x 2 block of the plan's matrix (as two
 * rank-one parts, each the sides' sum, where one is stiff or the matrix dense). The constraint value is
 * the larger side's.
 */
TVO_CONSTRAINT_TERM_ENTRIES(distance_pair);
#endif

/** a0 must not be zero; all values finite. */
tvo_status_t tvo_halfspace_term_init(tvo_halfspace_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                     const tvo_real_t normal[2], const tvo_real_t normal_rate[2], tvo_real_t bound_m,
                                     tvo_real_t bound_rate_mps);

TVO_CONSTRAINT_TERM_ENTRIES(halfspace);

/**
 * 1 <= count <= TVO_MAX_OBSTACLES disks with radius > 0, pairwise disjoint (TVO_ERR_PARAM
 * otherwise: the construction needs non-intersecting obstacles); robot_radius_m >= 0. On a refused
 * disk *bad_obstacle (if not NULL) is its index (the later of two that intersect), else -1.
 */
tvo_status_t tvo_free_space_term_init(tvo_free_space_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                      tvo_real_t robot_radius_m, const tvo_disk_t *obstacles, uint8_t count,
                                      int16_t *bad_obstacle);

TVO_CONSTRAINT_TERM_ENTRIES(free_space);

/** Clearance |y_r - o_i| - r - r_i of robot position p to obstacle i (negative: collision). */
tvo_real_t tvo_disk_clearance(const tvo_disk_t *obstacle, tvo_real_t robot_radius_m, const tvo_real_t position_m[2]);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_CONSTRAINTS_H */
