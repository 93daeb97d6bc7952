/* A wire double as the core's scalar, and a core scalar as a wire float, for both codecs. */
#ifndef TVO_WIRE_REAL_H
#define TVO_WIRE_REAL_H

#include <float.h>
#include <math.h>

#include "tvo/config.h"

/* Out of float range becomes +-infinity, which the core rejects as not finite (a plain conversion
 * of such a value to float is undefined behaviour in C). */
static inline tvo_real_t tvo_wire_real(double value)
{
#if !TVO_USE_DOUBLE
    if (value > (double)FLT_MAX) {
        return INFINITY;
    }
    if (value < -(double)FLT_MAX) {
        return -INFINITY;
    }
#endif
    return (tvo_real_t)value;
}

/* A measured value (a sample's or a target's): finite stays finite, saturated to the core's largest
 * value, so a finite 1e300 reaches the core's range checks (beyond the workspace, status 19) rather
 * than passing for a NaN/Inf (status 2); NaN and +-Inf stay what they are. */
static inline tvo_real_t tvo_wire_measured(double value)
{
#if !TVO_USE_DOUBLE
    if (value > (double)FLT_MAX && isfinite(value)) {
        return FLT_MAX;
    }
    if (value < -(double)FLT_MAX && isfinite(value)) {
        return -FLT_MAX;
    }
#endif
    return tvo_wire_real(value);
}

/* A value for a float field of the wire: the float32 core's value exactly; a double build's rounded,
 * beyond float range +-infinity (never the undefined conversion). */
static inline float tvo_wire_float(tvo_real_t value)
{
#if TVO_USE_DOUBLE
    if (value > (double)FLT_MAX) {
        return INFINITY;
    }
    if (value < -(double)FLT_MAX) {
        return -INFINITY;
    }
#endif
    return (float)value;
}

#endif /* TVO_WIRE_REAL_H */
