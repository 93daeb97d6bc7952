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

#ifdef __cplusplus
}
#endif

#endif /* TVO_TRIG_H */
