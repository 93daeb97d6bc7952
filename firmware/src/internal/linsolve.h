/*
 * Internal: linsolve's functions (the types are in tvo/linsolve.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_LINSOLVE_H
#define TVO_INTERNAL_LINSOLVE_H

#include "tvo/linsolve.h"
#include "internal/assert.h"
#include "internal/jet.h"

#ifdef __cplusplus
extern "C" {
#endif

/** m += weight u u^T for a part, and (grad not NULL) grad[u's indices] += u's entries x its gradient
 *  jets to order: a part added into a matrix. The part must not lie in m or grad. */
void tvo_rank_one_add_to(const tvo_rank_one_t *part, tvo_matrix_t m, tvo_jet_t *grad, uint8_t order);

/** Zeroes the leading n x n block and drops every rank-one part (the matrix: every entry, no plan). */
void tvo_hessian_clear(tvo_hessian_t *h, uint8_t n);

#if TVO_BLOCK_SOLVE
/** Zeroes only the plan's blocks and drops every rank-one part: the matrix is then the plan's (its terms
 *  must add only into those blocks), and tvo_saddle_solve_split solves by the plan. */
void tvo_hessian_clear_blocks(tvo_hessian_t *h, const tvo_solve_plan_t *plan);
#endif

/**
 * Solves A x = b for symmetric A (lower triangle read) of size n <= TVO_MAX_Z_DIM.
 * A is overwritten by its Cholesky factor. x may alias b.
 */
tvo_status_t tvo_cholesky_solve(tvo_matrix_t a, uint8_t n, const tvo_real_t *b, tvo_real_t *x);

/**
 * Solves the saddle system of size primal_n + dual_n (primal_n >= 1, dual_n <= TVO_MAX_EQUALITIES,
 * total <= TVO_MAX_Z_DIM);
 * a (symmetric, full matrix read) is overwritten. x may alias b. shift may be NULL.
 */
tvo_status_t tvo_saddle_solve(tvo_matrix_t a, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b, tvo_real_t *x,
                              tvo_real_t *shift);

/**
 * Adds a part (count <= TVO_RANK_ONE_MAX_ENTRIES). A part with positive weight is kept apart while
 * there is room; otherwise (or for the smallest, by weight |u|^2, when full) it is added into the
 * matrix and its gradient jets into grad (to order). The part must not lie in h's matrix or grad.
 */
void tvo_hessian_add_part(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad, uint8_t order);

/**
 * tvo_hessian_add_part for a part that may well not be stiff: one that does not dominate the
 * matrix's diagonal entries at its own indices (by TVO_STIFF_RATIO) goes straight into the matrix
 * and grad, without being kept (tvo_hessian_settle would add it in anyway).
 */
void tvo_hessian_add(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad, uint8_t order);

#if TVO_BLOCK_SOLVE
/**
 * A coupling of robots a and b (outputs a, a + 1 and b, b + 1) along a unit direction e and across it: the
 * parts weight_along v(e) v(e)^T and weight_across v(e_perp) v(e_perp)^T, v(e) = (e, -e), e_perp = (-e_1,
 * e_0) (a distance bound's closed form). In a plan's matrix (tvo_hessian_clear_blocks), when
 * tvo_hessian_add would keep neither apart (judging them in that order), both go in as one 2 x 2 block B
 * on (a, a) and (b, b) and -B on (a, b) and (b, a), and it returns 1; else it changes nothing and returns
 * 0, and the caller adds the parts with tvo_hessian_add (a dense matrix always: one or two robots keep
 * their arithmetic). The gradients are the caller's: the parts' sum is what it adds.
 */
int tvo_hessian_add_pair(tvo_hessian_t *h, uint8_t a, uint8_t b, const tvo_real_t e[2], tvo_real_t along_weight,
                         tvo_real_t across_weight);
#endif

/**
 * Keeps apart only the parts that are stiff (weight |u|^2 above TVO_STIFF_RATIO times the matrix's
 * largest diagonal entry), and none with equalities (dual_n > 0); the others go into the matrix and
 * grad as in tvo_hessian_add_part.
 */
void tvo_hessian_settle(tvo_hessian_t *h, uint8_t n, uint8_t dual_n, tvo_jet_t *grad, uint8_t order);

/**
 * Solves (matrix + sum_k w_k u_k u_k^T) x = b + sum_k gamma_k u_k for the parts kept apart
 * (gamma: one entry per part; may be NULL without parts), as tvo_saddle_solve does: by
 * Sherman-Morrison-Woodbury on the matrix's Cholesky factor when the matrix alone is positive
 * definite and there are no equalities (no digit of the soft directions is lost), else by adding
 * the parts in. h is overwritten. x may alias b.
 */
tvo_status_t tvo_saddle_solve_split(tvo_hessian_t *h, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                    const tvo_real_t *gamma, tvo_real_t *x, tvo_real_t *shift);

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_LINSOLVE_H */
