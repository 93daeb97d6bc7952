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

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_TRIG_H */
