/*
 * Inequality-constraint terms f_i(y, t) <= 0, each entering the objective through the relaxed
 * barrier (tvo/barrier.h): gradient += w(t) grad_y f_i with w = -(1/c) B'_delta(s - f_i).
 *
 * Robots are numbered 0..N-1; robot r's position is y[2r], y[2r+1].
 *
 * - Distance bounds between two robots (squared, so f is smooth): with D = y_a - y_b,
 *     minimum: d(t)^2 - |D|^2 <= 0      maximum: |D|^2 - d(t)^2 <= 0,     d(t) = d0 + d1 t.
 *   The minimum bound is nonconvex: its Hessian contribution can make the total Hessian indefinite
 *   (the law's solve then regularises, see tvo/linsolve.h).
 * - Half-spaces a(t)^T y_r <= b(t) with a(t) = a0 + a1 t, b(t) = b0 + b1 t.
 * - The local free space of a disk robot (radius r) among disk obstacles (centre o_i, radius r_i),
 *   after Arslan & Koditschek: f_i(y; y_c) = a_i(y_c)^T y - b_i(y_c) with
 *     a_i = o_i - y_c,  theta_i = 1/2 - (r_i^2 - r^2) / (2 |o_i - y_c|^2),
 *     b_i = a_i^T (theta_i o_i + (1 - theta_i) y_c + r (y_c - o_i)/|y_c - o_i|).
 *   y_c is the robot's own position. This implementation treats y_c as a parameter frozen at the
 *   current output (the constant coefficient of the y jet): Hessian columns and time derivatives
 *   see the half-planes as fixed, and they are re-derived at every evaluation. So the law's
 *   g-dot = H y' + grad_yt omits (d grad / d y_c) y' (the motion of the planes with the robot); the
 *   gradient dynamics are imposed on the "projected goal" problem of Arslan & Koditschek at each
 *   instant, not on the total derivative. At y = y_c, f_i = -c (c + 2 r_i)/2 with c the clearance
 *   |o_i - y_c| - r - r_i: negative when the robot clears obstacle i. (A robot covering a smaller
 *   obstacle, c < -2 r_i, is outside what the construction handles: the plane there reads feasible.
 *   tvo_free_space_constraint_max reports |f| for a colliding robot, so the s0 rule always sees a
 *   collision as a violation.)
 */
#ifndef TVO_CONSTRAINTS_H
#define TVO_CONSTRAINTS_H

#include "tvo/barrier.h"
#include "tvo/objective.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum {
    TVO_DISTANCE_MIN = 0,
    TVO_DISTANCE_MAX = 1
} tvo_distance_kind_t;

typedef struct {
    const tvo_barrier_t *barrier;
    tvo_distance_kind_t kind;
    uint8_t offset_a;               /* 2 * robot_a */
    uint8_t offset_b;               /* 2 * robot_b */
    tvo_real_t bound_m;             /* d0 > 0 */
    tvo_real_t bound_rate_mps;      /* d1; d(t) must stay > 0 over the run (checked per evaluation) */
} tvo_distance_term_t;

/** robot_a != robot_b, both < TVO_MAX_ROBOTS; bound_m > 0 and finite. */
tvo_status_t tvo_distance_term_init(tvo_distance_term_t *term, const tvo_barrier_t *barrier, tvo_distance_kind_t kind,
                                    uint8_t robot_a, uint8_t robot_b, tvo_real_t bound_m, tvo_real_t bound_rate_mps);
tvo_status_t tvo_distance_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                       uint8_t order, tvo_jet_t *grad);
/** Closed form of tvo_distance_gradient_jet: the same gradient jets plus the Hessian (see tvo_term_t). */
tvo_status_t tvo_distance_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                   uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian);
tvo_status_t tvo_distance_constraint_max(const void *term, const tvo_real_t *y, uint8_t primal_dim, tvo_real_t t_s,
                                         tvo_real_t *max_value);

typedef struct {
    const tvo_barrier_t *barrier;
    uint8_t offset;                 /* 2 * robot */
    tvo_real_t normal[2];           /* a0 */
    tvo_real_t normal_rate[2];      /* a1 */
    tvo_real_t bound_m;             /* b0 */
    tvo_real_t bound_rate_mps;      /* b1 */
} tvo_halfspace_term_t;

/** a0 must not be zero; all values finite. */
tvo_status_t tvo_halfspace_term_init(tvo_halfspace_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                     const tvo_real_t normal[2], const tvo_real_t normal_rate[2], tvo_real_t bound_m,
                                     tvo_real_t bound_rate_mps);
tvo_status_t tvo_halfspace_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                        uint8_t order, tvo_jet_t *grad);
/** Closed form of tvo_halfspace_gradient_jet: the same gradient jets plus the Hessian (see tvo_term_t). */
tvo_status_t tvo_halfspace_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                   uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian);
tvo_status_t tvo_halfspace_constraint_max(const void *term, const tvo_real_t *y, uint8_t primal_dim, tvo_real_t t_s,
                                          tvo_real_t *max_value);

typedef struct {
    tvo_real_t center_m[2];
    tvo_real_t radius_m;
} tvo_disk_t;

typedef struct {
    const tvo_barrier_t *barrier;
    uint8_t offset;                 /* 2 * robot */
    uint8_t obstacle_count;
    tvo_real_t robot_radius_m;
    tvo_disk_t obstacle[TVO_MAX_OBSTACLES];
} tvo_free_space_term_t;

/**
 * 1 <= count <= TVO_MAX_OBSTACLES disks with radius > 0, pairwise disjoint (TVO_ERR_PARAM
 * otherwise: the construction needs non-intersecting obstacles); robot_radius_m >= 0.
 */
tvo_status_t tvo_free_space_term_init(tvo_free_space_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                      tvo_real_t robot_radius_m, const tvo_disk_t *obstacles, uint8_t count);
tvo_status_t tvo_free_space_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                         uint8_t order, tvo_jet_t *grad);
/** Closed form of tvo_free_space_gradient_jet: the same gradient jets plus the Hessian (see tvo_term_t). */
tvo_status_t tvo_free_space_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim, const tvo_time_jet_t *t,
                                   uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian);
tvo_status_t tvo_free_space_constraint_max(const void *term, const tvo_real_t *y, uint8_t primal_dim, tvo_real_t t_s,
                                           tvo_real_t *max_value);

/** Clearance |y_r - o_i| - r - r_i of robot position p to obstacle i (negative: collision). */
tvo_real_t tvo_disk_clearance(const tvo_disk_t *obstacle, tvo_real_t robot_radius_m, const tvo_real_t position_m[2]);

#ifdef __cplusplus
}
#endif

#endif /* TVO_CONSTRAINTS_H */
