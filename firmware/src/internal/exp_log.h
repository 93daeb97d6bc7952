/*
 * Internal: the core's own float32 exp and log, correctly rounded (the float nearest the exact value,
 * ties to even) for every float argument, so every target computes the same bits from the same
 * arguments: x86-64 with glibc, Cortex-M with newlib and RV32 with picolibc alike, where the
 * libraries' expf and logf differ in last bits. Only IEEE 754 float operations (one rounding each:
 * the core compiles with -ffp-contract=off) and integer arithmetic. The double build calls libm.
 * tests/unit/test_exp_log.c checks them; tools/agree --accuracy measures them against glibc's.
 */
#ifndef TVO_INTERNAL_EXP_LOG_H
#define TVO_INTERNAL_EXP_LOG_H

#include "tvo/config.h"

#ifdef __cplusplus
extern "C" {
#endif

/** exp(x) correctly rounded: +0 below about -103.97, +inf above about 88.72, NaN quieted. */
float tvo_expf(float x);

/** tvo_expf's integer path, which soft-float targets run alone (exposed for the tests), for
 * 2^-26 <= |x| < 104. */
float tvo_expf_integer(float x);

/** log(x) correctly rounded: -inf at +-0, NaN below 0 and for NaN (quieted), +0 at 1. */
float tvo_logf(float x);

/* The scalar type's exp and log for the core: its own in float32, libm's in double. */
#if TVO_USE_DOUBLE
#define TVO_EXP exp
#define TVO_LOG log
#else
#define TVO_EXP tvo_expf
#define TVO_LOG tvo_logf
#endif

#ifdef __cplusplus
}
#endif

#endif /* TVO_INTERNAL_EXP_LOG_H */
