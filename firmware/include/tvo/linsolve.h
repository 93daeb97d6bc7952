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

/**
 * The block solve's plan, chosen once at tvo_problem_init from the problem's coupling (tvo/problem.h):
 * the law's matrix seen as 2 x 2 blocks, one node per robot (its two outputs) and one per formation
 * offset (its two multipliers), an elimination order (robots by least fill first, multipliers last)
 * and the blocks its factor holds (the coupling's and their fill). A step then clears, factors and
 * solves only those blocks, in the matrix's own storage: a ring, chain or star of N robots costs O(N).
 * Built where a build holds three robots or more (TVO_BLOCK_SOLVE); one or two robots keep the dense
 * solve, which is cheaper there.
 */
#define TVO_BLOCK_SOLVE (TVO_MAX_ROBOTS > 2)
/** Nodes of a plan: every robot, and a formation offset's pair of multipliers each. */
#define TVO_PLAN_MAX_NODES (TVO_MAX_ROBOTS + TVO_MAX_EQUALITIES / 2)
/** Off-diagonal blocks of a plan's factor: as many as a full factor has, so any coupling fits. */
#define TVO_PLAN_MAX_BLOCKS (TVO_PLAN_MAX_NODES * (TVO_PLAN_MAX_NODES - 1) / 2)

#if TVO_BLOCK_SOLVE
typedef struct {
    uint8_t node_count;                                  /* 0: none (the dense solve) */
    uint8_t primal_nodes;                                /* the robots: the first positions */
    uint8_t first[TVO_PLAN_MAX_NODES];                   /* z index of each position's first coordinate */
    uint16_t below_start[TVO_PLAN_MAX_NODES + 1];        /* position p's blocks: below[below_start[p] ..] */
    uint8_t below[TVO_ARRAY_LEN(TVO_PLAN_MAX_BLOCKS)];   /* the later positions p couples to, by their first
                                                            coordinate, in order */
} tvo_solve_plan_t;
#endif

typedef struct {
    tvo_matrix_t matrix;
#if TVO_BLOCK_SOLVE
    const tvo_solve_plan_t *plan; /* the blocks the matrix holds (NULL: every entry), set per evaluation */
#endif
    uint8_t rank_one_count;
    tvo_rank_one_t rank_one[TVO_MAX_RANK_ONE_PARTS];
    tvo_solve_scratch_t scratch; /* tvo_saddle_solve_split's; no meaning between solves */
} tvo_hessian_t;

/** A rank-one part is stiff when weight |u|^2 exceeds this times the matrix's largest diagonal entry. */
#define TVO_STIFF_RATIO TVO_R(1e3)

#ifdef __cplusplus
}
#endif

#endif /* TVO_LINSOLVE_H */
