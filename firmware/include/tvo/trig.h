/*
 * Sine and cosine together, for the hot path.
 *
 * The step needs a handful of (sin, cos) pairs of the same angles; libm's sinf and cosf each reduce
 * the argument again and cost ~70 instructions on a Cortex-M4F. tvo_sincos reduces once (Cody-Waite,
 * three-part pi/2) and evaluates both minimax polynomials on [-pi/4, pi/4]: within 2 float32 ulps of
 * the exact values for |angle| <= TVO_SINCOS_FAST_LIMIT_RAD; beyond it, an exact reduction by the
 * bits of 2/pi (Payne-Hanek) instead of libm, whose huge-argument path needs over 400 bytes of stack
 * on Cortex-M. The double build uses libm.
 * tvo_sincos_turns takes the angle as a fraction of a turn in Q0.64, exactly reduced by its bits
 * (periodic targets keep their phase in fixed point so hours of time lose nothing).
 */
#ifndef TVO_TRIG_H
#define TVO_TRIG_H

#include "tvo/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Beyond this the Cody-Waite reduction would lose bits: the exact reduction takes over. */
#define TVO_SINCOS_FAST_LIMIT_RAD TVO_R(8192.0)

/** *sin_out = sin(angle_rad), *cos_out = cos(angle_rad). NaN/Inf give NaN, as libm does. */
void tvo_sincos(tvo_real_t angle_rad, tvo_real_t *sin_out, tvo_real_t *cos_out);

/**
 * sin and cos of 2 pi turns_q64 / 2^64 + extra_rad: a phase in Q0.64 turns plus a small angle
 * (|extra_rad| <= 2 pi keeps full precision). |extra_rad| > TVO_SINCOS_FAST_LIMIT_RAD, or NaN,
 * gives NaN: the periodic targets' path has no huge-angle reduction (TVO_TARGET_MAX_OMEGA_RADPS).
 */
void tvo_sincos_turns(uint64_t turns_q64, tvo_real_t extra_rad, tvo_real_t *sin_out, tvo_real_t *cos_out);

#ifdef __cplusplus
}
#endif

#endif /* TVO_TRIG_H */
