/* Fixed-size Cholesky and saddle-point solves; see tvo/linsolve.h. */
#include "internal/linsolve.h"

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

#if TVO_SHAPE_COPIES /* the dense loops serve the common shapes' copies only */
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
#endif

/* Row i's envelope starts at first[i], the column of its first nonzero left of the diagonal (i if
 * none). The factor is zero left of it too (Cholesky fills in only right of a row's first nonzero),
 * so every product a dense loop would take there is a zero: skipping them changes no nonzero digit
 * (at most a zero's sign). A ring of distance bounds couples each robot with two others only. */
static unsigned envelope_start(const tvo_real_t *row, const unsigned i)
{
    unsigned k = 0;
    while (k < i && row[k] == TVO_R(0.0)) { /* NaN is not 0: it stays in, as in the dense loops */
        ++k;
    }
    return k;
}

/* cholesky_factor_shape for a run-time size, row by row over each row's envelope: every entry the
 * same sum in the same order times the same reciprocal of its pivot. */
static int cholesky_factor_envelope(tvo_real_t *a, const unsigned stride, const unsigned n, uint8_t *first)
{
    tvo_real_t inv_pivot[TVO_MAX_Z_DIM];
    for (unsigned i = 0; i < n && i < TVO_MAX_Z_DIM; ++i) {
        tvo_real_t *row_i = &AT(a, stride, i, 0);
        const unsigned first_i = envelope_start(row_i, i);
        first[i] = (uint8_t)first_i;
        for (unsigned j = first_i; j < i; ++j) {
            const tvo_real_t *row_j = &AT(a, stride, j, 0);
            tvo_real_t s = row_i[j];
            for (unsigned k = first_i > first[j] ? first_i : first[j]; k < j; ++k) {
                s -= row_i[k] * row_j[k];
            }
            row_i[j] = s * inv_pivot[j];
        }
        const tvo_real_t diagonal = row_i[i];
        tvo_real_t d = diagonal;
        for (unsigned k = first_i; k < i; ++k) {
            d -= row_i[k] * row_i[k];
        }
        if (!(diagonal > TVO_R(0.0)) || !(d > TVO_R(64.0) * TVO_EPSILON * diagonal)) {
            return 0;
        }
        const tvo_real_t l_ii = TVO_SQRT(d);
        inv_pivot[i] = TVO_R(1.0) / l_ii;
        row_i[i] = l_ii;
    }
    return 1;
}

/* cholesky_substitute_shape for a run-time size, over the envelope the factor found (first). */
static void cholesky_substitute_envelope(const tvo_real_t *l, const unsigned stride, const unsigned n,
                                         const uint8_t *first, const tvo_real_t *b, tvo_real_t *x)
{
    for (unsigned i = 0; i < n; ++i) {
        const tvo_real_t *row = &AT(l, stride, i, 0);
        tvo_real_t s = b[i];
        for (unsigned k = first[i]; k < i; ++k) {
            s -= row[k] * x[k];
        }
        x[i] = s / row[i];
    }
    for (unsigned ii = n; ii > 0u; --ii) {
        const unsigned i = ii - 1u;
        const tvo_real_t *column = &AT(l, stride, i, i); /* L_ki for k = i, i + 1, ... */
        tvo_real_t s = x[i];
        for (unsigned k = i + 1u; k < n; ++k) {
            column += stride;
            if (first[k] <= i) {
                s -= *column * x[k];
            }
        }
        x[i] = s / AT(l, stride, i, i);
    }
}

/* The primal blocks of the common shapes (one robot, two) with the matrix's own stride, dense; any
 * other size over its envelope, which the factor writes to first (TVO_MAX_Z_DIM entries) for the
 * substitutions with that factor. */
static int cholesky_factor(tvo_real_t *a, unsigned stride, unsigned n, uint8_t *first)
{
#if TVO_SHAPE_COPIES
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_OUTPUT_DIM) {
        return cholesky_factor_shape(a, TVO_MAX_Z_DIM, TVO_SHAPE_OUTPUT_DIM);
    }
    if (stride == TVO_MAX_Z_DIM && n == TVO_SHAPE_PAIR_OUTPUT_DIM) {
        return cholesky_factor_shape(a, TVO_MAX_Z_DIM, TVO_SHAPE_PAIR_OUTPUT_DIM);
    }
#endif
    return cholesky_factor_envelope(a, stride, n, first);
}

static void cholesky_substitute(const tvo_real_t *l, unsigned stride, unsigned n, const uint8_t *first,
                                const tvo_real_t *b, tvo_real_t *x)
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
    cholesky_substitute_envelope(l, stride, n, first, b, x);
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

/* 1 if the leading n x n block of a and b[0..n-1] are finite. Their sum is finite only then (an
 * infinity or NaN cannot cancel to a finite sum): one addition per entry; only a sum that overflowed
 * is settled entry by entry. */
static int block_finite(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_real_t *b, unsigned n)
{
    tvo_real_t sum = TVO_R(0.0);
    for (unsigned i = 0; i < n; ++i) {
        const tvo_real_t *row = a[i];
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < n; ++j) {
            sum += row[j];
        }
        sum += b[i];
    }
    if (isfinite(sum)) {
        return 1;
    }
    for (unsigned i = 0; i < n; ++i) {
        if (!all_finite(a[i], n) || !isfinite(b[i])) {
            return 0;
        }
    }
    return 1;
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
    uint8_t first[TVO_MAX_Z_DIM];
    if (!cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n, first)) {
        return TVO_ERR_NOT_POSITIVE_DEFINITE;
    }
    cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, n, first, b, x);
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
}

/* Factors P + mu I in place (p = the primal block of a), smallest workable mu first. */
static tvo_status_t regularized_factor(tvo_real_t (*a)[TVO_MAX_Z_DIM], uint8_t n, tvo_real_t *diag,
                                       tvo_real_t *shift, uint8_t *first)
{
    /* The factor overwrites the lower triangle and the diagonal: keep the diagonal, and let the strict
     * upper triangle (never written) be the pristine copy the retries restore from. */
    for (uint8_t i = 0; i < n; ++i) {
        diag[i] = a[i][i];
    }
    *shift = TVO_R(0.0);
    /* The factor reads the lower triangle: the upper one (symmetric input) stays as the copy. */
    if (cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n, first)) {
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
        if (cholesky_factor(&a[0][0], TVO_MAX_Z_DIM, n, first)) {
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
    if (!block_finite(a, b, n)) {
        return TVO_ERR_NOT_FINITE;
    }
    tvo_real_t mu = TVO_R(0.0);
    uint8_t first[TVO_MAX_Z_DIM]; /* the primal factor's envelope */
    tvo_status_t st = regularized_factor(a, primal_n, scratch->diag, &mu, first);
    if (st != TVO_OK) {
        return st;
    }
    if (shift != NULL) {
        *shift = mu;
    }
    /* u = P^-1 b_p; then, with equalities, Y = P^-1 C^T and S w = C u - b_d, x_p = u - Y w. */
    if (dual_n == 0u) {
        cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, first, b, x);
        return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
    }
#if TVO_MAX_EQUALITIES > 0
    tvo_real_t *u = scratch->first;
    cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, first, b, u);
    tvo_real_t(*y_cols)[TVO_MAX_Z_DIM] = scratch->columns;
    tvo_real_t(*schur)[TVO_SOLVE_SMALL_DIM] = scratch->small;
    tvo_real_t *rhs = scratch->small_rhs;
    tvo_real_t *w = scratch->small_x;
    for (uint8_t q = 0; q < dual_n && q < TVO_MAX_EQUALITIES; ++q) {
        cholesky_substitute(&a[0][0], TVO_MAX_Z_DIM, primal_n, first, a[primal_n + q], y_cols[q]);
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
    uint8_t first_small[TVO_MAX_Z_DIM];
    if (!cholesky_factor(&schur[0][0], TVO_SOLVE_SMALL_DIM, dual_n, first_small)) {
        return TVO_ERR_NOT_POSITIVE_DEFINITE;
    }
    cholesky_substitute(&schur[0][0], TVO_SOLVE_SMALL_DIM, dual_n, first_small, rhs, w);
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
}

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

/* add_part_shape for count (1 or 2) parts of r (tvo_relative_parts_t) starting at first, one after
 * the other: the same sums bit for bit (each entry's additions in the parts' order), each product
 * formed once. Row b + p's weight is -(weight e_p) and column b + q's entry -e_q: negations, which
 * are exact, so every entry's product is +-(weight e_p) e_q. */
TVO_SHAPE_BODY void add_relative_shape(const tvo_relative_parts_t *r, const unsigned first, const unsigned count,
                                       tvo_matrix_t m, tvo_jet_t *grad, const uint8_t order)
{
    const unsigned a = r->offset_a;
    const unsigned b = r->offset_b;
    const unsigned n = TVO_JET_ORDER_IS_CONSTANT_2(order) ? 2u : tvo_jet_order_clamp(order);
    /* The parts read once into registers before any store (r must not overlap m or grad). */
    tvo_real_t e[2][2];
    tvo_real_t g[2][TVO_JET_MAX_ORDER + 1];
    tvo_real_t q[2][2][2]; /* [part][p][q] = (weight e_p) e_q */
    TVO_UNROLL_SMALL
    for (unsigned k = 0; k < count; ++k) {
        e[k][0] = r->direction[first + k][0];
        e[k][1] = r->direction[first + k][1];
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j <= n; ++j) {
            g[k][j] = r->gradient[first + k].c[j];
        }
        TVO_UNROLL_SMALL
        for (unsigned p = 0; p < 2u; ++p) {
            const tvo_real_t wp = r->weight[first + k] * e[k][p];
            q[k][p][0] = wp * e[k][0];
            q[k][p][1] = wp * e[k][1];
        }
    }
    TVO_UNROLL_SMALL
    for (unsigned p = 0; p < 2u; ++p) {
        tvo_real_t *row_a = m[a + p];
        tvo_real_t *row_b = m[b + p];
        TVO_UNROLL_SMALL
        for (unsigned c = 0; c < 2u; ++c) {
            tvo_real_t aa = row_a[a + c];
            tvo_real_t ab = row_a[b + c];
            tvo_real_t ba = row_b[a + c];
            tvo_real_t bb = row_b[b + c];
            TVO_UNROLL_SMALL
            for (unsigned k = 0; k < count; ++k) {
                aa += q[k][p][c];
                ab -= q[k][p][c];
                ba -= q[k][p][c];
                bb += q[k][p][c];
            }
            row_a[a + c] = aa;
            row_a[b + c] = ab;
            row_b[a + c] = ba;
            row_b[b + c] = bb;
        }
    }
    if (grad == NULL) {
        return;
    }
    TVO_UNROLL_SMALL
    for (unsigned p = 0; p < 2u; ++p) {
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j <= n; ++j) {
            tvo_real_t ga = grad[a + p].c[j];
            tvo_real_t gb = grad[b + p].c[j];
            TVO_UNROLL_SMALL
            for (unsigned k = 0; k < count; ++k) {
                const tvo_real_t product = e[k][p] * g[k][j];
                ga += product;
                gb -= product;
            }
            grad[a + p].c[j] = ga;
            grad[b + p].c[j] = gb;
        }
    }
}

/* Part k of r as a rank-one part. */
static void relative_part(const tvo_relative_parts_t *r, unsigned k, tvo_rank_one_t *part)
{
    part->count = 4u;
    part->index[0] = r->offset_a;
    part->index[1] = (uint8_t)(r->offset_a + 1u);
    part->index[2] = r->offset_b;
    part->index[3] = (uint8_t)(r->offset_b + 1u);
    part->value[0] = r->direction[k][0];
    part->value[1] = r->direction[k][1];
    part->value[2] = -r->direction[k][0];
    part->value[3] = -r->direction[k][1];
    part->weight = r->weight[k];
    part->gradient = r->gradient[k];
}

/* tvo_hessian_add for a valid part of count entries; relative (not NULL): the part is relative's
 * part relative_k (tvo_hessian_add_relative), count 4. */
TVO_SHAPE_BODY void hessian_add_shape(tvo_hessian_t *h, const tvo_rank_one_t *part, tvo_jet_t *grad,
                                      const unsigned count, const uint8_t order, const tvo_relative_parts_t *relative,
                                      const unsigned relative_k)
{
    /* The scale is at least 1: a part no larger than TVO_STIFF_RATIO is not stiff, whatever the
     * diagonal (the common case, decided without reading it). */
    const tvo_real_t size = rank_one_size_shape(part, count);
    int stiff = size > TVO_STIFF_RATIO;
    if (stiff) {
        tvo_real_t scale = TVO_R(1.0);
        TVO_UNROLL_SMALL
        for (unsigned i = 0; i < count; ++i) {
            const tvo_real_t d = TVO_FABS(h->matrix[part->index[i]][part->index[i]]);
            scale = d > scale ? d : scale;
        }
        stiff = size > TVO_STIFF_RATIO * scale;
    }
    if (stiff) {
        tvo_hessian_add_part(h, part, grad, order);
    } else if (relative != NULL) {
        add_relative_shape(relative, relative_k, 1u, h->matrix, grad, order);
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
        hessian_add_shape(h, part, grad, 2u, TVO_SHAPE_ORDER, NULL, 0u);
        return;
    }
    if (order == TVO_SHAPE_ORDER && part->count == 4u) {
        hessian_add_shape(h, part, grad, 4u, TVO_SHAPE_ORDER, NULL, 0u);
        return;
    }
#endif
    hessian_add_shape(h, part, grad, part->count, order, NULL, 0u);
}

/* A relative part's size weight |u|^2 as rank_one_size_shape forms it, with u = (e, -e): the squares
 * of -e are those of e. */
static inline tvo_real_t relative_size(const tvo_relative_parts_t *r, unsigned k)
{
    const tvo_real_t e0_sq = r->direction[k][0] * r->direction[k][0];
    const tvo_real_t e1_sq = r->direction[k][1] * r->direction[k][1];
    tvo_real_t norm_sq = TVO_R(0.0);
    norm_sq += e0_sq;
    norm_sq += e1_sq;
    norm_sq += e0_sq;
    norm_sq += e1_sq;
    return r->weight[k] * norm_sq;
}

/* tvo_hessian_add_relative for valid parts. */
TVO_SHAPE_BODY void hessian_add_relative_shape(tvo_hessian_t *h, const tvo_relative_parts_t *r, tvo_jet_t *grad,
                                               const uint8_t order)
{
    /* Parts no larger than TVO_STIFF_RATIO are not stiff whatever the diagonal (hessian_add_shape):
     * both go in together. */
    if (!(relative_size(r, 0u) > TVO_STIFF_RATIO) && !(relative_size(r, 1u) > TVO_STIFF_RATIO)) {
        add_relative_shape(r, 0u, 2u, h->matrix, grad, order);
        return;
    }
    for (unsigned k = 0; k < 2u; ++k) {
        tvo_rank_one_t part;
        relative_part(r, k, &part);
        hessian_add_shape(h, &part, grad, 4u, order, r, k);
    }
}

void tvo_hessian_add_relative(tvo_hessian_t *h, const tvo_relative_parts_t *parts, tvo_jet_t *grad, uint8_t order)
{
    TVO_ASSERT(h != NULL && parts != NULL && parts->offset_a != parts->offset_b);
#if TVO_SHAPE_COPIES
    if (order == TVO_SHAPE_ORDER) {
        hessian_add_relative_shape(h, parts, grad, TVO_SHAPE_ORDER);
        return;
    }
#endif
    hessian_add_relative_shape(h, parts, grad, order);
}

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

/* y = A^-1 u for a sparse u, with A's factor in the lower triangle. */
static void substitute_sparse(const tvo_real_t *factor, unsigned n, const uint8_t *first, const tvo_rank_one_t *part,
                              tvo_real_t *dense, tvo_real_t *y)
{
    for (unsigned i = 0; i < n; ++i) {
        dense[i] = TVO_R(0.0);
    }
    for (unsigned i = 0; i < part->count; ++i) {
        dense[part->index[i]] += part->value[i];
    }
    cholesky_substitute(factor, TVO_MAX_Z_DIM, n, first, dense, y);
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
        h->matrix[i][i] = diag[i];
        dense_b[i] = b[i];
        for (unsigned j = 0; j < i; ++j) {
            h->matrix[i][j] = h->matrix[j][i];
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
    if (parts == 0u) {
        return saddle_solve(h->matrix, primal_n, dual_n, b, x, shift, &h->scratch);
    }
    const unsigned n = primal_n;
    if (!block_finite(h->matrix, b, n)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (!all_finite(gamma, parts)) {
        return TVO_ERR_NOT_FINITE;
    }
    /* The soft part alone: if it is positive definite the stiff parts are solved apart, exactly. */
    tvo_solve_scratch_t *scratch = &h->scratch;
    for (unsigned i = 0; i < n; ++i) {
        scratch->diag[i] = h->matrix[i][i];
    }
    uint8_t first[TVO_MAX_Z_DIM];
    if (!cholesky_factor(&h->matrix[0][0], TVO_MAX_Z_DIM, n, first)) {
        return solve_parts_added(h, primal_n, dual_n, b, gamma, x, shift);
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
    cholesky_substitute(&h->matrix[0][0], TVO_MAX_Z_DIM, n, first, b, z);
    for (unsigned k = 0; k < parts; ++k) {
        substitute_sparse(&h->matrix[0][0], n, first, &h->rank_one[k], scratch->dense, y_cols[k]);
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
    uint8_t first_small[TVO_MAX_Z_DIM];
    if (!cholesky_factor(&capacitance[0][0], TVO_SOLVE_SMALL_DIM, parts, first_small)) {
        /* Nearly dependent directions (three planes of one robot in the plane): solve the sum. */
        return solve_parts_added(h, primal_n, dual_n, b, gamma, x, shift);
    }
    cholesky_substitute(&capacitance[0][0], TVO_SOLVE_SMALL_DIM, parts, first_small, rhs, w);
    for (unsigned i = 0; i < n; ++i) {
        tvo_real_t sum = z[i];
        for (unsigned k = 0; k < parts; ++k) {
            sum += y_cols[k][i] * w[k];
        }
        x[i] = sum;
    }
    return all_finite(x, n) ? TVO_OK : TVO_ERR_NUMERIC;
}
