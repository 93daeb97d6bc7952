/*
 * The TV-O feedback law (paper, Theorem "TVO-based control"); see tvo/law.h.
 *
 * One jet pass along the trajectory gives grad^(0..k-1) and the y^(k)-free remainder r of
 * grad^(k); one pass per two unit directions (time frozen) gives two Hessian columns.
 * Then y^(k) = -H^{-1} (r + sum_i a_i grad^(i)).
 */
#include "internal/law.h"

#include <string.h>

#include "internal/objective_kernel.h"
#include "shape.h"
#include "internal/tracking_kernel.h"
#include "internal/linsolve.h"

/* 0! .. 3! (k <= TVO_MAX_RELATIVE_DEGREE <= 3). */
static const tvo_real_t factorial[4] = {TVO_R(1.0), TVO_R(1.0), TVO_R(2.0), TVO_R(6.0)};

int tvo_law_gains_hurwitz(uint8_t k, const tvo_real_t *a)
{
    TVO_ASSERT(a != NULL && k <= TVO_MAX_RELATIVE_DEGREE);
    for (uint8_t i = 0; i < k; ++i) {
        if (!isfinite(a[i]) || !(a[i] > TVO_R(0.0))) {
            return 0;
        }
    }
    /* Routh-Hurwitz for s^3 + a2 s^2 + a1 s + a0: all positive and a2 a1 > a0. */
    if (k == 3u && !(a[2] * a[1] > a[0])) {
        return 0;
    }
    return 1;
}

void tvo_law_init(tvo_law_t *law, uint8_t relative_degree, uint8_t dim, const tvo_real_t *gain)
{
    TVO_ASSERT(law != NULL && gain != NULL);
    TVO_ASSERT(relative_degree >= 1u && relative_degree <= TVO_MAX_RELATIVE_DEGREE);
    TVO_ASSERT(dim >= 1u && dim <= TVO_MAX_Z_DIM);
    TVO_ASSERT(tvo_law_gains_hurwitz(relative_degree, gain));
    memset(law, 0, sizeof(*law));
    for (uint8_t i = 0; i < relative_degree && i < TVO_MAX_RELATIVE_DEGREE; ++i) {
        law->gain[i] = gain[i];
        law->gain_by_factorial[i] = gain[i] * factorial[i];
    }
    law->relative_degree = relative_degree;
    law->dim = dim;
}

tvo_status_t tvo_law_check_sampling_reach(uint8_t relative_degree, const tvo_real_t *gain, tvo_real_t period_s)
{
    /* C(k, j) for j < k <= 3, row k. */
    static const tvo_real_t binomial[4][3] = {
        {TVO_R(0.0), TVO_R(0.0), TVO_R(0.0)},
        {TVO_R(1.0), TVO_R(0.0), TVO_R(0.0)},
        {TVO_R(1.0), TVO_R(2.0), TVO_R(0.0)},
        {TVO_R(1.0), TVO_R(3.0), TVO_R(3.0)},
    };
    TVO_ASSERT(gain != NULL);
    TVO_ASSERT(relative_degree >= 1u && relative_degree <= TVO_MAX_RELATIVE_DEGREE);
    TVO_ASSERT(isfinite(period_s) && period_s > TVO_R(0.0));
    const tvo_real_t nyquist_radps = TVO_PI / period_s;
    tvo_real_t power = TVO_R(1.0); /* R^(k-j), j descending from k - 1 */
    for (uint8_t n = 0; n < relative_degree; ++n) {
        const uint8_t j = (uint8_t)(relative_degree - 1u - n);
        power *= nyquist_radps;
        if (!(gain[j] <= binomial[relative_degree][j] * power)) {
            return TVO_ERR_PARAM; /* beyond the bound, or NaN */
        }
    }
    return TVO_OK;
}

static void zero_output(tvo_real_t *y_k, uint8_t dim)
{
    for (uint8_t i = 0; i < dim && i < TVO_MAX_Z_DIM; ++i) {
        y_k[i] = TVO_R(0.0);
    }
}

/*
 * The Hessian of the terms without a closed form, added into h.
 * Hessian columns H[:, col] = d/dtau grad(y + e_col tau, t) with time frozen, two columns per
 * gradient evaluation: direction a is seeded at tau^2 and direction b at tau^3 of an order-3 jet.
 * Any product of two seeded terms is O(tau^4) and truncated, so
 *   grad(y + e_a tau^2 + e_b tau^3) = grad(y) + H e_a tau^2 + H e_b tau^3 + O(tau^4)
 * exactly, with the ordinary Taylor arithmetic of every term (no mode, no special jet type).
 * With jets shorter than order 3 (a build limited to k < 3), one column per evaluation at tau^1.
 * The jets are the workspace's (their trajectory contents are no longer needed).
 */
#if TVO_JET_MAX_ORDER >= 3
#define HESSIAN_ORDER 3u
#define HESSIAN_COLUMNS_PER_PASS 2u
static const uint8_t hessian_seed_power[HESSIAN_COLUMNS_PER_PASS] = {2u, 3u};
#else
#define HESSIAN_ORDER 1u
#define HESSIAN_COLUMNS_PER_PASS 1u
static const uint8_t hessian_seed_power[HESSIAN_COLUMNS_PER_PASS] = {1u};
#endif

static tvo_status_t add_jet_hessian(const tvo_objective_t *objective, const tvo_output_derivs_t *y,
                                    const tvo_time_jet_t *t, tvo_law_workspace_t *work)
{
    const uint8_t m = objective->dim;
    tvo_jet_t *y_jet = work->y_jet;
    tvo_jet_t *g_jet = work->g_jet;
    tvo_real_t(*h)[TVO_MAX_Z_DIM] = work->hessian.matrix;
    tvo_time_jet_t *frozen = &work->time;
    *frozen = *t;
    frozen->rate = TVO_R(0.0);
    frozen->shared = &work->shared; /* emptied: frozen time has schedules of its own */
    work->shared.owner = NULL;
    for (uint8_t i = 0; i < m; ++i) {
        tvo_jet_constant(y->d[0][i], &y_jet[i]);
    }
    for (uint8_t first = 0; first < m; first = (uint8_t)(first + HESSIAN_COLUMNS_PER_PASS)) {
        for (uint8_t d = 0; d < HESSIAN_COLUMNS_PER_PASS && first + d < m; ++d) {
            y_jet[first + d].c[hessian_seed_power[d]] = TVO_R(1.0);
        }
        const tvo_status_t st =
            objective_sum_terms(objective, y_jet, frozen, HESSIAN_ORDER, g_jet, NULL, SUM_JET_TERMS, NULL);
        for (uint8_t d = 0; d < HESSIAN_COLUMNS_PER_PASS && first + d < m; ++d) {
            y_jet[first + d].c[hessian_seed_power[d]] = TVO_R(0.0);
        }
        if (st != TVO_OK) {
            return st;
        }
        for (uint8_t d = 0; d < HESSIAN_COLUMNS_PER_PASS && first + d < m; ++d) {
            for (uint8_t i = 0; i < m; ++i) {
                h[i][first + d] += g_jet[i].c[hessian_seed_power[d]];
            }
        }
    }
    return TVO_OK;
}

/* Trajectory jets y(tau) = sum_{j<k} y^(j) tau^j / j!, with y^(k) = 0 on this curve (coefficients
 * above k: the passes of order k never read them, the Hessian's seeds clear them); 0 if a
 * derivative is not finite (when check: a caller whose own result check catches them passes 0). */
TVO_SHAPE_BODY int trajectory_jets(const tvo_output_derivs_t *y, tvo_jet_t *y_jet, const uint8_t k, const uint8_t m,
                                   const int check)
{
    static const tvo_real_t inv_factorial[4] = {TVO_R(1.0), TVO_R(1.0), TVO_R(0.5), TVO_R(1.0) / TVO_R(6.0)};
    tvo_real_t probe = TVO_R(0.0); /* value * 0 is NaN exactly for a value that is not finite */
    TVO_UNROLL_SMALL
    for (unsigned j = 0; j < k; ++j) {
        const tvo_real_t *value = y->d[j];
        const tvo_real_t scale = inv_factorial[j];
        TVO_UNROLL_SMALL
        for (unsigned i = 0; i < m; ++i) {
            if (check) {
                probe += value[i] * TVO_R(0.0);
            }
            y_jet[i].c[j] = value[i] * scale;
        }
    }
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        y_jet[i].c[k] = TVO_R(0.0);
    }
    return !check || isfinite(probe);
}

/* grad^(j) = j! c_j; rhs = r + sum_{j<k} a_j grad^(j) with r = k! c_k. Returns the sum of the rhs
 * entries times 0: NaN exactly when one is not finite. */
TVO_SHAPE_BODY tvo_real_t combine_rhs(const tvo_law_t *law, const tvo_jet_t *g_jet, tvo_real_t *rhs, const uint8_t k,
                                      const uint8_t m)
{
    const tvo_real_t r_scale = factorial[k];
    const tvo_real_t *gain = law->gain_by_factorial;
    tvo_real_t probe = TVO_R(0.0);
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        tvo_real_t sum = g_jet[i].c[k] * r_scale;
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < k; ++j) {
            sum += gain[j] * g_jet[i].c[j];
        }
        probe += sum * TVO_R(0.0);
        rhs[i] = sum;
    }
    return probe;
}

/* The gradient and its derivatives as one vector each, grad^(j) = j! c_j, for the rows asked for
 * (grad_rows[j] non-NULL) and their first `count` entries (telemetry); with the rank-one parts kept
 * apart in `parts` added in (NULL: none). */
TVO_SHAPE_BODY void write_gradient_rows(const tvo_jet_t *g_jet, const tvo_hessian_t *parts, tvo_real_t *const *grad_rows,
                                        const unsigned count, const uint8_t k, const uint8_t m)
{
    const unsigned part_count = parts != NULL ? parts->rank_one_count : 0u;
    TVO_UNROLL_SMALL
    for (unsigned j = 0; j <= k; ++j) {
        tvo_real_t *row = grad_rows[j];
        if (row == NULL) {
            continue;
        }
        const tvo_real_t scale = factorial[j];
        TVO_UNROLL_SMALL
        for (unsigned i = 0; i < m; ++i) { /* over m, a constant in the common shape */
            if (i < count) {
                row[i] = g_jet[i].c[j] * scale;
            }
        }
        for (unsigned p = 0; p < part_count; ++p) {
            const tvo_rank_one_t *part = &parts->rank_one[p];
            for (unsigned e = 0; e < part->count; ++e) {
                if (part->index[e] < count) {
                    row[part->index[e]] += part->gradient.c[j] * scale * part->value[e];
                }
            }
        }
    }
}

/* Whether every term is a tracking term's closed form, with no multipliers: the Hessian is then the
 * constant diagonal sum of the weights, and the law needs neither the matrix nor the general solve.
 * The objective's flag rules the rest out at once; the terms are checked before they are trusted. */
static inline int tracking_terms_only(const tvo_objective_t *objective)
{
    if (!objective->tracking_only || objective->dual_dim != 0u || objective->jets_only ||
        objective->term_count == 0u) {
        return 0;
    }
    for (unsigned p = 0; p < objective->term_count && p < TVO_MAX_TERMS; ++p) {
        if (objective->terms[p].kind != TVO_TERM_TRACKING) {
            return 0;
        }
    }
    return 1;
}

/* With one copy (a size build), the tracking path stays out of line: its target arrays would
 * otherwise sit in the general path's frame, under the deepest call chain of the step. */
#if TVO_SHAPE_COPIES || !defined(__GNUC__)
#define TRACKING_PATH_BODY TVO_SHAPE_BODY
#else
#define TRACKING_PATH_BODY static __attribute__((noinline))
#endif

/* The status the general path reports for what the tracking path declined (its checks in its order:
 * the derivatives before the terms), with y_k zeroed as there. Off the step's common path. */
static tvo_status_t tracking_path_refusal(const tvo_output_derivs_t *y, tvo_real_t *y_k, tvo_law_workspace_t *work,
                                          tvo_status_t found, uint8_t k, uint8_t m)
{
    zero_output(y_k, m);
    if (k > TVO_MAX_RELATIVE_DEGREE || m > TVO_MAX_Z_DIM) {
        return found; /* checked by check_call: restated for the compiler's bounds */
    }
    return trajectory_jets(y, work->y_jet, k, m, 1) ? found : TVO_ERR_NOT_FINITE;
}

/*
 * The evaluation of an objective of tracking terms only (tracking_terms_only): the same arithmetic in
 * the same order as the general path (each term's gradient added in turn, the weights summed on the
 * diagonal, the solve rhs / W), and the same status for any input the general path refuses. One
 * exception: an output that no term covers has no curvature, which the general path's solve
 * regularises and this path refuses (TVO_ERR_NOT_POSITIVE_DEFINITE); the law then falls back to the
 * general path where the objective links it.
 */
TVO_SHAPE_BODY tvo_status_t tracking_shape_body(const tvo_law_t *law, const tvo_objective_t *objective,
                                                const tvo_output_derivs_t *y, const tvo_time_jet_t *t, tvo_real_t *y_k,
                                                tvo_real_t *const *grad_rows, tvo_real_t *gradient,
                                                tvo_real_t *gradient_rate, const unsigned grad_count,
                                                tvo_real_t *regularization, tvo_law_workspace_t *work, const uint8_t k,
                                                const uint8_t m)
{
    if (!isfinite(t->t_s) || !isfinite(t->rate)) {
        zero_output(y_k, m);
        return TVO_ERR_NOT_FINITE;
    }
    /* A derivative that is not finite reaches its output's gradient, hence the rhs checked below (an
     * output no term covers has no weight, which the solve's check declines): checked only then. The
     * terms read the derivatives where they are (tracking_add_along: no jets of y). */
    tvo_jet_t *g_jet = work->g_jet;
    /* The diagonal of the workspace's matrix holds the weights' sums (entry i at i * stride). */
    tvo_real_t *diagonal = &work->hessian.matrix[0][0];
    const unsigned stride = TVO_MAX_Z_DIM + 1u;
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j <= k; ++j) {
            g_jet[i].c[j] = TVO_R(0.0); /* the coefficients this order reads */
        }
        diagonal[i * stride] = TVO_R(0.0);
    }
    /* Along the trajectory (rate 1, as the general path's time jet); the targets read only t's time.
     * The checks are tvo_tracking_gradient_hessian's, in its order. */
    for (unsigned p = 0; p < objective->term_count && p < TVO_MAX_TERMS; ++p) {
        const tvo_tracking_term_t *term = (const tvo_tracking_term_t *)objective->terms[p].term;
        tvo_status_t st = TVO_ERR_NULL;
        if (term != NULL) {
            st = (unsigned)term->offset + 2u > m ? TVO_ERR_DIMENSION
                 : term->target == NULL          ? TVO_ERR_NULL
                                                 : tracking_add_along(term, y->d, t, k, g_jet, diagonal, stride);
        }
        if (st != TVO_OK) {
            return tracking_path_refusal(y, y_k, work, st, k, m);
        }
    }
    tvo_real_t *x = work->rhs;
    if (!isfinite(combine_rhs(law, g_jet, x, k, m))) {
        return tracking_path_refusal(y, y_k, work, TVO_ERR_NUMERIC, k, m);
    }
    /* tvo_saddle_solve's diagonal solve: each W_ii finite (else, as there, TVO_ERR_NOT_FINITE) and
     * > 0 (else the general path's solve regularises: refused here), then x = rhs / W. */
    tvo_real_t probe = TVO_R(0.0);
    int positive = 1;
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        probe += diagonal[i * stride] * TVO_R(0.0);
        positive &= diagonal[i * stride] > TVO_R(0.0);
    }
    if (!isfinite(probe) || !positive) {
        return tracking_path_refusal(y, y_k, work, isfinite(probe) ? TVO_ERR_NOT_POSITIVE_DEFINITE : TVO_ERR_NOT_FINITE,
                                     k, m);
    }
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        x[i] = x[i] / diagonal[i * stride];
        probe += x[i] * TVO_R(0.0);
    }
    if (!isfinite(probe)) {
        zero_output(y_k, m);
        return TVO_ERR_NUMERIC;
    }
    const unsigned count = m < grad_count ? m : grad_count;
    if (grad_rows != NULL) {
        write_gradient_rows(g_jet, NULL, grad_rows, count, k, m);
    } else {
        /* A controller's report (grad_rows NULL): grad and its rate, the first two rows (k >= 1, both asked
         * for). */
        TVO_UNROLL_SMALL
        for (unsigned i = 0; i < m; ++i) {
            if (i < count) {
                gradient[i] = g_jet[i].c[0] * factorial[0];
                gradient_rate[i] = g_jet[i].c[1] * factorial[1];
            }
        }
    }
    if (regularization != NULL) {
        *regularization = TVO_R(0.0);
    }
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < m; ++i) {
        y_k[i] = -x[i];
    }
    return TVO_OK;
}

#if TVO_SHAPE_COPIES
/*
 * tracking_shape_body for one tracking term over both outputs at the common order, the law's most common
 * call (one robot tracking): the same operations in the same order, each sum begun from 0 as there, its
 * values kept in registers rather than the workspace. NULL grad_rows (a controller's report).
 */
TVO_SHAPE_BODY tvo_status_t tracking_one_term_body(const tvo_law_t *law, const tvo_tracking_term_t *term,
                                                   const tvo_output_derivs_t *y, const tvo_time_jet_t *t,
                                                   tvo_real_t *y_k, tvo_real_t *gradient, tvo_real_t *gradient_rate,
                                                   const unsigned grad_count, tvo_real_t *regularization,
                                                   tvo_law_workspace_t *work)
{
    const uint8_t k = TVO_SHAPE_ORDER;
    const uint8_t m = TVO_SHAPE_OUTPUT_DIM;
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    tvo_status_t st = TVO_ERR_NULL;
    if (term != NULL) {
        st = (unsigned)term->offset + 2u > m ? TVO_ERR_DIMENSION
             : term->target == NULL          ? TVO_ERR_NULL
                                             : tracking_target_derivatives(term->target, t, k, deriv);
    }
    if (st != TVO_OK) {
        return tracking_path_refusal(y, y_k, work, st, k, m);
    }
    static const tvo_real_t inv_factorial[3] = {TVO_R(1.0), TVO_R(1.0), TVO_R(0.5)};
    const tvo_real_t *gain = law->gain_by_factorial;
    tvo_real_t g[2][3];
    tvo_real_t rhs[2];
    tvo_real_t diagonal[2];
    tvo_real_t probe = TVO_R(0.0);
    for (unsigned i = 0; i < 2u; ++i) {
        const tvo_real_t w = term->weight[i];
        for (unsigned j = 0; j < 3u; ++j) {
            const tvo_real_t y_j = j < k ? y->d[j][i] * inv_factorial[j] : TVO_R(0.0);
            g[i][j] = TVO_R(0.0) + w * (y_j - deriv[j][i] * inv_factorial[j]);
        }
        diagonal[i] = TVO_R(0.0) + term->weight[i];
    }
    for (unsigned i = 0; i < 2u; ++i) { /* combine_rhs */
        tvo_real_t sum = g[i][2] * factorial[2];
        sum += gain[0] * g[i][0];
        sum += gain[1] * g[i][1];
        probe += sum * TVO_R(0.0);
        rhs[i] = sum;
    }
    if (!isfinite(probe)) {
        return tracking_path_refusal(y, y_k, work, TVO_ERR_NUMERIC, k, m);
    }
    probe = TVO_R(0.0);
    int positive = 1;
    for (unsigned i = 0; i < 2u; ++i) {
        probe += diagonal[i] * TVO_R(0.0);
        positive &= diagonal[i] > TVO_R(0.0);
    }
    if (!isfinite(probe) || !positive) {
        return tracking_path_refusal(y, y_k, work, isfinite(probe) ? TVO_ERR_NOT_POSITIVE_DEFINITE : TVO_ERR_NOT_FINITE,
                                     k, m);
    }
    tvo_real_t x[2];
    for (unsigned i = 0; i < 2u; ++i) {
        x[i] = rhs[i] / diagonal[i];
        probe += x[i] * TVO_R(0.0);
    }
    if (!isfinite(probe)) {
        zero_output(y_k, m);
        return TVO_ERR_NUMERIC;
    }
    for (unsigned i = 0; i < 2u; ++i) {
        if (i < grad_count) {
            gradient[i] = g[i][0] * factorial[0];
            gradient_rate[i] = g[i][1] * factorial[1];
        }
    }
    if (regularization != NULL) {
        *regularization = TVO_R(0.0);
    }
    for (unsigned i = 0; i < 2u; ++i) {
        y_k[i] = -x[i];
    }
    return TVO_OK;
}
#endif /* TVO_SHAPE_COPIES */

/* The tracking path for the call recorded in the workspace (a size build's call passes three). */
TRACKING_PATH_BODY tvo_status_t evaluate_tracking_shape(tvo_law_workspace_t *work, const uint8_t k, const uint8_t m)
{
    const tvo_law_outputs_t *out = &work->outputs;
    return tracking_shape_body(work->call.law, work->call.objective, work->call.y, work->call.t, work->call.y_k,
                               out->grad_rows, out->grad_rows[0], out->grad_rows[1], out->grad_count,
                               out->regularization, work, k, m);
}

#if TVO_BLOCK_SOLVE
/* The objective's block-solve plan, if it has one that fits it and its closed forms are used. */
static inline const tvo_solve_plan_t *usable_plan(const tvo_objective_t *objective)
{
    const tvo_solve_plan_t *plan = objective->plan;
    if (plan == NULL || objective->jets_only || 2u * plan->primal_nodes != objective->primal_dim ||
        2u * plan->node_count != objective->dim) {
        return NULL;
    }
    return plan;
}
#endif

/* The evaluation for a validated law and objective of order k and dimension m; each output is
 * optional: grad_rows[j] receives grad^(j) (j <= k, grad_count entries), hessian_out the Hessian,
 * *shift the solve's regularisation. */
TVO_SHAPE_BODY tvo_status_t evaluate_shape(const tvo_law_t *law, const tvo_objective_t *objective,
                                              const tvo_output_derivs_t *y, const tvo_time_jet_t *t,
                                              tvo_real_t *y_k, tvo_real_t *const *grad_rows, uint8_t grad_count,
                                              tvo_real_t (*hessian_out)[TVO_MAX_Z_DIM], tvo_real_t *shift,
                                              tvo_law_workspace_t *work, const uint8_t k, const uint8_t m)
{
    zero_output(y_k, m);
    if (!isfinite(t->t_s) || !isfinite(t->rate)) {
        return TVO_ERR_NOT_FINITE;
    }
    tvo_jet_t *y_jet = work->y_jet;
    tvo_jet_t *g_jet = work->g_jet;
    tvo_hessian_t *hessian = &work->hessian;
    tvo_real_t(*h)[TVO_MAX_Z_DIM] = hessian->matrix;
    hessian->rank_one_count = 0u;
    if (!trajectory_jets(y, y_jet, k, m, 1)) {
        return TVO_ERR_NOT_FINITE;
    }
#if TVO_BLOCK_SOLVE
    /* Three robots or more: only the blocks of the problem's coupling (a tool asking for the Hessian gets
     * every entry). The common shapes (one or two robots) are dense. */
    const tvo_solve_plan_t *plan = m > TVO_SHAPE_PAIR_OUTPUT_DIM ? usable_plan(objective) : NULL;
    if (plan != NULL && hessian_out == NULL) {
        tvo_hessian_clear_blocks(hessian, plan);
    } else
#endif
    {
        TVO_UNROLL_SMALL
        for (unsigned i = 0; i < m; ++i) {
            TVO_UNROLL_SMALL
            for (unsigned j = 0; j < m; ++j) {
                h[i][j] = TVO_R(0.0);
            }
        }
#if TVO_BLOCK_SOLVE
        hessian->plan = plan;
#endif
    }
    tvo_time_jet_t *along = &work->time;
    *along = *t;
    along->rate = TVO_R(1.0);
    along->shared = &work->shared; /* the barrier's schedules, computed by the first term that needs them */
    work->shared.owner = NULL;
    /* One pass: every term's gradient jets; the closed forms add their Hessian on the way. */
    uint8_t jet_terms = 0u;
    tvo_status_t st = objective_sum_terms(objective, y_jet, along, k, g_jet, hessian, SUM_CLOSED_FORMS, &jet_terms);
    if (st != TVO_OK) {
        return st;
    }

    /* Barrier parts that are not stiff join the matrix and the gradient; the stiff ones stay apart. */
    tvo_hessian_settle(hessian, objective->primal_dim, objective->dual_dim, g_jet, k);

    /* rhs for the gradient jets and (gamma) for each part kept apart, whose gradient is a multiple
     * of its direction. */
    tvo_real_t *rhs = work->rhs;
    tvo_real_t *gamma = work->gamma;
    tvo_real_t probe = combine_rhs(law, g_jet, rhs, k, m);
    const tvo_real_t r_scale = factorial[k];
    const tvo_real_t *gain = law->gain_by_factorial;
    for (unsigned p = 0; p < hessian->rank_one_count; ++p) {
        const tvo_jet_t *g = &hessian->rank_one[p].gradient;
        tvo_real_t sum = g->c[k] * r_scale;
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < k; ++j) {
            sum += gain[j] * g->c[j];
        }
        probe += sum * TVO_R(0.0);
        gamma[p] = sum;
    }
    if (!isfinite(probe)) {
        return TVO_ERR_NUMERIC; /* a gradient coefficient was not finite */
    }
    if (grad_rows != NULL) {
        write_gradient_rows(g_jet, hessian, grad_rows, m < grad_count ? m : grad_count, k, m);
    }

    if (jet_terms > 0u) {
#if TVO_BLOCK_SOLVE
        if (plan != NULL) {
            return TVO_ERR_NOT_INITIALIZED; /* a plan's terms all have closed forms: one was changed by hand */
        }
#endif
        st = add_jet_hessian(objective, y, t, work);
        if (st != TVO_OK) {
            return st;
        }
    }
#if TVO_BLOCK_SOLVE
    /* The block solve reads one copy of each block (its factor makes the other copy the first's). */
    if (plan == NULL)
#endif
    {
        /* Symmetrise: the exact Hessian is symmetric; rounding should not make the solve see otherwise. */
        symmetrize(&h[0][0], TVO_MAX_Z_DIM, m);
    }
    if (hessian_out != NULL) {
        /* The whole Hessian, rank-one parts included, for tests and tools. */
        for (unsigned i = 0; i < m; ++i) {
            for (unsigned j = 0; j < m; ++j) {
                hessian_out[i][j] = h[i][j];
            }
        }
        for (unsigned p = 0; p < hessian->rank_one_count; ++p) {
            tvo_rank_one_add_to(&hessian->rank_one[p], hessian_out, NULL, 0u);
        }
    }

    st = tvo_saddle_solve_split(hessian, objective->primal_dim, objective->dual_dim, rhs, gamma, rhs, shift);
    if (st != TVO_OK) {
        return st;
    }
    TVO_UNROLL_SMALL
    for (uint8_t i = 0; i < m; ++i) {
        y_k[i] = -rhs[i];
    }
    return TVO_OK;
}

/* The checks of an evaluation's law and objective (the entries check the pointers). */
static tvo_status_t check_call(const tvo_law_t *law, const tvo_objective_t *objective)
{
    if (law->relative_degree == 0u || law->relative_degree > TVO_MAX_RELATIVE_DEGREE) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    const uint8_t m = law->dim;
    if (m == 0u || m > TVO_MAX_Z_DIM || objective->dim != m ||
        (unsigned)objective->primal_dim + objective->dual_dim != m) {
        return TVO_ERR_DIMENSION;
    }
    return TVO_OK;
}

tvo_status_t law_general_path(void *law_workspace)
{
    tvo_law_workspace_t *work = (tvo_law_workspace_t *)law_workspace;
    const tvo_law_t *law = work->call.law;
    const tvo_objective_t *objective = work->call.objective;
    const tvo_status_t st = check_call(law, objective); /* reached through a pointer: checks again */
    if (st != TVO_OK) {
        return st;
    }
    const tvo_law_outputs_t *out = &work->outputs;
    const uint8_t k = law->relative_degree;
    const uint8_t m = law->dim;
#if TVO_SHAPE_COPIES
    if (k == TVO_SHAPE_ORDER && m == TVO_SHAPE_OUTPUT_DIM) {
        return evaluate_shape(law, objective, work->call.y, work->call.t, work->call.y_k, out->grad_rows,
                              out->grad_count, out->hessian, out->regularization, work, TVO_SHAPE_ORDER,
                              TVO_SHAPE_OUTPUT_DIM);
    }
#if TVO_MAX_Z_DIM >= TVO_SHAPE_PAIR_OUTPUT_DIM
    if (k == TVO_SHAPE_ORDER && m == TVO_SHAPE_PAIR_OUTPUT_DIM) {
        return evaluate_shape(law, objective, work->call.y, work->call.t, work->call.y_k, out->grad_rows,
                              out->grad_count, out->hessian, out->regularization, work, TVO_SHAPE_ORDER,
                              TVO_SHAPE_PAIR_OUTPUT_DIM);
    }
#endif
#endif
    return evaluate_shape(law, objective, work->call.y, work->call.t, work->call.y_k, out->grad_rows,
                          out->grad_count, out->hessian, out->regularization, work, k, m);
}

/* The tracking path for the common shapes' copies or the run-time counts. */
static tvo_status_t evaluate_tracking(tvo_law_workspace_t *work)
{
    const uint8_t k = work->call.law->relative_degree;
    const uint8_t m = work->call.law->dim;
#if TVO_SHAPE_COPIES
    if (k == TVO_SHAPE_ORDER && m == TVO_SHAPE_OUTPUT_DIM) {
        return evaluate_tracking_shape(work, TVO_SHAPE_ORDER, TVO_SHAPE_OUTPUT_DIM);
    }
#if TVO_MAX_Z_DIM >= TVO_SHAPE_PAIR_OUTPUT_DIM
    if (k == TVO_SHAPE_ORDER && m == TVO_SHAPE_PAIR_OUTPUT_DIM) {
        return evaluate_tracking_shape(work, TVO_SHAPE_ORDER, TVO_SHAPE_PAIR_OUTPUT_DIM);
    }
#endif
#endif
    if (k > TVO_MAX_RELATIVE_DEGREE || m > TVO_MAX_Z_DIM) {
        return TVO_ERR_NOT_INITIALIZED; /* checked by check_call: restated for the compiler's bounds */
    }
    return evaluate_tracking_shape(work, k, m);
}

/* A call check_call refused: y_k zeroed where its length is known (an initialised law, another size). */
static tvo_status_t refuse_call(const tvo_law_workspace_t *work, tvo_status_t status)
{
    if (status == TVO_ERR_DIMENSION) {
        zero_output(work->call.y_k, work->call.law->dim);
    }
    return status;
}

/* Only fields set by hand (e.g. jets_only on an objective of tvo_tracking_add's terms) bring such an
 * objective past the tracking path without a general path: nothing this link's law can evaluate. */
static tvo_status_t refuse_without_general_path(tvo_law_workspace_t *work)
{
    zero_output(work->call.y_k, work->call.law->dim);
    return TVO_ERR_NOT_INITIALIZED;
}

#if defined(__GNUC__)
#define ENTRY_BODY static inline __attribute__((always_inline))
#else
#define ENTRY_BODY static inline
#endif
/* The evaluation of a validated call recorded in work->call, writing where work->outputs says: the
 * tracking path where it applies; the general path (general: NULL when the objective does not link
 * it) for anything else and for what the tracking path declines, by a tail call. In its entries'
 * bodies, so no frame of its own sits under the general path's. */
ENTRY_BODY tvo_status_t evaluate_recorded(tvo_law_workspace_t *work, tvo_general_path_fn general)
{
    /* Few values live across the calls here: this frame sits under the general path's. */
    const tvo_status_t checked = check_call(work->call.law, work->call.objective);
    if (checked != TVO_OK) {
        return refuse_call(work, checked);
    }
    if (work->outputs.hessian == NULL && tracking_terms_only(work->call.objective)) {
        const tvo_status_t st = evaluate_tracking(work);
        if (st == TVO_OK || general == NULL) {
            return st;
        }
    }
    if (general == NULL) {
        return refuse_without_general_path(work);
    }
    return general(work);
}

/* Records the call (pointers valid, as the callers assert; the rest checked by evaluate_recorded). */
static inline void record_call(const tvo_law_t *law, const tvo_objective_t *objective, const tvo_output_derivs_t *y,
                               const tvo_time_jet_t *t, tvo_real_t *y_k, tvo_law_workspace_t *work)
{
    work->call.law = law;
    work->call.objective = objective;
    work->call.y = y;
    work->call.t = t;
    work->call.y_k = y_k;
}

tvo_status_t tvo_law_evaluate(const tvo_law_t *law, const tvo_objective_t *objective,
                              const tvo_output_derivs_t *y, const tvo_time_jet_t *t,
                              tvo_real_t *y_k, tvo_law_eval_t *eval)
{
    tvo_law_workspace_t work;
    memset(&work.outputs, 0, sizeof(work.outputs));
    if (eval != NULL) {
        memset(eval, 0, sizeof(*eval));
        for (uint8_t j = 0; j <= TVO_MAX_RELATIVE_DEGREE; ++j) {
            work.outputs.grad_rows[j] = eval->grad[j];
        }
        work.outputs.grad_count = TVO_MAX_Z_DIM;
        work.outputs.hessian = eval->hessian;
        work.outputs.regularization = &eval->regularization;
    }
    TVO_ASSERT(law != NULL && objective != NULL && y != NULL && t != NULL && y_k != NULL);
    record_call(law, objective, y, t, y_k, &work);
    /* The tools' entry (a Hessian on request): the general path always, whatever the objective links. */
    return evaluate_recorded(&work, law_general_path);
}

tvo_status_t tvo_law_evaluate_report(const tvo_law_t *law, const tvo_objective_t *objective,
                                     const tvo_output_derivs_t *y, const tvo_time_jet_t *t, tvo_real_t *y_k,
                                     tvo_law_report_t *report, tvo_law_workspace_t *work)
{
    TVO_ASSERT(law != NULL && objective != NULL && y != NULL && t != NULL && y_k != NULL && report != NULL &&
               work != NULL);
    report->regularization = TVO_R(0.0);
#if TVO_SHAPE_COPIES
    /* The controllers' common case, one robot's tracking at k = 2, in this body (no call, no dispatch, no
     * record of the call unless the path declines it). */
    const int common = objective->tracking_only && law->relative_degree == TVO_SHAPE_ORDER &&
                       law->dim == TVO_SHAPE_OUTPUT_DIM && objective->dim == TVO_SHAPE_OUTPUT_DIM &&
                       objective->primal_dim == TVO_SHAPE_OUTPUT_DIM && tracking_terms_only(objective);
    const int tried = common && report->gradient != NULL && report->gradient_rate != NULL;
    if (tried && objective->term_count == 1u) {
        if (!isfinite(t->t_s) || !isfinite(t->rate)) {
            zero_output(y_k, TVO_SHAPE_OUTPUT_DIM);
            return TVO_ERR_NOT_FINITE; /* tracking_shape_body's first check */
        }
        const tvo_status_t st = tracking_one_term_body(law, (const tvo_tracking_term_t *)objective->terms[0].term, y, t,
                                                       y_k, report->gradient, report->gradient_rate, report->count,
                                                       &report->regularization, work);
        if (st == TVO_OK || objective->general_path == NULL) {
            return st;
        }
    } else if (tried) {
        const tvo_status_t st = tracking_shape_body(law, objective, y, t, y_k, NULL, report->gradient,
                                                    report->gradient_rate, report->count, &report->regularization, work,
                                                    TVO_SHAPE_ORDER, TVO_SHAPE_OUTPUT_DIM);
        if (st == TVO_OK || objective->general_path == NULL) {
            return st;
        }
    }
#endif
    tvo_law_outputs_t *out = &work->outputs;
    out->grad_rows[0] = report->gradient;
    out->grad_rows[1] = report->gradient_rate;
    for (uint8_t j = 2; j <= TVO_MAX_RELATIVE_DEGREE; ++j) {
        out->grad_rows[j] = NULL;
    }
    out->grad_count = report->count;
    out->hessian = NULL;
    out->regularization = &report->regularization;
    record_call(law, objective, y, t, y_k, work);
#if TVO_SHAPE_COPIES
    if (tried) {
        return objective->general_path(work); /* what the path declined */
    }
#endif
    return evaluate_recorded(work, objective->general_path);
}
