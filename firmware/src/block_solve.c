/* The block solve's plan and pieces; see internal/block_solve.h and tvo/linsolve.h. */
#include "internal/block_solve.h"

#if TVO_BLOCK_SOLVE

/* ------------------------------------------------------------------------- the plan, at init */

/* A set of nodes as bits, 32 to a word. */
#define SET_WORDS ((TVO_PLAN_MAX_NODES + 31u) / 32u)

static int set_has(const uint32_t *set, unsigned node)
{
    return (set[node / 32u] >> (node % 32u)) & 1u;
}

static void set_add(uint32_t *set, unsigned node)
{
    set[node / 32u] |= (uint32_t)1u << (node % 32u);
}

/* The members of set that are not in done. */
static unsigned count_left(const uint32_t *set, const uint32_t *done)
{
    unsigned count = 0u;
    for (unsigned w = 0; w < SET_WORDS; ++w) {
        uint32_t bits = set[w] & ~done[w];
        for (unsigned b = 0; b < 32u && bits != 0u; ++b) {
            bits &= bits - 1u; /* drops the lowest member */
            ++count;
        }
    }
    return count;
}

/* Of the nodes [from, to) not in done, the one with the fewest neighbours left (the lowest on ties). */
static unsigned least_fill(uint32_t (*adjacent)[SET_WORDS], const uint32_t *done, unsigned from, unsigned to)
{
    unsigned best = to;
    unsigned best_count = 0u;
    for (unsigned v = from; v < to; ++v) {
        if (set_has(done, v)) {
            continue;
        }
        const unsigned count = count_left(adjacent[v], done);
        if (best == to || count < best_count) {
            best = v;
            best_count = count;
        }
    }
    return best;
}

tvo_status_t tvo_solve_plan_build(tvo_solve_plan_t *plan, uint8_t robots, uint8_t offsets, uint8_t first_multiplier,
                                  const uint8_t *pairs, uint16_t pair_count)
{
    TVO_ASSERT(plan != NULL && (pairs != NULL || pair_count == 0u));
    plan->node_count = 0u;
    plan->primal_nodes = 0u;
    const unsigned nodes = (unsigned)robots + offsets;
    if (robots == 0u || nodes > TVO_PLAN_MAX_NODES || 2u * robots > first_multiplier ||
        (unsigned)first_multiplier + 2u * offsets > TVO_MAX_Z_DIM) {
        return TVO_ERR_DIMENSION;
    }
    uint32_t adjacent[TVO_PLAN_MAX_NODES][SET_WORDS] = {{0u}};
    for (unsigned k = 0; k < pair_count; ++k) {
        const unsigned a = pairs[2u * k];
        const unsigned b = pairs[2u * k + 1u];
        if (a >= nodes || b >= nodes || a == b) {
            return TVO_ERR_PARAM;
        }
        set_add(adjacent[a], b);
        set_add(adjacent[b], a);
    }
    /* Eliminating a node couples its neighbours left with each other (the fill): after the loop,
     * adjacent holds the factor's pattern, and a node's neighbours eliminated after it are its blocks. */
    uint32_t done[SET_WORDS] = {0u};
    uint8_t order[TVO_PLAN_MAX_NODES];
    for (unsigned p = 0; p < nodes; ++p) {
        const unsigned v = p < robots ? least_fill(adjacent, done, 0u, robots) : least_fill(adjacent, done, robots, nodes);
        order[p] = (uint8_t)v;
        for (unsigned u = 0; u < nodes; ++u) {
            if (u == v || set_has(done, u) || !set_has(adjacent[v], u)) {
                continue;
            }
            for (unsigned w = 0; w < SET_WORDS; ++w) {
                adjacent[u][w] |= adjacent[v][w] & ~done[w];
            }
            adjacent[u][u / 32u] &= ~((uint32_t)1u << (u % 32u)); /* no node is its own neighbour */
        }
        set_add(done, v);
    }
    unsigned blocks = 0u;
    for (unsigned p = 0; p < nodes; ++p) {
        const unsigned v = order[p];
        plan->first[p] = (uint8_t)(v < robots ? 2u * v : first_multiplier + 2u * (v - robots));
        plan->below_start[p] = (uint16_t)blocks;
        for (unsigned q = p + 1u; q < nodes; ++q) {
            if (set_has(adjacent[v], order[q]) && blocks < TVO_PLAN_MAX_BLOCKS) {
                const unsigned u = order[q];
                plan->below[blocks++] = (uint8_t)(u < robots ? 2u * u : first_multiplier + 2u * (u - robots));
            }
        }
    }
    plan->below_start[nodes] = (uint16_t)blocks;
    plan->primal_nodes = robots;
    plan->node_count = (uint8_t)nodes;
    return TVO_OK;
}

/* ------------------------------------------------------------------------- each step */

/* A block's two rows from its first entry: row[0][0..1] and row[1][0..1]. */
#define ROW1(row) ((row) + TVO_MAX_Z_DIM)

void block_clear(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan)
{
    TVO_ASSERT(a != NULL && plan != NULL);
    const uint8_t *below = plan->below;
    for (unsigned p = 0; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        tvo_real_t *d = &a[f][f];
        d[0] = TVO_R(0.0);
        d[1] = TVO_R(0.0);
        ROW1(d)[0] = TVO_R(0.0);
        ROW1(d)[1] = TVO_R(0.0);
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const unsigned g = below[k];
            tvo_real_t *upper = &a[f][g];
            tvo_real_t *lower = &a[g][f];
            upper[0] = TVO_R(0.0);
            upper[1] = TVO_R(0.0);
            ROW1(upper)[0] = TVO_R(0.0);
            ROW1(upper)[1] = TVO_R(0.0);
            lower[0] = TVO_R(0.0);
            lower[1] = TVO_R(0.0);
            ROW1(lower)[0] = TVO_R(0.0);
            ROW1(lower)[1] = TVO_R(0.0);
        }
    }
}

void block_prepare(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, tvo_real_t *diag)
{
    TVO_ASSERT(a != NULL && plan != NULL && diag != NULL);
    for (unsigned p = 0; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        tvo_real_t *d = &a[f][f];
        diag[f] = d[0];
        diag[f + 1u] = ROW1(d)[1];
        ROW1(d)[0] = d[1];
    }
}

void block_restore(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag, tvo_real_t mu)
{
    TVO_ASSERT(a != NULL && plan != NULL && diag != NULL);
    const uint8_t *below = plan->below;
    for (unsigned p = 0; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        const tvo_real_t shift = p < plan->primal_nodes ? mu : TVO_R(0.0);
        tvo_real_t *d = &a[f][f];
        d[0] = diag[f] + shift;
        ROW1(d)[1] = diag[f + 1u] + shift;
        ROW1(d)[0] = d[1];
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const unsigned g = below[k];
            const tvo_real_t *upper = &a[f][g];
            tvo_real_t *lower = &a[g][f];
            lower[0] = upper[0];
            lower[1] = ROW1(upper)[0];
            ROW1(lower)[0] = upper[1];
            ROW1(lower)[1] = ROW1(upper)[1];
        }
    }
}

/* Pivots of 64 eps of their reference or less (or a reference not positive) fail, as the dense factor's. */
static int pivot_fails(tvo_real_t pivot, tvo_real_t reference)
{
    return !(reference > TVO_R(0.0)) || !(pivot > TVO_R(64.0) * TVO_EPSILON * reference);
}

/* At the end of the robots' elimination the multipliers' blocks hold -S (S = C P^-1 C^T, D being 0):
 * negated, the rest is an ordinary Cholesky; reference receives S's diagonal for the pivot floors. */
static void negate_multiplier_blocks(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan,
                                     tvo_real_t *reference)
{
    for (unsigned p = plan->primal_nodes; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        const unsigned e = 2u * (p - plan->primal_nodes);
        tvo_real_t *d = &a[f][f];
        d[0] = -d[0];
        ROW1(d)[0] = -ROW1(d)[0];
        ROW1(d)[1] = -ROW1(d)[1];
        if (e + 1u < TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)) {
            reference[e] = d[0];
            reference[e + 1u] = ROW1(d)[1];
        }
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            tvo_real_t *lower = &a[plan->below[k]][f]; /* a later position: a multiplier's too */
            lower[0] = -lower[0];
            lower[1] = -lower[1];
            ROW1(lower)[0] = -ROW1(lower)[0];
            ROW1(lower)[1] = -ROW1(lower)[1];
        }
    }
}

block_factor_result_t block_factor(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag,
                                   tvo_real_t mu)
{
    TVO_ASSERT(a != NULL && plan != NULL && diag != NULL);
    tvo_real_t reference[TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)] = {TVO_R(0.0)};
    const uint8_t *below = plan->below;
    for (unsigned p = 0; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        const int primal = p < plan->primal_nodes;
        if (p == plan->primal_nodes) {
            negate_multiplier_blocks(a, plan, reference);
        }
        const unsigned e = primal ? 0u : (2u * (p - plan->primal_nodes)) % TVO_ARRAY_LEN(TVO_MAX_EQUALITIES);
        /* L_pp = chol(A_pp), in the block's lower entries. */
        tvo_real_t *d = &a[f][f];
        const tvo_real_t d0 = d[0];
        if (pivot_fails(d0, primal ? diag[f] + mu : reference[e])) {
            return primal ? BLOCK_PRIMAL_PIVOT : BLOCK_DUAL_PIVOT;
        }
        const tvo_real_t l00 = TVO_SQRT(d0);
        const tvo_real_t l10 = ROW1(d)[0] / l00;
        const tvo_real_t d1 = ROW1(d)[1] - l10 * l10;
        if (pivot_fails(d1, primal ? diag[f + 1u] + mu : reference[(e + 1u) % TVO_ARRAY_LEN(TVO_MAX_EQUALITIES)])) {
            return primal ? BLOCK_PRIMAL_PIVOT : BLOCK_DUAL_PIVOT;
        }
        const tvo_real_t l11 = TVO_SQRT(d1);
        d[0] = l00;
        ROW1(d)[0] = l10;
        ROW1(d)[1] = l11;
        const unsigned begin = plan->below_start[p];
        const unsigned end = plan->below_start[p + 1u];
        for (unsigned k = begin; k < end; ++k) {
            /* L_qp = A_qp L_pp^-T, row by row; then A_qr -= L_qp L_rp^T for each earlier block r of p and
             * A_qq -= L_qp L_qp^T (the fill made room for each). */
            const unsigned g = below[k];
            tvo_real_t *q = &a[g][f];
            const tvo_real_t q00 = q[0] / l00;
            const tvo_real_t q01 = (q[1] - l10 * q00) / l11;
            const tvo_real_t q10 = ROW1(q)[0] / l00;
            const tvo_real_t q11 = (ROW1(q)[1] - l10 * q10) / l11;
            q[0] = q00;
            q[1] = q01;
            ROW1(q)[0] = q10;
            ROW1(q)[1] = q11;
            for (unsigned r = begin; r < k; ++r) {
                const unsigned h = below[r];
                const tvo_real_t *l = &a[h][f];
                tvo_real_t *target = &a[g][h];
                target[0] -= q00 * l[0] + q01 * l[1];
                target[1] -= q00 * ROW1(l)[0] + q01 * ROW1(l)[1];
                ROW1(target)[0] -= q10 * l[0] + q11 * l[1];
                ROW1(target)[1] -= q10 * ROW1(l)[0] + q11 * ROW1(l)[1];
            }
            tvo_real_t *diagonal = &a[g][g];
            diagonal[0] -= q00 * q00 + q01 * q01;
            ROW1(diagonal)[0] -= q10 * q00 + q11 * q01;
            ROW1(diagonal)[1] -= q10 * q10 + q11 * q11;
        }
    }
    return BLOCK_FACTORED;
}

void block_substitute(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *b, tvo_real_t *x)
{
    TVO_ASSERT(a != NULL && plan != NULL && b != NULL && x != NULL);
    const unsigned nodes = plan->node_count <= TVO_PLAN_MAX_NODES ? plan->node_count : TVO_PLAN_MAX_NODES;
    const uint8_t *below = plan->below;
    for (unsigned p = 0; p < nodes; ++p) {
        const unsigned f = plan->first[p];
        x[f] = b[f];
        x[f + 1u] = b[f + 1u];
    }
    /* L z = b, each solved block's part taken off the later ones; then D z (the multipliers' blocks are
     * the negated Schur complement's). */
    for (unsigned p = 0; p < nodes; ++p) {
        const unsigned f = plan->first[p];
        const tvo_real_t *d = &a[f][f];
        const tvo_real_t z0 = x[f] / d[0];
        const tvo_real_t z1 = (x[f + 1u] - ROW1(d)[0] * z0) / ROW1(d)[1];
        x[f] = p < plan->primal_nodes ? z0 : -z0;
        x[f + 1u] = p < plan->primal_nodes ? z1 : -z1;
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const unsigned g = below[k];
            const tvo_real_t *l = &a[g][f];
            x[g] -= l[0] * z0 + l[1] * z1;
            x[g + 1u] -= ROW1(l)[0] * z0 + ROW1(l)[1] * z1;
        }
    }
    /* L^T x = D z, from the last position back. */
    for (unsigned pp = nodes; pp > 0u; --pp) {
        const unsigned p = pp - 1u;
        const unsigned f = plan->first[p];
        tvo_real_t y0 = x[f];
        tvo_real_t y1 = x[f + 1u];
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const unsigned g = below[k];
            const tvo_real_t *l = &a[g][f];
            y0 -= l[0] * x[g] + ROW1(l)[0] * x[g + 1u];
            y1 -= l[1] * x[g] + ROW1(l)[1] * x[g + 1u];
        }
        const tvo_real_t *d = &a[f][f];
        const tvo_real_t x1 = y1 / ROW1(d)[1];
        x[f + 1u] = x1;
        x[f] = (y0 - ROW1(d)[0] * x1) / d[0];
    }
}

int block_pattern_finite(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag)
{
    tvo_real_t probe = TVO_R(0.0); /* v * 0 is NaN exactly for a v that is not finite */
    for (unsigned p = 0; p < plan->node_count && p < TVO_PLAN_MAX_NODES; ++p) {
        const unsigned f = plan->first[p];
        probe += diag[f] * TVO_R(0.0);
        probe += diag[f + 1u] * TVO_R(0.0);
        probe += a[f][f + 1u] * TVO_R(0.0);
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const tvo_real_t *upper = &a[f][plan->below[k]];
            probe += upper[0] * TVO_R(0.0);
            probe += upper[1] * TVO_R(0.0);
            probe += ROW1(upper)[0] * TVO_R(0.0);
            probe += ROW1(upper)[1] * TVO_R(0.0);
        }
    }
    return isfinite(probe);
}

void block_gershgorin(tvo_real_t (*a)[TVO_MAX_Z_DIM], const tvo_solve_plan_t *plan, const tvo_real_t *diag,
                      tvo_real_t *off, tvo_real_t *scale, tvo_real_t *gershgorin)
{
    const unsigned primal = plan->primal_nodes <= TVO_PLAN_MAX_NODES ? plan->primal_nodes : TVO_PLAN_MAX_NODES;
    for (unsigned p = 0; p < primal; ++p) {
        const unsigned f = plan->first[p];
        off[f] = TVO_FABS(a[f][f + 1u]);
        off[f + 1u] = off[f];
    }
    for (unsigned p = 0; p < primal; ++p) {
        const unsigned f = plan->first[p];
        for (unsigned k = plan->below_start[p]; k < plan->below_start[p + 1u]; ++k) {
            const unsigned g = plan->below[k];
            if (g >= 2u * primal) {
                continue; /* a multiplier's block: not in P */
            }
            for (unsigned i = 0; i < 2u; ++i) {
                for (unsigned j = 0; j < 2u; ++j) {
                    const tvo_real_t v = TVO_FABS(a[f + i][g + j]);
                    off[f + i] += v;
                    off[g + j] += v;
                }
            }
        }
    }
    tvo_real_t s = TVO_R(1.0);
    tvo_real_t shift = TVO_R(0.0);
    for (unsigned p = 0; p < primal; ++p) {
        for (unsigned i = 0; i < 2u; ++i) {
            const unsigned c = plan->first[p] + i;
            if (TVO_FABS(diag[c]) > s) {
                s = TVO_FABS(diag[c]);
            }
            const tvo_real_t need = off[c] - diag[c];
            if (need > shift) {
                shift = need;
            }
        }
    }
    *scale = s;
    *gershgorin = shift;
}

#else
/* ISO C: a translation unit holds at least one declaration. */
typedef int tvo_block_solve_unused_t;
#endif /* TVO_BLOCK_SOLVE */
