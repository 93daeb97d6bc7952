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

/** Zeroes the leading n x n block and drops every rank-one part. */
void tvo_hessian_clear(tvo_hessian_t *h, uint8_t n);

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
