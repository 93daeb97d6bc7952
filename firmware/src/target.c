/* Moving targets and their time derivatives; see tvo/target.h. */
#include "tvo/target.h"

#include <string.h>

static int all_finite(const tvo_real_t *v, size_t n)
{
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(v[i])) {
            return 0;
        }
    }
    return 1;
}

tvo_status_t tvo_target_init_polynomial(tvo_target_t *target,
                                        const tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1])
{
    if (target == NULL || coeff == NULL) {
        return TVO_ERR_NULL;
    }
    if (!all_finite(&coeff[0][0], 2u * (TVO_POLY_MAX_DEGREE + 1u))) {
        return TVO_ERR_NOT_FINITE;
    }
    memset(target, 0, sizeof(*target));
    target->kind = TVO_TARGET_POLYNOMIAL;
    memcpy(target->u.polynomial.coeff, coeff, sizeof(target->u.polynomial.coeff));
    return TVO_OK;
}

tvo_status_t tvo_target_init_ellipse(tvo_target_t *target, const tvo_target_ellipse_t *ellipse)
{
    if (target == NULL || ellipse == NULL) {
        return TVO_ERR_NULL;
    }
    const tvo_real_t values[7] = {ellipse->center_m[0], ellipse->center_m[1], ellipse->semi_axis_m[0],
                                  ellipse->semi_axis_m[1], ellipse->omega_radps, ellipse->phase_rad,
                                  ellipse->rotation_rad};
    if (!all_finite(values, 7u)) {
        return TVO_ERR_NOT_FINITE;
    }
    if (!(ellipse->semi_axis_m[0] > TVO_R(0.0)) || !(ellipse->semi_axis_m[1] > TVO_R(0.0))) {
        return TVO_ERR_PARAM;
    }
    memset(target, 0, sizeof(*target));
    target->kind = TVO_TARGET_ELLIPSE;
    target->u.ellipse = *ellipse;
    /* The rotation is fixed: its cosine and sine once here, not at every evaluation. */
    target->rotation_cs[0] = TVO_COS(ellipse->rotation_rad);
    target->rotation_cs[1] = TVO_SIN(ellipse->rotation_rad);
    return TVO_OK;
}

tvo_status_t tvo_target_init_circle(tvo_target_t *target, const tvo_real_t center_m[2],
                                    tvo_real_t radius_m, tvo_real_t omega_radps, tvo_real_t phase_rad)
{
    if (target == NULL || center_m == NULL) {
        return TVO_ERR_NULL;
    }
    tvo_target_ellipse_t e;
    e.center_m[0] = center_m[0];
    e.center_m[1] = center_m[1];
    e.semi_axis_m[0] = radius_m;
    e.semi_axis_m[1] = radius_m;
    e.omega_radps = omega_radps;
    e.phase_rad = phase_rad;
    e.rotation_rad = TVO_R(0.0);
    const tvo_status_t st = tvo_target_init_ellipse(target, &e);
    if (st == TVO_OK) {
        target->kind = TVO_TARGET_CIRCLE;
    }
    return st;
}

tvo_status_t tvo_target_init_streamed(tvo_target_t *target)
{
    if (target == NULL) {
        return TVO_ERR_NULL;
    }
    memset(target, 0, sizeof(*target));
    target->kind = TVO_TARGET_STREAMED;
    target->u.streamed.has_sample = 0;
    return TVO_OK;
}

tvo_status_t tvo_target_stream_update(tvo_target_t *target, uint64_t stamp_ticks,
                                      const tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2])
{
    if (target == NULL || deriv == NULL) {
        return TVO_ERR_NULL;
    }
    if (target->kind != TVO_TARGET_STREAMED) {
        return TVO_ERR_PARAM;
    }
    if (!all_finite(&deriv[0][0], 2u * (TVO_STREAM_MAX_DERIV + 1u))) {
        return TVO_ERR_NOT_FINITE;
    }
    tvo_target_streamed_t *s = &target->u.streamed;
    if (s->has_sample && stamp_ticks <= s->stamp_ticks) {
        return TVO_ERR_OUT_OF_ORDER;
    }
    s->stamp_ticks = stamp_ticks;
    memcpy(s->deriv, deriv, sizeof(s->deriv));
    s->has_sample = 1;
    return TVO_OK;
}

static void polynomial_derivatives(const tvo_target_polynomial_t *p, tvo_real_t t_s, uint8_t order,
                                   tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    for (uint8_t j = 0; j <= order; ++j) {
        for (uint8_t axis = 0; axis < 2u; ++axis) {
            /* Horner on the j-th derivative: sum_{i>=j} A_i i!/(i-j)! t^(i-j). */
            tvo_real_t acc = TVO_R(0.0);
            for (int i = TVO_POLY_MAX_DEGREE; i >= (int)j; --i) {
                tvo_real_t falling = TVO_R(1.0);
                for (int m = 0; m < (int)j; ++m) {
                    falling *= (tvo_real_t)(i - m);
                }
                acc = acc * t_s + p->coeff[axis][i] * falling;
            }
            deriv[j][axis] = acc;
        }
    }
}

static void ellipse_derivatives(const tvo_target_ellipse_t *e, const tvo_real_t rotation_cs[2], tvo_real_t t_s,
                                uint8_t order, tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    const tvo_real_t phi = e->omega_radps * t_s + e->phase_rad;
    const tvo_real_t c = TVO_COS(phi);
    const tvo_real_t s = TVO_SIN(phi);
    /* d^j/dphi^j of (cos, sin) cycles with period 4. */
    const tvo_real_t dcos[4] = {c, -s, -c, s};
    const tvo_real_t dsin[4] = {s, c, -s, -c};
    const tvo_real_t cr = rotation_cs[0];
    const tvo_real_t sr = rotation_cs[1];
    tvo_real_t omega_pow = TVO_R(1.0);
    for (uint8_t j = 0; j <= order; ++j) {
        const tvo_real_t u = e->semi_axis_m[0] * dcos[j & 3u] * omega_pow;
        const tvo_real_t v = e->semi_axis_m[1] * dsin[j & 3u] * omega_pow;
        deriv[j][0] = cr * u - sr * v;
        deriv[j][1] = sr * u + cr * v;
        omega_pow *= e->omega_radps;
    }
    deriv[0][0] += e->center_m[0];
    deriv[0][1] += e->center_m[1];
}

static tvo_status_t streamed_derivatives(const tvo_target_streamed_t *s, const tvo_time_jet_t *t,
                                         uint8_t order, tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    if (!s->has_sample) {
        return TVO_ERR_TARGET_NOT_READY;
    }
    if (t->ticks < s->stamp_ticks) {
        return TVO_ERR_FUTURE_STAMP;
    }
    /* Exact age from integer ticks: no loss however long the run. */
    const tvo_real_t age_s = tvo_ticks_to_seconds(t->ticks - s->stamp_ticks, t->tick_hz);
    for (uint8_t j = 0; j <= order; ++j) {
        for (uint8_t axis = 0; axis < 2u; ++axis) {
            /* Taylor polynomial of the j-th derivative: sum_{i>=j} d_i age^(i-j) / (i-j)!, by Horner. */
            tvo_real_t acc = TVO_R(0.0);
            for (int i = TVO_STREAM_MAX_DERIV; i >= (int)j; --i) {
                acc = acc * age_s / (tvo_real_t)(i - (int)j + 1) + s->deriv[i][axis];
            }
            deriv[j][axis] = acc;
        }
    }
    return TVO_OK;
}

tvo_status_t tvo_target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    if (target == NULL || t == NULL || deriv == NULL) {
        return TVO_ERR_NULL;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    if (!isfinite(t->t_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    switch (target->kind) {
    case TVO_TARGET_POLYNOMIAL:
        polynomial_derivatives(&target->u.polynomial, t->t_s, order, deriv);
        return TVO_OK;
    case TVO_TARGET_CIRCLE:
    case TVO_TARGET_ELLIPSE:
        ellipse_derivatives(&target->u.ellipse, target->rotation_cs, t->t_s, order, deriv);
        return TVO_OK;
    case TVO_TARGET_STREAMED:
        return streamed_derivatives(&target->u.streamed, t, order, deriv);
    default:
        return TVO_ERR_PARAM;
    }
}

tvo_status_t tvo_target_jet(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order, tvo_jet_t out[2])
{
    if (target == NULL || t == NULL || out == NULL) {
        return TVO_ERR_NULL;
    }
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM;
    }
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    /* With time frozen (rate 0: Hessian columns) only the position enters the jet. */
    const uint8_t needed = (t->rate == TVO_R(0.0)) ? 0u : order;
    const tvo_status_t st = tvo_target_derivatives(target, t, needed, deriv);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_constant(TVO_R(0.0), &out[axis]);
        tvo_real_t scale = TVO_R(1.0);
        for (uint8_t j = 0; j <= needed; ++j) {
            out[axis].c[j] = deriv[j][axis] * scale;
            scale *= t->rate / (tvo_real_t)(j + 1u);
        }
    }
    return TVO_OK;
}
