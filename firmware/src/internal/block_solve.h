/*
 * Internal: the block solve's pieces (tvo/linsolve.h, tvo_solve_plan_t). The law's matrix stays in its
 * dense storage (tvo_hessian_t's matrix); a plan says which of its 2 x 2 blocks exist: each position's
 * diagonal block, and for positions p < q coupled in the factor the block pair at rows p, columns q (the
 * "upper" copy, which the factor never writes: the pristine matrix, as the dense solve's strict upper
 * triangle is) and rows q, columns p (the "lower" copy, where the factor's L_qp goes). Only these are
 * cleared, assembled into, factored and solved with. Not installed; unchecked: callers pass a plan from
 * tvo_solve_plan_build and a matrix whose blocks it names (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_BLOCK_SOLVE_H
#define TVO_INTERNAL_BLOCK_SOLVE_H

#include "tvo/linsolve.h"
#include "tvo/status.h"
#include "internal/assert.h"

#ifdef __cplusplus
extern "C" {
#endif

#if TVO_BLOCK_SOLVE

/**
 * The plan for robots 0 .. robots - 1 (outputs 2r, 2r + 1) and offsets multiplier pairs (node robots + i:
 * multipliers first_multiplier + 2i, + 2i + 1), coupled by the pairs of nodes given (a distance bound
 * couples its two robots, a formation offset each of its robots to its multipliers; repeats allowed).
 * The elimination order: the robots first, each time the one with the fewest neighbours left (the
 * least fill; ties to the lower index), then the multipliers the same way. TVO_ERR_DIMENSION when the
 * nodes exceed TVO_PLAN_MAX_NODES or a coordinate TVO_MAX_Z_DIM, TVO_ERR_PARAM for a pair that names a
 * node twice or one that does not exist; *plan is then empty (node_count 0).
 */
tvo_status_t tvo_solve_plan_build(tvo_solve_plan_t *plan, uint8_t robots, uint8_t offsets, uint8_t first_multiplier,
                                  const uint8_t *pairs, uint16_t pair_count);

/** Zeroes every block of the plan (both copies of a coupled pair), nothing else. */
void block_clear(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan);

/** diag receives the matrix's diagonal, and each diagonal block's lower entry its upper one: the first
 *  factor attempt then reads the blocks as the terms added them (both copies of a coupled pair alike but
 *  for the rounding of a rank-one part added entry by entry), a retry the pristine upper copies. */
void block_prepare(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, tvo_real_t *diag);

/** The lower copies from the upper ones (their transposes), the diagonal from diag plus mu on the
 *  robots' coordinates: the pristine matrix, shifted, ready to factor. */
void block_restore(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag, tvo_real_t mu);

/** What a factor attempt met. */
typedef enum {
    BLOCK_FACTORED = 0,
    BLOCK_PRIMAL_PIVOT = 1, /* a robot's pivot was not above its floor: the shift may help */
    BLOCK_DUAL_PIVOT = 2    /* the multipliers' Schur complement is not positive definite: dependent equalities */
} block_factor_result_t;

/**
 * Factors the restored matrix in place, in the plan's order: L D L^T with D = I on the robots' blocks and
 * -I on the multipliers' (their block is the negated Schur complement C P^-1 C^T, factored by Cholesky).
 * A pivot must keep more than 64 eps of its reference, as the dense factor's: a robot's coordinate its
 * diagonal entry diag + mu, a multiplier's its Schur complement's diagonal entry.
 */
block_factor_result_t block_factor(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag,
                                   tvo_real_t mu);

/** x = A^-1 b with A's factor from block_factor, over the plan's 2 * node_count coordinates; x may alias b. */
void block_substitute(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *b, tvo_real_t *x);

/** 1 if the pristine matrix (diag and the upper copies) is finite. */
int block_pattern_finite(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag);

/**
 * Over the robots' coordinates of the pristine matrix: *scale = max(1, max |P_ii|) and *gershgorin =
 * max_i (sum_{j != i} |P_ij| - P_ii), the dense solve's two numbers; off: scratch of 2 * primal_nodes.
 */
void block_gershgorin(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag, tvo_real_t *off,
                      tvo_real_t *scale, tvo_real_t *gershgorin);

#endif /* TVO_BLOCK_SOLVE */

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_BLOCK_SOLVE_H */
