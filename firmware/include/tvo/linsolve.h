/*
 * Fixed-size linear solves for the law's Newton step.
 *
 * - tvo_cholesky_solve: symmetric positive definite A x = b (LL^T); reports loss of definiteness
 *   (a pivot not above a relative floor) instead of dividing by (near) zero.
 * - tvo_saddle_solve: the law's solve for z = (y, nu): [P C^T; C D] x = b with P the primal
 *   (Hessian) block and, with equality constraints, C their Jacobian (D = 0 for linear ones).
 *   P is factored by Cholesky; when P is not positive definite (a nonconvex term such as a
 *   minimum-distance bound), it is regularised by the smallest shift mu I of the ladder
 *   mu = 1e-6 s, 1e-5 s, ..., 1e2 s (s = max(1, max |P_ii|)) that makes it so, and if none does,
 *   by the Gershgorin shift (the largest row's off-diagonal sum minus its diagonal) plus
 *   1e-6 s + 128 n eps (s + shift), a margin that keeps the shifted matrix positive definite after
 *   rounding too. The step then descends Phi but does not impose the
 *   gradient dynamics exactly; *shift reports mu (0 when none was needed). The dual part is
 *   eliminated through the Schur complement S = C P^-1 C^T - D, which must be positive definite
 *   (the equalities independent): TVO_ERR_NOT_POSITIVE_DEFINITE otherwise.
 */
#ifndef TVO_LINSOLVE_H
#define TVO_LINSOLVE_H

#include "tvo/config.h"
#include "tvo/jet.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef tvo_real_t tvo_matrix_t[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];

/** Most rank-one parts a Hessian keeps apart (the stiffest; the rest are added into the matrix):
 *  independent directions, so no more than the outputs, and 4 at most. */
#define TVO_MAX_RANK_ONE_PARTS (TVO_MAX_OUTPUT_DIM < 4 ? TVO_MAX_OUTPUT_DIM : 4)
/** Entries of a rank-one part's vector (a constraint's gradient touches at most two robots). */
#define TVO_RANK_ONE_MAX_ENTRIES 4

/**
 * A barrier's part of the objective along one direction u (sparse): curvature weight u u^T in the
 * Hessian and gradient(tau) u in the gradient jets.
 */
typedef struct {
    tvo_real_t weight;
    tvo_jet_t gradient;
    uint8_t count;
    uint8_t index[TVO_RANK_ONE_MAX_ENTRIES];
    tvo_real_t value[TVO_RANK_ONE_MAX_ENTRIES];
} tvo_rank_one_t;

/**
 * A Hessian as a matrix plus rank-one parts kept apart, with their gradients: a barrier's curvature
 * along its constraint's gradient can be 1e7 times the rest, and float32 can neither factor the sum
 * (the soft directions are lost to cancellation) nor add its gradient to the soft ones (their
 * digits are lost to rounding). tvo_saddle_solve_split solves with such parts apart.
 */
/** Small systems of the solve: the equalities' Schur complement or the parts' capacitance. */
#define TVO_SOLVE_SMALL_DIM (TVO_MAX_EQUALITIES > TVO_MAX_RANK_ONE_PARTS ? TVO_MAX_EQUALITIES : TVO_MAX_RANK_ONE_PARTS)

/** The solve's working storage, kept beside the matrix so the step's stack stays small. */
typedef struct {
    tvo_real_t diag[TVO_MAX_Z_DIM];                       /* the diagonal a factor overwrites */
    tvo_real_t first[TVO_MAX_Z_DIM];                      /* P^-1 b */
    tvo_real_t dense[TVO_MAX_Z_DIM];                      /* a sparse vector spread out, or b with parts */
    tvo_real_t columns[TVO_SOLVE_SMALL_DIM][TVO_MAX_Z_DIM]; /* P^-1 C^T or A^-1 U */
    tvo_real_t small[TVO_SOLVE_SMALL_DIM][TVO_SOLVE_SMALL_DIM];
    tvo_real_t small_rhs[TVO_SOLVE_SMALL_DIM];
    tvo_real_t small_x[TVO_SOLVE_SMALL_DIM];
} tvo_solve_scratch_t;

typedef struct {
    tvo_matrix_t matrix;
    uint8_t rank_one_count;
    tvo_rank_one_t rank_one[TVO_MAX_RANK_ONE_PARTS];
    tvo_solve_scratch_t scratch; /* tvo_saddle_solve_split's; no meaning between solves */
} tvo_hessian_t;

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

/** A rank-one part is stiff when weight |u|^2 exceeds this times the matrix's largest diagonal entry. */
#define TVO_STIFF_RATIO TVO_R(1e3)

#ifdef __cplusplus
}
#endif

#endif /* TVO_LINSOLVE_H */
