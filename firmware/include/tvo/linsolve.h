/*
 * Fixed-size symmetric positive-definite solve (Cholesky, LL^T) for the law's Newton step.
 */
#ifndef TVO_LINSOLVE_H
#define TVO_LINSOLVE_H

#include "tvo/config.h"
#include "tvo/status.h"

/**
 * Solves A x = b for symmetric A (lower triangle read) of size n <= TVO_MAX_OUTPUT_DIM.
 * A is overwritten by its Cholesky factor. Reports TVO_ERR_NOT_POSITIVE_DEFINITE when a pivot is
 * not above a relative tolerance instead of dividing by (near) zero. x may alias b.
 */
tvo_status_t tvo_cholesky_solve(tvo_real_t a[TVO_MAX_OUTPUT_DIM][TVO_MAX_OUTPUT_DIM], uint8_t n,
                                const tvo_real_t *b, tvo_real_t *x);

#endif /* TVO_LINSOLVE_H */
