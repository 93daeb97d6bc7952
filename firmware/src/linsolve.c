/* Fixed-size Cholesky and saddle-point solves; see tvo/linsolve.h. */
#include "internal/linsolve.h"

#include "internal/block_solve.h"
#include "shape.h"

#include <string.h>

/* Regularisation ladder: mu = s * 10^(LADDER_FIRST_EXP + j), j = 0 .. LADDER_STEPS - 1. */
#define LADDER_STEPS 9u
#define LADDER_FIRST_SCALE TVO_R(1e-6)

/* In-place LL^T of the leading n x n block (row-major, row stride `stride`); 0 if a pivot is not
 * above its floor. Each pivot must keep more than 64 eps of its own diagonal entry: the test of
 * Cholesky on the diagonally scaled matrix, so a barrier that stiffens one direction by 1e6 does not
 * make the soft directions look singular (a floor relative to the largest diagonal would). */
#define AT(a, stride, i, j) ((a)[(size_t)(i) * (stride) + (j)])

TVO_SHAPE_BODY int cholesky_factor_shape(tvo_real_t *a, const unsigned stride, const unsigned n)
{
    TVO_UNROLL_SMALL
    for (unsigned j = 0; j < n; ++j) {
        const tvo_real_t diagonal = AT(a, stride, j, j);
        tvo_real_t d = diagonal;
        for (unsigned k = 0; k < j; ++k) {
            d -= AT(a, stride, j, k) * AT(a, stride, j, k);
        }
        if (!(diagonal > TVO_R(0.0)) || !(d > TVO_R(64.0) * TVO_EPSILON * diagonal)) {
            return 0;
        }
        const tvo_real_t l_jj = TVO_SQRT(d);
        const tvo_real_t inv_l_jj = TVO_R(1.0) / l_jj;
        AT(a, stride, j, j) = l_jj;
        for (unsigned i = j + 1u; i < n; ++i) {
            tvo_real_t s = AT(a, stride, i, j);
            for (unsigned k = 0; k < j; ++k) {
                s -= AT(a, stride, i, k) * AT(a, stride, j, k);
            }
            AT(a, stride, i, j) = s * inv_l_jj;
        }
    }
    return 1;
}

/* x = (L L^T)^-1 b with the factor in the lower triangle; x may alias b. */
TVO_SHAPE_BODY void cholesky_substitute_shape(const tvo_real_t *l, const unsigned stride, const unsigned n,
                                              const tvo_real_t *b, tvo_real_t *x)
{
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < n; ++i) {
        tvo_real_t s = b[i];
        for (unsigned k = 0; k < i; ++k) {
            s -= AT(l, stride, i, k) * x[k];
        }
        x[i] = s / AT(l, stride, i, i);
    }
    TVO_UNROLL_SMALL
    for (unsigned ii = n; ii > 0u; --ii) {
        const unsigned i = ii - 1u;
        tvo_real_t s = x[i];
        for (unsigned k = i + 1u; k < n; ++k) {
            s -= AT(l, stride, k, i) * x[k];
        }
        x[i] = s / AT(l, stride, i, i);
    }
}

/* The primal blocks of the common shapes (one robot, two) with the matrix's own stride. */
static int cholesky_factor(tvo_real_t *a, unsigned stride, unsigned n)
{
#if TVO_SHAPE_COPIES
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_OUTPUT_DIM) {
        return cholesky_factor_shape(a, TVO_MAX_Z_DIM, TVO_SHAPE_OUTPUT_DIM);
    }
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_PAIR_OUTPUT_DIM) {
        return cholesky_factor_shape(a, TVO_MAX_Z_DIM, TVO_SHAPE_PAIR_OUTPUT_DIM);
    }
#endif
    return cholesky_factor_shape(a, stride, n);
}

static void cholesky_substitute(const tvo_real_t *l, unsigned stride, unsigned n, const tvo_real_t *b, tvo_real_t *x)
{
#if TVO_SHAPE_COPIES
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_OUTPUT_DIM) {
        cholesky_substitute_shape(l, TVO_MAX_Z_DIM, TVO_SHAPE_OUTPUT_DIM, b, x);
        return;
    }
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_PAIR_OUTPUT_DIM) {
        cholesky_substitute_shape(l, TVO_MAX_Z_DIM, TVO_SHAPE_PAIR_OUTPUT_DIM, b, x);
        return;
    }
#endif
    cholesky_substitute_shape(l, stride, n, b, x);
}

static int all_finite(const tvo_real_t *v, unsigned n)
{
    /* v * 0 is NaN exactly for an infinite or NaN v: one test for the lot, no branch per entry. */
    tvo_real_t probe = TVO_R(0.0);
    for (unsigned i = 0; i < n; ++i) {
        probe += v[i] * TVO_R(0.0);
    }
    return isfinite(probe);
}

tvo_status_t tvo_cholesky_solve(tvo_matrix_t a, uint8_t n, const tvo_real_t *b, tvo_real_t *x)
{
    if (a == NULL || b == NULL || x == NULL) {
        return TVO_ERR_NULL;
    }
    if (n == 0u || n > TVO_MAX_Z_DIM) {
        return TVO_ERR_DIMENSION;
    }
    for (uint8_t i = 0; i < n; ++i) {
        if (!isfinite(a[i][i])) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    if (!cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n)) {
        return TVO_ERR_NOT_POSITIVE_DEFINITE;
    }
    cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, n, b, x);
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
}

/* Factors P + mu I in place (p = the primal block of a), smallest workable mu first. */
static tvo_status_t regularized_factor(tvo_real_t (*a)[TVO_MAX_Z_DIM], uint8_t n, tvo_real_t *diag,
                                       tvo_real_t *shift)
{
    /* The factor overwrites the lower triangle and the diagonal: keep the diagonal, and let the strict
     * upper triangle (never written) be the pristine copy the retries restore from. */
    for (uint8_t i = 0; i < n; ++i) {
        diag[i] = a[i][i];
    }
    *shift = TVO_R(0.0);
    /* The factor reads the lower triangle: the upper one (symmetric input) stays as the copy. */
    if (cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n)) {
        return TVO_OK; /* the usual case: positive definite, no shift */
    }
    tvo_real_t scale = TVO_R(1.0);
    tvo_real_t gershgorin = TVO_R(0.0);
    for (uint8_t i = 0; i < n; ++i) {
        if (TVO_FABS(diag[i]) > scale) {
            scale = TVO_FABS(diag[i]);
        }
        tvo_real_t off = TVO_R(0.0);
        for (uint8_t j = 0; j < n; ++j) {
            off += (j == i) ? TVO_R(0.0) : TVO_FABS(j > i ? a[i][j] : a[j][i]);
        }
        /* Shift that makes row i strictly diagonally dominant with a positive diagonal. */
        const tvo_real_t need = off - diag[i];
        if (need > gershgorin) {
            gershgorin = need;
        }
    }
    tvo_real_t mu = LADDER_FIRST_SCALE * scale;
    for (uint8_t attempt = 1u; attempt <= LADDER_STEPS + 1u; ++attempt) {
        if (attempt == LADDER_STEPS + 1u) {
            /* Strict diagonal dominance with a margin that survives rounding and the pivot floor:
             * positive definite in floating point, not only in exact arithmetic. */
            mu = gershgorin + LADDER_FIRST_SCALE * scale +
                 TVO_R(128.0) * TVO_EPSILON * (tvo_real_t)n * (scale + gershgorin);
        }
        for (uint8_t i = 0; i < n; ++i) {
            a[i][i] = diag[i] + mu;
            for (uint8_t j = 0; j < i; ++j) {
                a[i][j] = a[j][i];
            }
        }
        if (cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n)) {
            *shift = mu;
            return TVO_OK;
        }
        mu *= TVO_R(10.0);
    }
    return TVO_ERR_NOT_POSITIVE_DEFINITE;
}

static tvo_status_t saddle_solve(tvo_real_t (*a)[TVO_MAX_Z_DIM], uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                 tvo_real_t *x, tvo_real_t *shift, tvo_solve_scratch_t *scratch);

tvo_status_t tvo_saddle_solve(tvo_matrix_t a, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b, tvo_real_t *x,
                              tvo_real_t *shift)
{
    tvo_solve_scratch_t scratch;
    return saddle_solve(a, primal_n, dual_n, b, x, shift, &scratch);
}

/* A diagonal positive definite P without equalities (tracking alone: W) needs no factor. 1 if solved
 * (x written), 0 if a is not such a matrix; NaN off the diagonal is not 0, so not diagonal. */
TVO_SHAPE_BODY int diagonal_solve_shape(tvo_real_t (*a)[TVO_MAX_Z_DIM], const uint8_t n, const tvo_real_t *b,
                                        tvo_real_t *x)
{
    tvo_real_t probe = TVO_R(0.0); /* v * 0 is NaN exactly for a v that is not finite */
    TVO_UNROLL_SMALL
    for (uint8_t i = 0; i < n; ++i) {
        const tvo_real_t *row = a[i];
        TVO_UNROLL_SMALL
        for (uint8_t j = 0; j < n; ++j) {
            if (j != i && row[j] != TVO_R(0.0)) {
                return 0;
            }
        }
        if (!(row[i] > TVO_R(0.0))) {
            return 0; /* not positive definite: the general path says which */
        }
        probe += row[i] * TVO_R(0.0); /* each alone: a finite sum of the two could overflow */
        probe += b[i] * TVO_R(0.0);
    }
    if (!isfinite(probe)) {
        return 0; /* the general path names the entry that is not finite */
    }
    TVO_UNROLL_SMALL
    for (uint8_t i = 0; i < n; ++i) {
        x[i] = b[i] / a[i][i];
    }
    return 1;
}

static int diagonal_solve(tvo_real_t (*a)[TVO_MAX_Z_DIM], uint8_t n, const tvo_real_t *b, tvo_real_t *x)
{
#if TVO_SHAPE_COPIES
    if (n == TVO_SHAPE_OUTPUT_DIM) {
        return diagonal_solve_shape(a, TVO_SHAPE_OUTPUT_DIM, b, x);
    }
#endif
    return diagonal_solve_shape(a, n, b, x);
}

/* b must not be one of the scratch's vectors other than dense. */
static tvo_status_t saddle_solve(tvo_real_t (*a)[TVO_MAX_Z_DIM], uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                 tvo_real_t *x, tvo_real_t *shift, tvo_solve_scratch_t *scratch)
{
    if (a == NULL || b == NULL || x == NULL) {
        return TVO_ERR_NULL;
    }
    const uint8_t n = (uint8_t)(primal_n + dual_n);
    if (primal_n == 0u || dual_n > TVO_MAX_EQUALITIES || (unsigned)primal_n + dual_n > TVO_MAX_Z_DIM) {
        return TVO_ERR_DIMENSION;
    }
    if (shift != NULL) {
        *shift = TVO_R(0.0);
    }
    if (dual_n == 0u && diagonal_solve(a, n, b, x)) {
        return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
    }
    for (uint8_t i = 0; i < n; ++i) {
        if (!all_finite(a[i], n) || !isfinite(b[i])) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    tvo_real_t mu = TVO_R(0.0);
    tvo_status_t st = regularized_factor(a, primal_n, scratch->diag, &mu);
    if (st != TVO_OK) {
        return st;
    }
    if (shift != NULL) {
        *shift = mu;
    }
    /* u = P^-1 b_p; then, with equalities, Y = P^-1 C^T and S w = C u - b_d, x_p = u - Y w. */
    if (dual_n == 0u) {
        cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, b, x);
        return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
    }
#if TVO_MAX_EQUALITIES > 0
    tvo_real_t *u = scratch->first;
    cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, b, u);
    tvo_real_t(*y_cols)[TVO_MAX_Z_DIM] = scratch->columns;
    tvo_real_t(*schur)[TVO_SOLVE_SMALL_DIM] = scratch->small;
    tvo_real_t *rhs = scratch->small_rhs;
    tvo_real_t *w = scratch->small_x;
    for (uint8_t q = 0; q < dual_n && q < TVO_MAX_EQUALITIES; ++q) {
        cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, a[primal_n + q], y_cols[q]);
    }
    for (uint8_t q = 0; q < dual_n && q < TVO_MAX_EQUALITIES; ++q) {
        const tvo_real_t *c_row = a[primal_n + q];
        tvo_real_t s = -b[primal_n + q];
        for (uint8_t i = 0; i < primal_n; ++i) {
            s += c_row[i] * u[i];
        }
        rhs[q] = s;
        for (uint8_t r = 0; r < dual_n && r < TVO_MAX_EQUALITIES; ++r) {
            tvo_real_t v = -a[primal_n + q][primal_n + r];
            for (uint8_t i = 0; i < primal_n; ++i) {
                v += c_row[i] * y_cols[r][i];
            }
            schur[q][r] = v;
        }
    }
    /* The Schur complement is symmetric in exact arithmetic; average away the rounding. */
    symmetrize(&schur[0][0], TVO_SOLVE_SMALL_DIM, dual_n);
    if (!cholesky_factor(&schur[0][0], TVO_SOLVE_SMALL_DIM, dual_n)) {
        return TVO_ERR_NOT_POSITIVE_DEFINITE;
    }
    cholesky_substitute(&schur[0][0], TVO_SOLVE_SMALL_DIM, dual_n, rhs, w);
    for (uint8_t i = 0; i < primal_n; ++i) {
        tvo_real_t s = u[i];
        for (uint8_t q = 0; q < dual_n && q < TVO_MAX_EQUALITIES; ++q) {
            s -= y_cols[q][i] * w[q];
        }
        x[i] = s;
    }
    for (uint8_t q = 0; q < dual_n; ++q) {
        x[primal_n + q] = w[q];
    }
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
#else
    return TVO_ERR_DIMENSION; /* unreachable: dual_n <= TVO_MAX_EQUALITIES was checked above */
#endif
}

void tvo_hessian_clear(tvo_hessian_t *h, uint8_t n)
{
    for (unsigned i = 0; i < n && i < TVO_MAX_Z_DIM; ++i) {
        for (unsigned j = 0; j < n && j < TVO_MAX_Z_DIM; ++j) {
            h->matrix[i][j] = TVO_R(0.0);
        }
    }
    h->rank_one_count = 0u;
#if TVO_BLOCK_SOLVE
    h->plan = NULL;
#endif
}

#if TVO_BLOCK_SOLVE
void tvo_hessian_clear_blocks(tvo_hessian_t *h, const tvo_solve_plan_t *plan)
{
    block_clear(h->matrix, plan);
    h->rank_one_count = 0u;
    h->plan = plan;
}

/* regularized_factor over a plan's blocks (h->plan): the same ladder, each attempt restoring and
 * factoring only the blocks; the multipliers' blocks follow the robots' in the same factor. */
static tvo_status_t block_regularized_factor(tvo_hessian_t *h, tvo_real_t *shift)
{
    const tvo_solve_plan_t *plan = h->plan;
    tvo_real_t(*a)[TVO_MAX_Z_DIM] = h->matrix;
    tvo_real_t *diag = h->scratch.diag;
    block_prepare(a, plan, diag);
    *shift = TVO_R(0.0);
    block_factor_result_t result = block_factor(a, plan, diag, TVO_R(0.0));
    if (result == BLOCK_FACTORED) {
        return TVO_OK; /* the usual case */
    }
    /* A pivot failed: an entry that is not finite fails one, so that is checked here, not before. */
    if (!block_pattern_finite(a, plan, diag)) {
        return TVO_ERR_NOT_FINITE;
    }
    tvo_real_t scale = TVO_R(1.0);
    tvo_real_t gershgorin = TVO_R(0.0);
    block_gershgorin(a, plan, diag, h->scratch.first, &scale, &gershgorin);
    const unsigned n = 2u * plan->primal_nodes;
    tvo_real_t mu = LADDER_FIRST_SCALE * scale;
    for (uint8_t attempt = 1u; result == BLOCK_PRIMAL_PIVOT && attempt <= LADDER_STEPS + 1u; ++attempt) {
        if (attempt == LADDER_STEPS + 1u) {
            mu = gershgorin + LADDER_FIRST_SCALE * scale +
                 TVO_R(128.0) * TVO_EPSILON * (tvo_real_t)n * (scale + gershgorin);
        }
        block_restore(a, plan, diag, mu);
        result = block_factor(a, plan, diag, mu);
        if (result == BLOCK_FACTORED) {
            *shift = mu;
            return TVO_OK;
        }
        mu *= TVO_R(10.0);
    }
    return TVO_ERR_NOT_POSITIVE_DEFINITE; /* the ladder's end, or dependent equalities */
}

/* saddle_solve over h's plan; b must not be the scratch's diag or first. */
static tvo_status_t block_saddle_solve(tvo_hessian_t *h, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                       tvo_real_t *x, tvo_real_t *shift)
{
    const unsigned n = (unsigned)primal_n + dual_n;
    if (2u * h->plan->primal_nodes != primal_n || 2u * h->plan->node_count != n) {
        return TVO_ERR_DIMENSION;
    }
    if (shift != NULL) {
        *shift = TVO_R(0.0);
    }
    if (!all_finite(b, n)) {
        return TVO_ERR_NOT_FINITE;
    }
    tvo_real_t mu = TVO_R(0.0);
    const tvo_status_t st = block_regularized_factor(h, &mu);
    if (st != TVO_OK) {
        return st;
    }
    if (shift != NULL) {
        *shift = mu;
    }
    block_substitute(h->matrix, h->plan, b, x);
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
}
#endif

/* The part's curvature into the matrix and its gradient jets into grad (when not NULL), for a part
 * of count entries. */
TVO_SHAPE_BODY void add_part_shape(const tvo_rank_one_t *part, tvo_matrix_t m, tvo_jet_t *grad, const unsigned count,
                                   const uint8_t order)
{
#if TVO_SHAPE_COPIES
    /* For speed, the part read once into registers (a store into m or grad could otherwise be a
     * store into the part, as far as the compiler knows; the part must not overlap them). */
    unsigned index[TVO_RANK_ONE_MAX_ENTRIES] = {0u};
    tvo_real_t value[TVO_RANK_ONE_MAX_ENTRIES] = {TVO_R(0.0)};
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < count; ++i) {
        index[i] = part->index[i];
        value[i] = part->value[i];
    }
#else
    const uint8_t *index = part->index; /* for size: read where it is */
    const tvo_real_t *value = part->value;
#endif
    const tvo_real_t weight = part->weight;
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < count; ++i) {
        const tvo_real_t wi = weight * value[i];
        tvo_real_t *row = m[index[i]];
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < count; ++j) {
            row[index[j]] += wi * value[j];
        }
        if (grad != NULL) {
            tvo_jet_axpy(value[i], &part->gradient, order, &grad[index[i]]);
        }
    }
}

static void add_into_matrix(const tvo_rank_one_t *part, tvo_matrix_t m, tvo_jet_t *grad, uint8_t order)
{
    add_part_shape(part, m, grad, part->count, order);
}

void tvo_rank_one_add_to(const tvo_rank_one_t *part, tvo_matrix_t m, tvo_jet_t *grad, uint8_t order)
{
    if (part == NULL || m == NULL || part->count > TVO_RANK_ONE_MAX_ENTRIES) {
        return;
    }
    add_into_matrix(part, m, grad, order);
}

/* A part's size weight |u|^2 (what decides whether it is stiff), for a part of count entries. */
TVO_SHAPE_BODY tvo_real_t rank_one_size_shape(const tvo_rank_one_t *part, const unsigned count)
{
    tvo_real_t norm_sq = TVO_R(0.0);
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < count; ++i) {
        norm_sq += part->value[i] * part->value[i];
    }
    return part->weight * norm_sq;
}

static tvo_real_t rank_one_size(const tvo_rank_one_t *part)
{
    return rank_one_size_shape(part, part->count);
}

void tvo_hessian_add_part(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad, uint8_t order)
{
    if (h == NULL || part == NULL || part->count > TVO_RANK_ONE_MAX_ENTRIES) {
        return;
    }
    if (!(part->weight > TVO_R(0.0))) {
        add_into_matrix(part, h->matrix, grad, order); /* only positive curvature can be solved apart */
        return;
    }
    if (h->rank_one_count < TVO_MAX_RANK_ONE_PARTS) {
        h->rank_one[h->rank_one_count++] = *part;
        return;
    }
    /* Full: the smallest of the kept parts and the new one goes into the matrix. */
    unsigned smallest = 0u;
    for (unsigned k = 1u; k < TVO_MAX_RANK_ONE_PARTS; ++k) {
        if (rank_one_size(&h->rank_one[k]) < rank_one_size(&h->rank_one[smallest])) {
            smallest = k;
        }
    }
    if (rank_one_size(part) > rank_one_size(&h->rank_one[smallest])) {
        add_into_matrix(&h->rank_one[smallest], h->matrix, grad, order);
        h->rank_one[smallest] = *part;
    } else {
        add_into_matrix(part, h->matrix, grad, order);
    }
}

/* tvo_hessian_add for a valid part of count entries. */
TVO_SHAPE_BODY void hessian_add_shape(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad,
                                      const unsigned count, const uint8_t order)
{
    /* Stiff: size > TVO_STIFF_RATIO max(1, |h_ii|) over its indices (an entry that is not a number passed
     * over), asked as size > ratio and then > ratio |h_ii| for each: the same comparison (ratio times the
     * maximum is the maximum of ratio times each), which a part far from stiff fails at once. */
    const tvo_real_t size = rank_one_size_shape(part, count);
    int stiff = size > TVO_STIFF_RATIO;
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < count; ++i) {
        stiff = stiff && !(size <= TVO_STIFF_RATIO * TVO_FABS(h->matrix[part->index[i]][part->index[i]]));
    }
    if (stiff) {
        tvo_hessian_add_part(h, part, grad, order);
    } else {
        add_part_shape(part, h->matrix, grad, count, order);
    }
}

void tvo_hessian_add(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad, uint8_t order)
{
    if (h == NULL || part == NULL || part->count > TVO_RANK_ONE_MAX_ENTRIES) {
        return;
    }
#if TVO_SHAPE_COPIES
    /* A plane's part has 2 entries (one robot), a distance bound's 4 (two robots). */
    if (order == TVO_SHAPE_ORDER && part->count == 2u) {
        hessian_add_shape(h, part, grad, 2u, TVO_SHAPE_ORDER);
        return;
    }
    if (order == TVO_SHAPE_ORDER && part->count == 4u) {
        hessian_add_shape(h, part, grad, 4u, TVO_SHAPE_ORDER);
        return;
    }
#endif
    hessian_add_shape(h, part, grad, part->count, order);
}

#if TVO_BLOCK_SOLVE
/* size > TVO_STIFF_RATIO max(1, |d_i|) (hessian_add_shape's test, in its order of questions). */
static int stiff_against(tvo_real_t size, tvo_real_t d0, tvo_real_t d1, tvo_real_t d2, tvo_real_t d3)
{
    return size > TVO_STIFF_RATIO && !(size <= TVO_STIFF_RATIO * TVO_FABS(d0)) &&
           !(size <= TVO_STIFF_RATIO * TVO_FABS(d1)) && !(size <= TVO_STIFF_RATIO * TVO_FABS(d2)) &&
           !(size <= TVO_STIFF_RATIO * TVO_FABS(d3));
}

int tvo_hessian_add_pair(tvo_hessian_t *h, uint8_t a, uint8_t b, const tvo_real_t e[2], tvo_real_t along_weight,
                         tvo_real_t across_weight)
{
    if (h == NULL || e == NULL || h->plan == NULL || (unsigned)a + 2u > TVO_MAX_Z_DIM ||
        (unsigned)b + 2u > TVO_MAX_Z_DIM) {
        return 0;
    }
    tvo_real_t *a0 = h->matrix[a];
    tvo_real_t *a1 = h->matrix[a + 1u];
    tvo_real_t *b0 = h->matrix[b];
    tvo_real_t *b1 = h->matrix[b + 1u];
    const tvo_real_t e0 = e[0];
    const tvo_real_t e1 = e[1];
    /* Each part judged as hessian_add_shape judges it, |v|^2 summed in its order: the one along e against
     * the diagonal as it is, the one across against the diagonal with the first added. */
    const tvo_real_t e00 = e0 * e0;
    const tvo_real_t e11 = e1 * e1;
    const tvo_real_t w00 = along_weight * e0 * e0;
    const tvo_real_t w11 = along_weight * e1 * e1;
    if (stiff_against(along_weight * (((e00 + e11) + e00) + e11), a0[a], a1[a + 1u], b0[b], b1[b + 1u]) ||
        stiff_against(across_weight * (((e11 + e00) + e11) + e00), a0[a] + w00, a1[a + 1u] + w11, b0[b] + w00,
                      b1[b + 1u] + w11)) {
        return 0;
    }
    /* B = w_along e e^T + w_across e_perp e_perp^T: its three entries, once for the four blocks. */
    const tvo_real_t b00 = w00 + across_weight * e1 * e1;
    const tvo_real_t b01 = (along_weight - across_weight) * e0 * e1;
    const tvo_real_t b11 = w11 + across_weight * e0 * e0;
    a0[a] += b00;
    a0[a + 1u] += b01;
    a1[a] += b01;
    a1[a + 1u] += b11;
    b0[b] += b00;
    b0[b + 1u] += b01;
    b1[b] += b01;
    b1[b + 1u] += b11;
    a0[b] -= b00;
    a0[b + 1u] -= b01;
    a1[b] -= b01;
    a1[b + 1u] -= b11;
    b0[a] -= b00;
    b0[a + 1u] -= b01;
    b1[a] -= b01;
    b1[a + 1u] -= b11;
    return 1;
}
#endif

void tvo_hessian_settle(tvo_hessian_t *h, uint8_t n, uint8_t dual_n, tvo_jet_t *grad, uint8_t order)
{
    if (h == NULL || h->rank_one_count == 0u) {
        return;
    }
    tvo_real_t scale = TVO_R(1.0);
    for (unsigned i = 0; i < n && i < TVO_MAX_Z_DIM; ++i) {
        if (TVO_FABS(h->matrix[i][i]) > scale) {
            scale = TVO_FABS(h->matrix[i][i]);
        }
    }
    unsigned kept = 0u;
    for (unsigned k = 0; k < h->rank_one_count && k < TVO_MAX_RANK_ONE_PARTS; ++k) {
        const tvo_rank_one_t *part = &h->rank_one[k];
        if (dual_n == 0u && rank_one_size(part) > TVO_STIFF_RATIO * scale) {
            if (kept != k) {
                h->rank_one[kept] = *part;
            }
            kept++;
        } else {
            add_into_matrix(part, h->matrix, grad, order);
        }
    }
    h->rank_one_count = (uint8_t)kept;
}

/* x = A^-1 b with h's factor (its plan's, or the dense one's in the lower triangle); x may alias b. */
static void substitute_factor(tvo_hessian_t *h, unsigned n, const tvo_real_t *b, tvo_real_t *x)
{
#if TVO_BLOCK_SOLVE
    if (h->plan != NULL) {
        block_substitute(h->matrix, h->plan, b, x);
        return;
    }
#endif
    cholesky_substitute(&h->matrix[0][0], TVO_MAX_Z_DIM, n, b, x);
}

/* y = A^-1 u for a sparse u, with h's factor. */
static void substitute_sparse(tvo_hessian_t *h, unsigned n, const tvo_rank_one_t *part, tvo_real_t *dense,
                              tvo_real_t *y)
{
    for (unsigned i = 0; i < n; ++i) {
        dense[i] = TVO_R(0.0);
    }
    for (unsigned i = 0; i < part->count; ++i) {
        dense[part->index[i]] += part->value[i];
    }
    substitute_factor(h, n, dense, y);
}

static tvo_real_t dot_sparse(const tvo_rank_one_t *part, const tvo_real_t *v)
{
    tvo_real_t sum = TVO_R(0.0);
    for (unsigned i = 0; i < part->count; ++i) {
        sum += part->value[i] * v[part->index[i]];
    }
    return sum;
}

/* The matrix restored from its upper triangle and diag (a factor overwrote it), the parts and their
 * right-hand sides added in, and the sum solved as tvo_saddle_solve does. */
static tvo_status_t solve_parts_added(tvo_hessian_t *h, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                      const tvo_real_t *gamma, tvo_real_t *x, tvo_real_t *shift)
{
    const unsigned n = primal_n;
    const tvo_real_t *diag = h->scratch.diag;
    tvo_real_t *dense_b = h->scratch.dense;
    for (unsigned i = 0; i < n && i < TVO_MAX_Z_DIM; ++i) {
        dense_b[i] = b[i];
    }
#if TVO_BLOCK_SOLVE
    if (h->plan != NULL) {
        block_restore(h->matrix, h->plan, diag, TVO_R(0.0));
    } else
#endif
    {
        for (unsigned i = 0; i < n && i < TVO_MAX_Z_DIM; ++i) {
            h->matrix[i][i] = diag[i];
            for (unsigned j = 0; j < i; ++j) {
                h->matrix[i][j] = h->matrix[j][i];
            }
        }
    }
    for (unsigned k = 0; k < h->rank_one_count && k < TVO_MAX_RANK_ONE_PARTS; ++k) {
        const tvo_rank_one_t *part = &h->rank_one[k];
        add_into_matrix(part, h->matrix, NULL, 0u);
        for (unsigned i = 0; i < part->count; ++i) {
            dense_b[part->index[i]] += gamma[k] * part->value[i];
        }
    }
    h->rank_one_count = 0u;
#if TVO_BLOCK_SOLVE
    if (h->plan != NULL) {
        return block_saddle_solve(h, primal_n, dual_n, dense_b, x, shift);
    }
#endif
    return saddle_solve(h->matrix, primal_n, dual_n, dense_b, x, shift, &h->scratch);
}

tvo_status_t tvo_saddle_solve_split(tvo_hessian_t *h, uint8_t primal_n, uint8_t dual_n, const tvo_real_t *b,
                                    const tvo_real_t *gamma, tvo_real_t *x, tvo_real_t *shift)
{
    if (h == NULL || b == NULL || x == NULL) {
        return TVO_ERR_NULL;
    }
    const unsigned parts = h->rank_one_count;
    if (primal_n == 0u || (unsigned)primal_n + dual_n > TVO_MAX_Z_DIM || parts > TVO_MAX_RANK_ONE_PARTS ||
        (parts > 0u && (gamma == NULL || dual_n > 0u))) {
        return parts > 0u && gamma == NULL ? TVO_ERR_NULL : TVO_ERR_DIMENSION;
    }
#if TVO_BLOCK_SOLVE
    const int blocks = h->plan != NULL;
    if (blocks && parts == 0u) {
        return block_saddle_solve(h, primal_n, dual_n, b, x, shift);
    }
#else
    const int blocks = 0;
#endif
    if (parts == 0u) {
        return saddle_solve(h->matrix, primal_n, dual_n, b, x, shift, &h->scratch);
    }
    const unsigned n = primal_n;
    for (unsigned i = 0; i < n; ++i) {
        /* The dense matrix is checked entry by entry; the blocks' factor fails on what is not finite. */
        if ((!blocks && !all_finite(h->matrix[i], n)) || !isfinite(b[i])) {
            return TVO_ERR_NOT_FINITE;
        }
    }
    if (!all_finite(gamma, parts)) {
        return TVO_ERR_NOT_FINITE;
    }
    /* The soft part alone: if it is positive definite the stiff parts are solved apart, exactly. */
    tvo_solve_scratch_t *scratch = &h->scratch;
#if TVO_BLOCK_SOLVE
    if (blocks) {
        if (2u * h->plan->primal_nodes != n || h->plan->node_count != h->plan->primal_nodes) {
            return TVO_ERR_DIMENSION;
        }
        block_prepare(h->matrix, h->plan, scratch->diag);
        if (block_factor(h->matrix, h->plan, scratch->diag, TVO_R(0.0)) != BLOCK_FACTORED) {
            return solve_parts_added(h, primal_n, dual_n, b, gamma, x, shift);
        }
    } else
#endif
    {
        for (unsigned i = 0; i < n; ++i) {
            scratch->diag[i] = h->matrix[i][i];
        }
        if (!cholesky_factor(&h->matrix[0][0], TVO_MAX_Z_DIM, n)) {
            return solve_parts_added(h, primal_n, dual_n, b, gamma, x, shift);
        }
    }
    if (shift != NULL) {
        *shift = TVO_R(0.0);
    }
    /* With z = A^-1 b, Y = A^-1 U and C = S^-1 + U^T Y (S = diag(weights)):
     *   x = z + Y C^-1 (S^-1 gamma - U^T z),
     * (Woodbury for b, push-through for U gamma) where every term is of the solution's own size:
     * the stiff right-hand sides enter divided by their weights, never next to the soft ones. */
    tvo_real_t *z = scratch->first;
    tvo_real_t(*y_cols)[TVO_MAX_Z_DIM] = scratch->columns;
    tvo_real_t(*capacitance)[TVO_SOLVE_SMALL_DIM] = scratch->small;
    tvo_real_t *rhs = scratch->small_rhs;
    tvo_real_t *w = scratch->small_x;
    substitute_factor(h, n, b, z);
    for (unsigned k = 0; k < parts; ++k) {
        substitute_sparse(h, n, &h->rank_one[k], scratch->dense, y_cols[k]);
    }
    for (unsigned k = 0; k < parts; ++k) {
        const tvo_real_t inv_weight = TVO_R(1.0) / h->rank_one[k].weight;
        rhs[k] = gamma[k] * inv_weight - dot_sparse(&h->rank_one[k], z);
        for (unsigned l = 0; l < parts; ++l) {
            capacitance[k][l] = dot_sparse(&h->rank_one[k], y_cols[l]);
        }
        capacitance[k][k] += inv_weight;
    }
    symmetrize(&capacitance[0][0], TVO_SOLVE_SMALL_DIM, parts);
    if (!cholesky_factor(&capacitance[0][0], TVO_SOLVE_SMALL_DIM, parts)) {
        /* Nearly dependent directions (three planes of one robot in the plane): solve the sum. */
        return solve_parts_added(h, primal_n, dual_n, b, gamma, x, shift);
    }
    cholesky_substitute(&capacitance[0][0], TVO_SOLVE_SMALL_DIM, parts, rhs, w);
    for (unsigned i = 0; i < n; ++i) {
        tvo_real_t sum = z[i];
        for (unsigned k = 0; k < parts; ++k) {
            sum += y_cols[k][i] * w[k];
        }
        x[i] = sum;
    }
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
}
