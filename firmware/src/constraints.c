/* Inequality-constraint terms through the relaxed barrier; see tvo/constraints.h. */
#include "internal/constraints.h"

#include <string.h>

#include "internal/barrier_kernel.h"

/* The barrier's weight inline where the terms have shape copies (the order then a constant in them),
 * by call where they are compiled for size. */
#if TVO_SHAPE_COPIES
#define TERM_BARRIER_WEIGHT barrier_weight
#define TERM_BARRIER_SCHEDULE barrier_schedule
#else
#define TERM_BARRIER_WEIGHT tvo_barrier_weight_on_schedule
#define TERM_BARRIER_SCHEDULE tvo_barrier_schedule_shared
#endif

/* A robot centre closer than this to an obstacle centre has no defined separating plane. */
#define FREE_SPACE_MIN_CENTER_DISTANCE_M TVO_R(1e-6)

static int finite2(const tvo_real_t v[2])
{
    return isfinite(v[0]) && isfinite(v[1]);
}

/* Both entries within the workspace's magnitude (tvo/config.h). */
static int within2(const tvo_real_t v[2])
{
    return TVO_FABS(v[0]) <= TVO_POSITION_LIMIT_M && TVO_FABS(v[1]) <= TVO_POSITION_LIMIT_M;
}

/* value + rate (t + t_rate tau) as a jet. */
static void affine_time_jet(tvo_real_t value, tvo_real_t rate, const tvo_time_jet_t *t, tvo_jet_t *out)
{
    tvo_jet_variable(value + rate * t->t_s, rate * t->rate, out);
}

/* grad[index] += w * df (jets). */
static void add_weighted(tvo_jet_t *grad, uint8_t index, const tvo_jet_t *w, const tvo_jet_t *df, uint8_t order)
{
    tvo_jet_t product;
    tvo_jet_mul(w, df, order, &product);
    tvo_jet_add(&grad[index], &product, order, &grad[index]);
}

/* ---------------------------------------------------------------- a term kind's entries, written once */

/* return body(args..., order), with the order a constant in a second copy where the build has shape copies
 * (shape.h): the body's loops over the order unroll there. */
#if TVO_SHAPE_COPIES
#define RETURN_SHAPE_COPY(order, body, ...)                                                                      \
    if ((order) == TVO_SHAPE_ORDER) {                                                                            \
        return body(__VA_ARGS__, TVO_SHAPE_ORDER);                                                               \
    }                                                                                                            \
    return body(__VA_ARGS__, order)
#else
#define RETURN_SHAPE_COPY(order, body, ...) return body(__VA_ARGS__, order)
#endif

/* A body compiled into each caller: one frame fewer under the term. A body both entries call, whole: its
 * checks not split off into them. */
#if defined(__GNUC__)
#define TERM_INLINE_BODY static inline __attribute__((always_inline))
#define TERM_SHARED_BODY static __attribute__((noinline))
#else
#define TERM_INLINE_BODY static inline
#define TERM_SHARED_BODY static
#endif

/* kind##_sum: the shape copies of kind##_sum_shape(self, z, t, grad, hessian, order), the term's gradient jets
 * (with hessian, the closed form), in its caller; called once its arguments are valid. */
#define TERM_SHAPE_SUM(kind, term_type)                                                                          \
    TERM_INLINE_BODY tvo_status_t kind##_sum(const term_type *self, const tvo_jet_t *z, const tvo_time_jet_t *t, \
                                             tvo_jet_t *grad, tvo_hessian_t *hessian, uint8_t order)             \
    {                                                                                                            \
        RETURN_SHAPE_COPY(order, kind##_sum_shape, self, z, t, grad, hessian);                                   \
    }

/* A term kind's three entries (its tvo_term_t, internal/constraints.h) and their validation, from its parts:
 * kind##_fits(self, dim), its robots' outputs within dim; sum(self, z, t, grad, hessian, order), the
 * gradient jets and with hessian the closed form; kind##_max(self, y, t_s, max_value), the constraint's value
 * at y. terms_body: how the two gradient entries share their body (TERM_SHARED_BODY or TERM_INLINE_BODY). */
#define TERM_ENTRIES(kind, term_type, sum, terms_body)                                                           \
    terms_body tvo_status_t kind##_terms(const void *term, const tvo_jet_t *z, uint8_t dim,                      \
                                         const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,                \
                                         tvo_hessian_t *hessian)                                                 \
    {                                                                                                            \
        const term_type *self = (const term_type *)term;                                                         \
        if (self == NULL || z == NULL || t == NULL || grad == NULL) {                                            \
            return TVO_ERR_NULL;                                                                                 \
        }                                                                                                        \
        if (!kind##_fits(self, dim)) {                                                                           \
            return TVO_ERR_DIMENSION;                                                                            \
        }                                                                                                        \
        return sum(self, z, t, grad, hessian, order);                                                            \
    }                                                                                                            \
    tvo_status_t tvo_##kind##_gradient_jet(const void *term, const tvo_jet_t *z, uint8_t dim,                    \
                                           const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad)              \
    {                                                                                                            \
        return kind##_terms(term, z, dim, t, order, grad, NULL);                                                 \
    }                                                                                                            \
    tvo_status_t tvo_##kind##_gradient_hessian(const void *term, const tvo_jet_t *z, uint8_t dim,                \
                                               const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,          \
                                               tvo_hessian_t *hessian)                                           \
    {                                                                                                            \
        if (hessian == NULL) {                                                                                   \
            return TVO_ERR_NULL;                                                                                 \
        }                                                                                                        \
        return kind##_terms(term, z, dim, t, order, grad, hessian);                                              \
    }                                                                                                            \
    tvo_status_t tvo_##kind##_constraint_max(const void *term, const tvo_real_t *y, uint8_t primal_dim,          \
                                             tvo_real_t t_s, tvo_real_t *max_value)                              \
    {                                                                                                            \
        const term_type *self = (const term_type *)term;                                                         \
        if (self == NULL || y == NULL || max_value == NULL) {                                                    \
            return TVO_ERR_NULL;                                                                                 \
        }                                                                                                        \
        if (!kind##_fits(self, primal_dim)) {                                                                    \
            return TVO_ERR_DIMENSION;                                                                            \
        }                                                                                                        \
        return kind##_max(self, y, t_s, max_value);                                                              \
    }

/* The barrier's weight w(tau) of a term's single constraint value f, its schedule computed here (or the law's
 * shared one); dw_df where the closed form needs it (else NULL). */
TERM_INLINE_BODY tvo_status_t term_weight(const tvo_barrier_t *barrier, const tvo_time_jet_t *t, const tvo_jet_t *f,
                                          const uint8_t order, tvo_jet_t *w, tvo_real_t *dw_df)
{
    tvo_barrier_schedule_jet_t local;
    tvo_status_t st = TERM_BARRIER_SCHEDULE(barrier, t, order, &local);
    if (st == TVO_OK) {
        st = TERM_BARRIER_WEIGHT(barrier, barrier_schedule_of(t, &local), f, order, w, dw_df);
    }
    return st;
}

/* A term's robot output (x, y) at offset within dim. */
TERM_INLINE_BODY int output_fits(uint8_t offset, uint8_t dim)
{
    return (unsigned)offset + 2u <= dim;
}

/* kind##_fits of a term on one robot's output (at self->offset). */
#define ONE_ROBOT_FITS(kind, term_type)                                                                          \
    TERM_INLINE_BODY int kind##_fits(const term_type *self, uint8_t dim)                                         \
    {                                                                                                            \
        return output_fits(self->offset, dim);                                                                   \
    }

/* ---------------------------------------------------------------- distance bounds */

tvo_status_t tvo_distance_term_init(tvo_distance_term_t *term, const tvo_barrier_t *barrier, tvo_distance_kind_t kind,
                                    uint8_t robot_a, uint8_t robot_b, tvo_real_t bound_m, tvo_real_t bound_rate_mps)
{
    if (term == NULL || barrier == NULL) {
        return TVO_ERR_NULL;
    }
    if (robot_a >= TVO_MAX_ROBOTS || robot_b >= TVO_MAX_ROBOTS) {
        return TVO_ERR_DIMENSION;
    }
    if (!isfinite(bound_m) || !isfinite(bound_rate_mps)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (robot_a == robot_b || !(bound_m > TVO_R(0.0)) || (kind != TVO_DISTANCE_MIN && kind != TVO_DISTANCE_MAX) ||
        !(bound_m <= TVO_POSITION_LIMIT_M) || !(TVO_FABS(bound_rate_mps) <= TVO_POSITION_LIMIT_M)) {
        return TVO_ERR_PARAM;
    }
    term->barrier = barrier;
    term->kind = kind;
    term->offset_a = (uint8_t)(2u * robot_a);
    term->offset_b = (uint8_t)(2u * robot_b);
    term->bound_m = bound_m;
    term->bound_rate_mps = bound_rate_mps;
    return TVO_OK;
}

/* Sign of f in |D|^2: +1 for a maximum bound (|D|^2 - d^2), -1 for a minimum (d^2 - |D|^2). */
static tvo_real_t distance_sign(const tvo_distance_term_t *self)
{
    return (self->kind == TVO_DISTANCE_MAX) ? TVO_R(1.0) : TVO_R(-1.0);
}

/* The distance bound's gradient jets, and with hessian its closed-form Hessian
 * H += (dw/df) grad f grad f^T + w hess f, grad f = 2 sign (D, -D), hess f = 2 sign [I -I; -I I]. */
TVO_SHAPE_BODY tvo_status_t distance_sum_shape(const tvo_distance_term_t *self, const tvo_jet_t *z,
                                               const tvo_time_jet_t *t, tvo_jet_t *grad, tvo_hessian_t *hessian,
                                               const uint8_t order)
{
    tvo_jet_t bound;
    affine_time_jet(self->bound_m, self->bound_rate_mps, t, &bound);
    if (!(bound.c[0] > TVO_R(0.0))) {
        return TVO_ERR_PARAM; /* the schedule d(t) ran through zero */
    }
    const tvo_real_t sign = distance_sign(self);
    tvo_jet_t diff[2];
    tvo_jet_t f;
    tvo_jet_mul(&bound, &bound, order, &f);
    tvo_jet_scale(&f, -sign, order, &f);
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_t square;
        tvo_jet_sub(&z[self->offset_a + axis], &z[self->offset_b + axis], order, &diff[axis]);
        tvo_jet_mul(&diff[axis], &diff[axis], order, &square);
        tvo_jet_axpy(sign, &square, order, &f);
    }
    tvo_jet_t w;
    tvo_real_t dw_df = TVO_R(0.0);
    const tvo_status_t st = term_weight(self->barrier, t, &f, order, &w, hessian != NULL ? &dw_df : NULL);
    if (st != TVO_OK) {
        return st;
    }
    if (hessian == NULL) {
        for (uint8_t axis = 0; axis < 2u; ++axis) {
            /* grad_{y_a} f = 2 sign D, grad_{y_b} f = -2 sign D. */
            tvo_jet_t df;
            tvo_jet_scale(&diff[axis], TVO_R(2.0) * sign, order, &df);
            add_weighted(grad, (uint8_t)(self->offset_a + axis), &w, &df, order);
            tvo_jet_scale(&df, TVO_R(-1.0), order, &df);
            add_weighted(grad, (uint8_t)(self->offset_b + axis), &w, &df, order);
        }
        return TVO_OK;
    }
    /* Closed form: everything lives on the relative coordinates y_a - y_b. With v(e) = (e, -e) and
     * D = |D| d at tau = 0, the Hessian is (4 |D|^2 dw/df + 2 sign w) v(d) v(d)^T
     * + 2 sign w v(d_perp) v(d_perp)^T, and the gradient 2 sign w(tau) (alpha(tau) v(d) +
     * beta(tau) v(d_perp)) with alpha = d . D(tau), beta = d_perp . D(tau): two parts along
     * orthogonal directions, which a stiff maximum bound keeps apart (tvo/linsolve.h). */
    const tvo_real_t norm_sq = diff[0].c[0] * diff[0].c[0] + diff[1].c[0] * diff[1].c[0];
    tvo_real_t along[2] = {TVO_R(1.0), TVO_R(0.0)};
    if (norm_sq > TVO_R(0.0)) {
        const tvo_real_t inv_norm = TVO_R(1.0) / TVO_SQRT(norm_sq);
        along[0] = diff[0].c[0] * inv_norm;
        along[1] = diff[1].c[0] * inv_norm;
    }
    const tvo_real_t curvature = TVO_R(2.0) * sign * w.c[0];
    tvo_rank_one_t part;
    part.count = 4u;
    part.index[0] = self->offset_a;
    part.index[1] = (uint8_t)(self->offset_a + 1u);
    part.index[2] = self->offset_b;
    part.index[3] = (uint8_t)(self->offset_b + 1u);
    for (unsigned k = 0; k < 2u; ++k) {
        /* k = 0: along d; k = 1: across, d_perp = (-d_y, d_x). */
        const tvo_real_t e[2] = {k == 0u ? along[0] : -along[1], k == 0u ? along[1] : along[0]};
        part.value[0] = e[0];
        part.value[1] = e[1];
        part.value[2] = -e[0];
        part.value[3] = -e[1];
        part.weight = (k == 0u ? TVO_R(4.0) * norm_sq * dw_df : TVO_R(0.0)) + curvature;
        tvo_jet_t coordinate;
        tvo_jet_scale(&diff[0], e[0], order, &coordinate);
        tvo_jet_axpy(e[1], &diff[1], order, &coordinate);
        tvo_jet_mul(&w, &coordinate, order, &part.gradient);
        tvo_jet_scale(&part.gradient, TVO_R(2.0) * sign, order, &part.gradient);
        tvo_hessian_add(hessian, &part, grad, order);
    }
    return TVO_OK;
}

/* The bound's robots' outputs within dim. */
TERM_INLINE_BODY int distance_fits(const tvo_distance_term_t *self, uint8_t dim)
{
    return output_fits(self->offset_a, dim) && output_fits(self->offset_b, dim);
}

/* The bound's value at y (one copy: the pair's sides call it too). */
TERM_SHARED_BODY tvo_status_t distance_max(const tvo_distance_term_t *self, const tvo_real_t *y, tvo_real_t t_s,
                                           tvo_real_t *max_value)
{
    const tvo_real_t dx = y[self->offset_a] - y[self->offset_b];
    const tvo_real_t dy = y[self->offset_a + 1u] - y[self->offset_b + 1u];
    const tvo_real_t bound = self->bound_m + self->bound_rate_mps * t_s;
    *max_value = distance_sign(self) * (dx * dx + dy * dy - bound * bound);
    return TVO_OK;
}

TERM_SHAPE_SUM(distance, tvo_distance_term_t)
TERM_ENTRIES(distance, tvo_distance_term_t, distance_sum, TERM_SHARED_BODY)

#if TVO_BLOCK_SOLVE
/* ---------------------------------------------------------------- a distance bound's two sides */

/* What a bound's two sides sum to at tau = 0 and along the jet: the gradient is weight(tau) D(tau), the
 * Hessian the two parts along and across D's direction. */
typedef struct {
    tvo_jet_t diff[2];         /* D = y_a - y_b */
    tvo_jet_t weight;          /* sum over the sides of 2 sign w(tau) */
    tvo_real_t along[2];       /* D's direction at tau = 0 */
    tvo_real_t along_weight;   /* the sides' curvature along it, and across it */
    tvo_real_t across_weight;
} distance_pair_sum_t;

/* A bound's minimum and maximum (pair[0], pair[1]: one pair of robots) in one evaluation: their robots'
 * difference, its size and direction computed once, their weights summed into sum, their gradients added
 * as one; with hessian (when neither part is stiff) their Hessians as one 2 x 2 block
 * (tvo_hessian_add_pair). 0 in *added: one part was stiff (or the matrix is dense), nothing added; sum
 * holds what the parts need. */
TVO_SHAPE_BODY tvo_status_t distance_pair_shape(const tvo_distance_term_t *pair, const tvo_jet_t *z,
                                                const tvo_time_jet_t *t, tvo_jet_t *grad, tvo_hessian_t *hessian,
                                                distance_pair_sum_t *sum, int *added, const uint8_t order)
{
    const uint8_t a = pair[0].offset_a;
    const uint8_t b = pair[0].offset_b;
    tvo_jet_t *diff = sum->diff;
    tvo_jet_t size; /* |D|^2 */
    tvo_jet_sub(&z[a], &z[b], order, &diff[0]);
    tvo_jet_sub(&z[a + 1u], &z[b + 1u], order, &diff[1]);
    tvo_jet_mul(&diff[0], &diff[0], order, &size);
    {
        tvo_jet_t square;
        tvo_jet_mul(&diff[1], &diff[1], order, &square);
        tvo_jet_add(&size, &square, order, &size);
    }
    tvo_barrier_schedule_jet_t local;
    tvo_status_t st = TERM_BARRIER_SCHEDULE(pair[0].barrier, t, order, &local);
    const tvo_barrier_schedule_jet_t *schedule = barrier_schedule_of(t, &local);
    if (st != TVO_OK) {
        return st;
    }
    const tvo_real_t norm_sq = size.c[0];
    tvo_jet_constant(TVO_R(0.0), &sum->weight);
    sum->along_weight = TVO_R(0.0);
    sum->across_weight = TVO_R(0.0);
    for (unsigned side = 0; side < 2u; ++side) {
        const tvo_distance_term_t *self = &pair[side];
        tvo_jet_t f; /* sign (|D|^2 - d^2) */
        affine_time_jet(self->bound_m, self->bound_rate_mps, t, &f);
        if (!(f.c[0] > TVO_R(0.0))) {
            return TVO_ERR_PARAM; /* the schedule d(t) ran through zero */
        }
        const tvo_real_t sign = distance_sign(self);
        tvo_jet_mul(&f, &f, order, &f);
        tvo_jet_sub(&size, &f, order, &f);
        tvo_jet_scale(&f, sign, order, &f);
        tvo_jet_t w;
        tvo_real_t dw_df = TVO_R(0.0);
        st = TERM_BARRIER_WEIGHT(self->barrier, schedule, &f, order, &w, hessian != NULL ? &dw_df : NULL);
        if (st != TVO_OK) {
            return st;
        }
        const tvo_real_t curvature = TVO_R(2.0) * sign * w.c[0];
        sum->along_weight += TVO_R(4.0) * norm_sq * dw_df + curvature;
        sum->across_weight += curvature;
        tvo_jet_axpy(TVO_R(2.0) * sign, &w, order, &sum->weight);
    }
    sum->along[0] = TVO_R(1.0);
    sum->along[1] = TVO_R(0.0);
    if (norm_sq > TVO_R(0.0)) {
        const tvo_real_t inv_norm = TVO_R(1.0) / TVO_SQRT(norm_sq);
        sum->along[0] = diff[0].c[0] * inv_norm;
        sum->along[1] = diff[1].c[0] * inv_norm;
    }
    *added = hessian == NULL || tvo_hessian_add_pair(hessian, a, b, sum->along, sum->along_weight, sum->across_weight);
    if (*added) {
        /* The gradient: weight(tau) D(tau) into robot a's outputs, minus it into b's. */
        for (unsigned axis = 0; axis < 2u; ++axis) {
            tvo_jet_t product;
            tvo_jet_mul(&sum->weight, &diff[axis], order, &product);
            tvo_jet_add(&grad[a + axis], &product, order, &grad[a + axis]);
            tvo_jet_sub(&grad[b + axis], &product, order, &grad[b + axis]);
        }
    }
    return TVO_OK;
}

/* The pair's two parts, as tvo_hessian_add takes them, when one is too stiff for the block (or the matrix is
 * dense: an objective whose plan was dropped): the single bound's parts with the sides' weights summed
 * (they lie along the same two directions). */
TVO_COLD_BODY void distance_pair_parts(const tvo_distance_term_t *pair, const distance_pair_sum_t *sum,
                                       uint8_t order, tvo_jet_t *grad, tvo_hessian_t *hessian)
{
    tvo_rank_one_t part;
    part.count = 4u;
    part.index[0] = pair[0].offset_a;
    part.index[1] = (uint8_t)(pair[0].offset_a + 1u);
    part.index[2] = pair[0].offset_b;
    part.index[3] = (uint8_t)(pair[0].offset_b + 1u);
    for (unsigned k = 0; k < 2u; ++k) {
        /* k = 0: along d; k = 1: across, d_perp = (-d_y, d_x). */
        const tvo_real_t e0 = k == 0u ? sum->along[0] : -sum->along[1];
        const tvo_real_t e1 = k == 0u ? sum->along[1] : sum->along[0];
        part.value[0] = e0;
        part.value[1] = e1;
        part.value[2] = -e0;
        part.value[3] = -e1;
        part.weight = k == 0u ? sum->along_weight : sum->across_weight;
        tvo_jet_t coordinate;
        tvo_jet_scale(&sum->diff[0], e0, order, &coordinate);
        tvo_jet_axpy(e1, &sum->diff[1], order, &coordinate);
        tvo_jet_mul(&sum->weight, &coordinate, order, &part.gradient);
        tvo_hessian_add(hessian, &part, grad, order);
    }
}

/* In its own frame, apart from the parts'. */
TERM_SHARED_BODY tvo_status_t distance_pair_sum(const tvo_distance_term_t *pair, const tvo_jet_t *z,
                                                const tvo_time_jet_t *t, uint8_t order, tvo_jet_t *grad,
                                                tvo_hessian_t *hessian, distance_pair_sum_t *sum, int *added)
{
    RETURN_SHAPE_COPY(order, distance_pair_shape, pair, z, t, grad, hessian, sum, added);
}

/* One pair of robots, within dim. */
TERM_INLINE_BODY int distance_pair_fits(const tvo_distance_term_t *pair, uint8_t dim)
{
    return distance_fits(&pair[0], dim) && pair[1].offset_a == pair[0].offset_a && pair[1].offset_b == pair[0].offset_b;
}

/* The pair's gradient, and its Hessian as one block (or, a part stiff or the matrix dense, as two parts). */
TERM_INLINE_BODY tvo_status_t distance_pair_gradient(const tvo_distance_term_t *pair, const tvo_jet_t *z,
                                                  const tvo_time_jet_t *t, tvo_jet_t *grad, tvo_hessian_t *hessian,
                                                  uint8_t order)
{
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    distance_pair_sum_t sum;
    int added = 0;
    const tvo_status_t st = distance_pair_sum(pair, z, t, order, grad, hessian, &sum, &added);
    if (st == TVO_OK && !added) {
        distance_pair_parts(pair, &sum, order, grad, hessian); /* a stiff part, or a dense matrix */
    }
    return st;
}

/* The larger side's value; one that is not finite shows. */
static tvo_status_t distance_pair_max(const tvo_distance_term_t *pair, const tvo_real_t *y, tvo_real_t t_s,
                                      tvo_real_t *max_value)
{
    tvo_real_t high = TVO_R(0.0);
    tvo_status_t st = distance_max(&pair[0], y, t_s, max_value);
    if (st == TVO_OK) {
        st = distance_max(&pair[1], y, t_s, &high);
    }
    if (st == TVO_OK && (high > *max_value || !isfinite(high))) {
        *max_value = high;
    }
    return st;
}

TERM_ENTRIES(distance_pair, tvo_distance_term_t, distance_pair_gradient, TERM_INLINE_BODY)
#endif

/* ---------------------------------------------------------------- half-spaces */

tvo_status_t tvo_halfspace_term_init(tvo_halfspace_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                     const tvo_real_t normal[2], const tvo_real_t normal_rate[2], tvo_real_t bound_m,
                                     tvo_real_t bound_rate_mps)
{
    if (term == NULL || barrier == NULL || normal == NULL || normal_rate == NULL) {
        return TVO_ERR_NULL;
    }
    if (robot >= TVO_MAX_ROBOTS) {
        return TVO_ERR_DIMENSION;
    }
    if (!finite2(normal) || !finite2(normal_rate) || !isfinite(bound_m) || !isfinite(bound_rate_mps)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (normal[0] == TVO_R(0.0) && normal[1] == TVO_R(0.0)) {
        return TVO_ERR_PARAM;
    }
    if (!within2(normal) || !within2(normal_rate) || !(TVO_FABS(bound_m) <= TVO_POSITION_LIMIT_M) ||
        !(TVO_FABS(bound_rate_mps) <= TVO_POSITION_LIMIT_M)) {
        return TVO_ERR_PARAM; /* beyond the workspace (tvo/config.h) */
    }
    term->barrier = barrier;
    term->offset = (uint8_t)(2u * robot);
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        term->normal[axis] = normal[axis];
        term->normal_rate[axis] = normal_rate[axis];
    }
    term->bound_m = bound_m;
    term->bound_rate_mps = bound_rate_mps;
    return TVO_OK;
}

/* The half-space's gradient jets, and with hessian its closed form H += (dw/df) a a^T (f is affine). */
TVO_SHAPE_BODY tvo_status_t halfspace_sum_shape(const tvo_halfspace_term_t *self, const tvo_jet_t *z,
                                                const tvo_time_jet_t *t, tvo_jet_t *grad, tvo_hessian_t *hessian,
                                                const uint8_t order)
{
    tvo_jet_t normal[2];
    tvo_jet_t f;
    affine_time_jet(-self->bound_m, -self->bound_rate_mps, t, &f);
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_t product;
        affine_time_jet(self->normal[axis], self->normal_rate[axis], t, &normal[axis]);
        tvo_jet_mul(&normal[axis], &z[self->offset + axis], order, &product);
        tvo_jet_add(&f, &product, order, &f);
    }
    tvo_jet_t w;
    tvo_real_t dw_df = TVO_R(0.0);
    const tvo_status_t st = term_weight(self->barrier, t, &f, order, &w, hessian != NULL ? &dw_df : NULL);
    if (st != TVO_OK) {
        return st;
    }
    if (hessian == NULL) {
        for (uint8_t axis = 0; axis < 2u; ++axis) {
            add_weighted(grad, (uint8_t)(self->offset + axis), &w, &normal[axis], order);
        }
        return TVO_OK;
    }
    /* Closed form: the part along a = a(t) carries curvature dw/df a a^T and gradient w(tau) a; the
     * normal's own motion, w(tau) (a(tau) - a), goes into the gradient as it is. */
    tvo_rank_one_t part;
    part.weight = dw_df;
    part.count = 2u;
    part.index[0] = self->offset;
    part.index[1] = (uint8_t)(self->offset + 1u);
    part.value[0] = normal[0].c[0];
    part.value[1] = normal[1].c[0];
    part.gradient = w;
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_t motion = normal[axis];
        motion.c[0] = TVO_R(0.0);
        add_weighted(grad, (uint8_t)(self->offset + axis), &w, &motion, order);
    }
    tvo_hessian_add(hessian, &part, grad, order);
    return TVO_OK;
}

ONE_ROBOT_FITS(halfspace, tvo_halfspace_term_t)

static tvo_status_t halfspace_max(const tvo_halfspace_term_t *self, const tvo_real_t *y, tvo_real_t t_s,
                                  tvo_real_t *max_value)
{
    tvo_real_t f = -(self->bound_m + self->bound_rate_mps * t_s);
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        f += (self->normal[axis] + self->normal_rate[axis] * t_s) * y[self->offset + axis];
    }
    *max_value = f;
    return TVO_OK;
}

TERM_SHAPE_SUM(halfspace, tvo_halfspace_term_t)
TERM_ENTRIES(halfspace, tvo_halfspace_term_t, halfspace_sum, TERM_SHARED_BODY)

/* ---------------------------------------------------------------- local free space among disks */

tvo_real_t tvo_disk_clearance(const tvo_disk_t *obstacle, tvo_real_t robot_radius_m, const tvo_real_t position_m[2])
{
    if (obstacle == NULL || position_m == NULL) {
        return TVO_R(0.0);
    }
    const tvo_real_t dx = position_m[0] - obstacle->center_m[0];
    const tvo_real_t dy = position_m[1] - obstacle->center_m[1];
    return TVO_SQRT(dx * dx + dy * dy) - robot_radius_m - obstacle->radius_m;
}

tvo_status_t tvo_free_space_term_init(tvo_free_space_term_t *term, const tvo_barrier_t *barrier, uint8_t robot,
                                      tvo_real_t robot_radius_m, const tvo_disk_t *obstacles, uint8_t count,
                                      int16_t *bad_obstacle)
{
    int16_t unused;
    int16_t *const culprit = (bad_obstacle != NULL) ? bad_obstacle : &unused;
    *culprit = -1;
    if (term == NULL || barrier == NULL || obstacles == NULL) {
        return TVO_ERR_NULL;
    }
    if (robot >= TVO_MAX_ROBOTS || count == 0u || count > TVO_MAX_OBSTACLES) {
        return TVO_ERR_DIMENSION;
    }
    if (!isfinite(robot_radius_m)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (robot_radius_m < TVO_R(0.0) || !(robot_radius_m <= TVO_POSITION_LIMIT_M)) {
        return TVO_ERR_PARAM;
    }
    for (uint8_t i = 0; i < count; ++i) {
        *culprit = (int16_t)i;
        if (!finite2(obstacles[i].center_m) || !isfinite(obstacles[i].radius_m)) {
            return TVO_ERR_NOT_FINITE;
        }
        if (!(obstacles[i].radius_m > TVO_R(0.0)) || !(obstacles[i].radius_m <= TVO_POSITION_LIMIT_M) ||
            !within2(obstacles[i].center_m)) {
            return TVO_ERR_PARAM;
        }
        for (uint8_t j = 0; j < i; ++j) {
            /* The local free space is built for non-intersecting obstacles. */
            if (tvo_disk_clearance(&obstacles[j], obstacles[i].radius_m, obstacles[i].center_m) <= TVO_R(0.0)) {
                return TVO_ERR_PARAM;
            }
        }
    }
    *culprit = -1;
    memset(term, 0, sizeof(*term));
    term->barrier = barrier;
    term->offset = (uint8_t)(2u * robot);
    term->obstacle_count = count;
    term->robot_radius_m = robot_radius_m;
    for (uint8_t i = 0; i < count; ++i) {
        term->obstacle[i] = obstacles[i];
    }
    return TVO_OK;
}

/* The separating half-plane a^T y <= b of obstacle i for a robot centred at y_c. */
static tvo_status_t free_space_plane(const tvo_free_space_term_t *self, uint8_t i, const tvo_real_t y_c[2],
                                     tvo_real_t normal[2], tvo_real_t *bound)
{
    const tvo_disk_t *o = &self->obstacle[i];
    normal[0] = o->center_m[0] - y_c[0];
    normal[1] = o->center_m[1] - y_c[1];
    const tvo_real_t dist_sq = normal[0] * normal[0] + normal[1] * normal[1];
    const tvo_real_t dist = TVO_SQRT(dist_sq);
    if (!(dist > FREE_SPACE_MIN_CENTER_DISTANCE_M)) {
        return TVO_ERR_NUMERIC;
    }
    const tvo_real_t r = self->robot_radius_m;
    const tvo_real_t theta = TVO_R(0.5) - (o->radius_m * o->radius_m - r * r) / (TVO_R(2.0) * dist_sq);
    tvo_real_t b = TVO_R(0.0);
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        const tvo_real_t point = theta * o->center_m[axis] + (TVO_R(1.0) - theta) * y_c[axis] - r * normal[axis] / dist;
        b += normal[axis] * point;
    }
    *bound = b;
    return TVO_OK;
}

/* The free space's gradient jets, and with hessian its closed form H += sum_i (dw_i/df) a_i a_i^T
 * (the planes are frozen at y_c: affine in y). The schedules are shared by every plane. */
TVO_SHAPE_BODY tvo_status_t free_space_sum_shape(const tvo_free_space_term_t *self, const tvo_jet_t *z,
                                                 const tvo_time_jet_t *t, tvo_jet_t *grad, tvo_hessian_t *hessian,
                                                 const uint8_t order)
{
    tvo_barrier_schedule_jet_t local;
    tvo_status_t st = TERM_BARRIER_SCHEDULE(self->barrier, t, order, &local);
    const tvo_barrier_schedule_jet_t *schedule = barrier_schedule_of(t, &local);
    if (st != TVO_OK) {
        return st;
    }
    /* y_c frozen at the current output: the planes do not move along the jet (see the header). */
    const uint8_t o = self->offset;
    const tvo_real_t y_c[2] = {z[o].c[0], z[o + 1u].c[0]};
    for (uint8_t i = 0; i < self->obstacle_count && i < TVO_MAX_OBSTACLES; ++i) {
        tvo_real_t normal[2];
        tvo_real_t bound;
        st = free_space_plane(self, i, y_c, normal, &bound);
        if (st != TVO_OK) {
            return st;
        }
        tvo_jet_t f;
        tvo_jet_constant(-bound, &f);
        tvo_jet_axpy(normal[0], &z[o], order, &f);
        tvo_jet_axpy(normal[1], &z[o + 1u], order, &f);
        tvo_jet_t w;
        tvo_real_t dw_df = TVO_R(0.0);
        st = TERM_BARRIER_WEIGHT(self->barrier, schedule, &f, order, &w, hessian != NULL ? &dw_df : NULL);
        if (st != TVO_OK) {
            return st;
        }
        if (hessian == NULL) {
            tvo_jet_axpy(normal[0], &w, order, &grad[o]);
            tvo_jet_axpy(normal[1], &w, order, &grad[o + 1u]);
            continue;
        }
        /* Closed form: the plane's part, curvature dw/df n n^T and gradient w(tau) n. */
        tvo_rank_one_t part;
        part.weight = dw_df;
        part.gradient = w;
        part.count = 2u;
        part.index[0] = o;
        part.index[1] = (uint8_t)(o + 1u);
        part.value[0] = normal[0];
        part.value[1] = normal[1];
        tvo_hessian_add(hessian, &part, grad, order);
    }
    return TVO_OK;
}

ONE_ROBOT_FITS(free_space, tvo_free_space_term_t)

/* The worst plane's value at y (the planes through y itself). */
static tvo_status_t free_space_max(const tvo_free_space_term_t *self, const tvo_real_t *y, tvo_real_t t_s,
                                   tvo_real_t *max_value)
{
    (void)t_s;
    const tvo_real_t y_c[2] = {y[self->offset], y[self->offset + 1u]};
    tvo_real_t worst = TVO_R(0.0);
    for (uint8_t i = 0; i < self->obstacle_count && i < TVO_MAX_OBSTACLES; ++i) {
        tvo_real_t normal[2];
        tvo_real_t bound;
        const tvo_status_t st = free_space_plane(self, i, y_c, normal, &bound);
        if (st != TVO_OK) {
            return st;
        }
        tvo_real_t f = normal[0] * y_c[0] + normal[1] * y_c[1] - bound;
        /* At y = y_c the plane gives f = -c (c + 2 r_i) / 2 with c the clearance: positive for every
         * collision with -2 r_i < c < 0, but negative again for a robot covering a smaller obstacle
         * (c < -2 r_i). The s0 rule must see every collision as a violation, so a colliding robot
         * reports |f|: the plane's own value wherever that is already right. */
        if (tvo_disk_clearance(&self->obstacle[i], self->robot_radius_m, y_c) < TVO_R(0.0)) {
            f = TVO_FABS(f);
        }
        if (i == 0u || f > worst) {
            worst = f;
        }
    }
    *max_value = worst;
    return TVO_OK;
}

TERM_SHAPE_SUM(free_space, tvo_free_space_term_t)
TERM_ENTRIES(free_space, tvo_free_space_term_t, free_space_sum, TERM_SHARED_BODY)
