/* Moving targets and their time derivatives; see tvo/target.h. */
#include "internal/target.h"

#include <string.h>

#include "shape.h"
#include "internal/target_kernel.h"
#include "internal/trig_kernel.h"

/* TVO_ERR_NOT_FINITE if one of the n values is not finite, else TVO_ERR_PARAM if one of the first
 * `limited` has |v_i| > limit, else TVO_OK. */
static __attribute__((noinline)) tvo_status_t check_values(const tvo_real_t *v, size_t n, size_t limited,
                                                           tvo_real_t limit)
{
    tvo_status_t st = TVO_OK;
    for (size_t i = 0; i < n; ++i) {
        if (!isfinite(v[i])) {
            return TVO_ERR_NOT_FINITE;
        }
        if (i < limited && !(TVO_FABS(v[i]) <= limit)) {
            st = TVO_ERR_PARAM;
        }
    }
    return st;
}

tvo_status_t tvo_target_init_polynomial(tvo_target_t *target,
                                        const tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1])
{
    if (target == NULL || coeff == NULL) {
        return TVO_ERR_NULL;
    }
    /* Its value at the epoch in the workspace, its coefficients within TVO_POLY_COEFF_LIMIT (wider). */
    const size_t count = 2u * (TVO_POLY_MAX_DEGREE + 1u);
    const tvo_status_t st = check_values(&coeff[0][0], count, count, TVO_POLY_COEFF_LIMIT);
    if (st != TVO_OK) {
        return st;
    }
    if (!(TVO_FABS(coeff[0][0]) <= TVO_POSITION_LIMIT_M) || !(TVO_FABS(coeff[1][0]) <= TVO_POSITION_LIMIT_M)) {
        return TVO_ERR_PARAM;
    }
    memset(target, 0, sizeof(*target));
    target->kind = TVO_TARGET_POLYNOMIAL;
    memcpy(target->u.polynomial.coeff, coeff, sizeof(target->u.polynomial.coeff));
    /* The highest power in use: evaluation skips the zero coefficients above it. */
    target->poly_degree = 0u;
    for (uint8_t j = 1; j <= TVO_POLY_MAX_DEGREE; ++j) {
        if (coeff[0][j] != TVO_R(0.0) || coeff[1][j] != TVO_R(0.0)) {
            target->poly_degree = j;
        }
    }
    return TVO_OK;
}

uint64_t tvo_target_turns_q64(double omega_radps)
{
    if (!isfinite(omega_radps)) {
        return 0u;
    }
    const double turns = omega_radps * 0.159154943091895335768883763372514362;
    const double frac = ldexp(turns - floor(turns), 64);
    return (frac >= 18446744073709551616.0 || !(frac >= 0.0)) ? 0u : (uint64_t)frac;
}

/* The fractional turns of an angle in Q0.64, at tvo_real_t's precision. */
static uint64_t turns_q64_of(tvo_real_t angle_rad)
{
    const tvo_real_t turns = angle_rad * TVO_INV_TWO_PI;
    const tvo_real_t frac = turns - TVO_FLOOR(turns);
#if TVO_USE_DOUBLE
    const double scaled = ldexp(frac, 64);
    return (scaled >= 18446744073709551616.0 || !(scaled >= 0.0)) ? 0u : (uint64_t)scaled;
#else
    const float scaled = frac * 4294967296.0f;
    return (scaled >= 4294967296.0f || !(scaled >= 0.0f)) ? 0u : (uint64_t)(uint32_t)scaled << 32;
#endif
}

tvo_status_t tvo_target_init_ellipse(tvo_target_t *target, const tvo_target_ellipse_t *ellipse)
{
    if (target == NULL || ellipse == NULL) {
        return TVO_ERR_NULL;
    }
    const tvo_real_t values[7] = {ellipse->center_m[0], ellipse->center_m[1], ellipse->semi_axis_m[0],
                                  ellipse->semi_axis_m[1], ellipse->omega_radps, ellipse->phase_rad,
                                  ellipse->rotation_rad};
    /* All seven finite; the centre and semi-axes (the first four) within the workspace. */
    const tvo_status_t st = check_values(values, 7u, 4u, TVO_POSITION_LIMIT_M);
    if (st == TVO_ERR_NOT_FINITE) {
        return st;
    }
    if (st != TVO_OK || !(ellipse->semi_axis_m[0] > TVO_R(0.0)) || !(ellipse->semi_axis_m[1] > TVO_R(0.0)) ||
        !(TVO_FABS(ellipse->omega_radps) <= TVO_TARGET_MAX_OMEGA_RADPS)) {
        return TVO_ERR_PARAM;
    }
    memset(target, 0, sizeof(*target));
    target->kind = TVO_TARGET_ELLIPSE;
    target->u.ellipse = *ellipse;
    /* The rotation is fixed: the rotated semi-axes once here, not at every evaluation. */
    tvo_real_t sin_rotation;
    tvo_real_t cos_rotation;
    tvo_sincos(ellipse->rotation_rad, &sin_rotation, &cos_rotation);
    target->axis_m[0][0] = ellipse->semi_axis_m[0] * cos_rotation;
    target->axis_m[0][1] = ellipse->semi_axis_m[0] * sin_rotation;
    target->axis_m[1][0] = -ellipse->semi_axis_m[1] * sin_rotation;
    target->axis_m[1][1] = ellipse->semi_axis_m[1] * cos_rotation;
    /* The phase runs in fixed point from whole seconds: exact after hours (see ellipse_derivatives). */
    target->phase0_q64 = turns_q64_of(ellipse->phase_rad);
    target->rate_q64 = (ellipse->rate_turns_q64 != 0u) ? ellipse->rate_turns_q64 : turns_q64_of(ellipse->omega_radps);
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
    e.rate_turns_q64 = 0u;
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
    const size_t count = 2u * (TVO_STREAM_MAX_DERIV + 1u);
    const tvo_status_t st = check_values(&deriv[0][0], count, count, TVO_POSITION_LIMIT_M);
    if (st != TVO_OK) {
        return st; /* not finite, or beyond the workspace (or a rate of it) */
    }
    tvo_target_streamed_t *s = &target->u.streamed;
    if (s->has_sample && stamp_ticks <= s->stamp_ticks) {
        return TVO_ERR_TICK_NOT_ADVANCING; /* the stamp does not advance past the sample's */
    }
    s->stamp_ticks = stamp_ticks;
    memcpy(s->deriv, deriv, sizeof(s->deriv));
    s->has_sample = 1;
    return TVO_OK;
}

static void polynomial_derivatives(const tvo_target_polynomial_t *p, uint8_t degree, tvo_real_t t_s, uint8_t order,
                                   tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    /* Taylor shift by repeated synthetic division: after pass j, b[j] = p^(j)(t) / j!, in
     * (order + 1) * degree multiply-adds over the coefficients actually used. */
    static const tvo_real_t factorial[4] = {TVO_R(1.0), TVO_R(1.0), TVO_R(2.0), TVO_R(6.0)};
    for (unsigned axis = 0; axis < 2u; ++axis) {
        tvo_real_t b[TVO_POLY_MAX_DEGREE + 1];
        for (unsigned i = 0; i <= degree; ++i) {
            b[i] = p->coeff[axis][i];
        }
        for (unsigned j = 0; j <= order; ++j) {
            if (j > degree) {
                deriv[j][axis] = TVO_R(0.0);
                continue;
            }
            for (unsigned i = degree; i > j; --i) {
                b[i - 1u] += t_s * b[i];
            }
            deriv[j][axis] = b[j] * factorial[j];
        }
    }
}

static tvo_status_t streamed_derivatives(const tvo_target_streamed_t *s, const tvo_time_jet_t *t,
                                         uint8_t order, tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    /* A controller's step never gets here with either: its loop holds first (target_ready_at). */
    if (!s->has_sample) {
        return TVO_ERR_NOT_INITIALIZED;
    }
    if (t->ticks < s->stamp_ticks) {
        return TVO_ERR_PARAM; /* before the sample's stamp: extrapolation is causal only */
    }
    /* The age from integer ticks: exact however long the run. Beyond 2^32 ticks (50 days at 1 kHz,
     * 71.6 min at the edge's 1 MHz) one rounding of each operand, which costs nothing at float's
     * precision and needs no 64-bit division. */
    const uint64_t age_ticks = t->ticks - s->stamp_ticks;
    tvo_real_t age_s = TVO_R(0.0);
    if (age_ticks <= UINT32_MAX) {
        age_s = tvo_ticks_to_seconds32((uint32_t)age_ticks, t->tick_hz);
    } else if (t->tick_hz != 0u) {
        age_s = (tvo_real_t)age_ticks / (tvo_real_t)t->tick_hz;
    }
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
    return target_derivatives(target, t, order, deriv);
}

tvo_status_t target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    TVO_ASSERT(target != NULL && t != NULL && deriv != NULL);
    if (order > TVO_JET_MAX_ORDER) {
        return TVO_ERR_PARAM; /* checked by the callers; kept, as it bounds the loops below */
    }
    switch (target->kind) {
    case TVO_TARGET_POLYNOMIAL:
        polynomial_derivatives(&target->u.polynomial, target->poly_degree, t->t_s, order, deriv);
        return TVO_OK;
    case TVO_TARGET_CIRCLE:
    case TVO_TARGET_ELLIPSE:
        if (t->tick_hz == 0u || t->frac_ticks >= t->tick_hz) {
            return TVO_ERR_PARAM; /* the phase needs the exact split of tvo_time_jet_at */
        }
#if TVO_SHAPE_COPIES
        if (order == TVO_SHAPE_ORDER) {
            ellipse_derivatives(target, t, TVO_SHAPE_ORDER, deriv); /* the k = 2 law's: its cycle unrolled */
            return TVO_OK;
        }
#endif
        ellipse_derivatives(target, t, order, deriv);
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
    if (!isfinite(t->t_s)) {
        return TVO_ERR_NOT_FINITE;
    }
    return target_jet(target, t, order, out);
}
