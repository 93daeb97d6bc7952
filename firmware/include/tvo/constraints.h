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

typedef struct {
    const tvo_barrier_t *barrier;
    uint8_t offset;                 /* 2 * robot */
    tvo_real_t normal[2];           /* a0 */
    tvo_real_t normal_rate[2];      /* a1 */
    tvo_real_t bound_m;             /* b0 */
    tvo_real_t bound_rate_mps;      /* b1 */
} tvo_halfspace_term_t;

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

#ifdef __cplusplus
}
#endif

#endif /* TVO_CONSTRAINTS_H */
