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
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef tvo_real_t tvo_matrix_t[TVO_MAX_Z_DIM][TVO_MAX_Z_DIM];

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

#ifdef __cplusplus
}
#endif

#endif /* TVO_LINSOLVE_H */
