/*
 * Internal: trig's functions (the types are in tvo/trig.h, which the instance structs need).
 * Not installed; unchecked: callers pass valid arguments (TVO_ASSERT in debug builds).
 */
#ifndef TVO_INTERNAL_TRIG_H
#define TVO_INTERNAL_TRIG_H

#include "tvo/trig.h"
#include "internal/assert.h"

#ifdef __cplusplus
extern "C" {
#endif

/** *sin_out = sin(angle_rad), *cos_out = cos(angle_rad). NaN/Inf give NaN, as libm does. */
void tvo_sincos(tvo_real_t angle_rad, tvo_real_t *sin_out, tvo_real_t *cos_out);

/**
 * sin and cos of 2 pi turns_q64 / 2^64 + extra_rad: a phase in Q0.64 turns plus a small angle
 * (|extra_rad| <= 2 pi keeps full precision). |extra_rad| > TVO_SINCOS_FAST_LIMIT_RAD, or NaN,
 * gives NaN: the periodic targets' path has no huge-angle reduction (TVO_TARGET_MAX_OMEGA_RADPS).
 */
void tvo_sincos_turns(uint64_t turns_q64, tvo_real_t extra_rad, tvo_real_t *sin_out, tvo_real_t *cos_out);

/**
 * atan2(y, x) in float32 from IEEE 754 float operations alone (one rounding each), so every target
 * computes the same bits (libm's atan2f differ between glibc and newlib): within 2 ulps of the exact
 * angle (tools/agree --accuracy measures it), C99 Annex F's values at zeros and infinities, a NaN argument
 * quieted. TVO_ATAN2 is it in the float build and libm's atan2 in double.
 */
float tvo_atan2f(float y, float x);

#if TVO_USE_DOUBLE
#define TVO_ATAN2 atan2
#else
#define TVO_ATAN2 tvo_atan2f
#endif

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_TRIG_H */
