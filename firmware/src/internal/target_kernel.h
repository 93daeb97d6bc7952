/*
 * Internal: a target's derivatives and jet, unchecked (TVO_ASSERT in debug builds), for a caller that
 * has checked the pointers and that t's time is finite (the tracking term's closed form).
 * tvo_target_derivatives and tvo_target_jet check their arguments, then call these.
 */
#ifndef TVO_TARGET_KERNEL_H
#define TVO_TARGET_KERNEL_H

#include "internal/target.h"
#include "shape.h"
#include "internal/trig_kernel.h"

/* deriv[j] = y_d^(j)(t), j = 0..order: an order above TVO_JET_MAX_ORDER and the kind's misuses (a
 * streamed target without a sample or asked before its stamp, which a step's target_ready_at rules
 * out first; a time jet without the exact split a periodic phase needs) are still refused. */
tvo_status_t target_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2]);

/* y_d(t(tau)) as one jet per axis, for a target and time as above (inline: its caller's frame holds
 * the derivatives). */
static inline tvo_status_t target_jet(const tvo_target_t *target, const tvo_time_jet_t *t, uint8_t order,
                                      tvo_jet_t out[2])
{
    TVO_ASSERT(target != NULL && t != NULL && out != NULL);
    tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2];
    /* With time frozen (rate 0: Hessian columns) only the position enters the jet. */
    const uint8_t needed = (t->rate == TVO_R(0.0)) ? 0u : order;
    const tvo_status_t st = target_derivatives(target, t, needed, deriv);
    if (st != TVO_OK) {
        return st;
    }
    for (uint8_t axis = 0; axis < 2u; ++axis) {
        tvo_jet_constant(TVO_R(0.0), &out[axis]);
        tvo_real_t scale = TVO_R(1.0);
        for (uint8_t j = 0; j <= needed && j <= TVO_JET_MAX_ORDER; ++j) {
            out[axis].c[j] = deriv[j][axis] * scale;
            scale *= t->rate / (tvo_real_t)(j + 1u);
        }
    }
    return TVO_OK;
}

TVO_SHAPE_BODY void ellipse_derivatives(const tvo_target_t *target, const tvo_time_jet_t *t, const uint8_t order,
                                        tvo_real_t deriv[TVO_JET_MAX_ORDER + 1][2])
{
    const tvo_target_ellipse_t *e = &target->u.ellipse;
    /* phi = phase + omega t: whole seconds advance the Q0.64 phase exactly (wrapping is whole
     * turns), the fraction of a second adds a small angle in tvo_real_t. */
    const uint64_t turns = target->phase0_q64 + target->rate_q64 * (uint64_t)t->whole_s;
    const tvo_real_t frac_s = t->frac_s; /* frac_ticks / tick_hz */
    tvo_real_t s;
    tvo_real_t c;
#if TVO_SHAPE_COPIES && !TVO_USE_DOUBLE
    /* tvo_sincos_turns in this body: the angle is within its limit (|omega| <= TVO_TARGET_MAX_OMEGA_RADPS,
     * frac_s < 1; init checked), and its check would turn an angle beyond into NaN all the same. */
    const float extra_rad = e->omega_radps * frac_s;
    if (TVO_FABS(extra_rad) <= TVO_SINCOS_FAST_LIMIT_RAD) {
        sincos_turns_body(turns, extra_rad, &s, &c);
    } else {
        tvo_sincos_turns(turns, extra_rad, &s, &c);
    }
#else
    tvo_sincos_turns(turns, e->omega_radps * frac_s, &s, &c);
#endif
    /* y_d = centre + A cos phi + B sin phi with the rotated semi-axes A, B (from init); the
     * derivatives of (cos, sin) cycle with period 4 and scale by omega^j. */
    const tvo_real_t dcos[4] = {c, -s, -c, s};
    const tvo_real_t dsin[4] = {s, c, -s, -c};
    /* In locals: deriv's stores could alias the target, which would be read again at every order. */
    const tvo_real_t a0 = target->axis_m[0][0];
    const tvo_real_t a1 = target->axis_m[0][1];
    const tvo_real_t b0 = target->axis_m[1][0];
    const tvo_real_t b1 = target->axis_m[1][1];
    const tvo_real_t omega = e->omega_radps;
    deriv[0][0] = (a0 * c + b0 * s) + e->center_m[0];
    deriv[0][1] = (a1 * c + b1 * s) + e->center_m[1];
    tvo_real_t omega_pow = omega;
    TVO_UNROLL_SMALL
    for (unsigned j = 1; j <= order; ++j) {
        const tvo_real_t u = dcos[j & 3u] * omega_pow;
        const tvo_real_t v = dsin[j & 3u] * omega_pow;
        deriv[j][0] = a0 * u + b0 * v;
        deriv[j][1] = a1 * u + b1 * v;
        omega_pow *= omega;
    }
}


#endif /* TVO_TARGET_KERNEL_H */
