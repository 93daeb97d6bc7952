/*
 * Build-time configuration of the control core: the scalar type and every size limit.
 *
 * Everything in the core is sized from the constants below; nothing is allocated at run time.
 * Each limit can be set at build time (-DTVO_MAX_OUTPUT_DIM=2 ...) to size RAM and stack for a
 * product: a single-robot board needs neither 4 robots' arrays nor equality multipliers.
 * Build with -DTVO_USE_DOUBLE=1 (CMake option TVO_DOUBLE) for double precision; the default is
 * float32, which a Cortex-M4F executes in hardware.
 */
#ifndef TVO_CONFIG_H
#define TVO_CONFIG_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#ifndef TVO_USE_DOUBLE
#define TVO_USE_DOUBLE 0
#endif

#if TVO_USE_DOUBLE
typedef double tvo_real_t;
#define TVO_R(x) (x)
#define TVO_SQRT sqrt
#define TVO_SIN sin
#define TVO_COS cos
#define TVO_FABS fabs
#define TVO_FLOOR floor
#define TVO_EPSILON 2.220446049250313e-16
#else
typedef float tvo_real_t;
#define TVO_R(x) (x##f)
#define TVO_SQRT sqrtf
#define TVO_SIN sinf
#define TVO_COS cosf
#define TVO_FABS fabsf
#define TVO_FLOOR floorf
#define TVO_EPSILON 1.1920929e-07f
#endif

/* pi and the two constants derived from it that the core uses, in the scalar type, written once. */
#define TVO_PI TVO_R(3.14159265358979323846)
#define TVO_INV_TWO_PI TVO_R(0.159154943091895335768883763372514362)
#define TVO_TWO_OVER_PI TVO_R(0.636619772367581343076)

/** Highest relative degree k the law supports (jets carry k+1 Taylor coefficients). */
#ifndef TVO_MAX_RELATIVE_DEGREE
#define TVO_MAX_RELATIVE_DEGREE 3
#endif
/** Highest jet order: Taylor coefficients c[0..TVO_JET_MAX_ORDER]. */
#define TVO_JET_MAX_ORDER TVO_MAX_RELATIVE_DEGREE
/** Largest flat-output dimension (2 per unicycle). */
#ifndef TVO_MAX_OUTPUT_DIM
#define TVO_MAX_OUTPUT_DIM 8
#endif
/** Most robots one controller drives (each contributes 2 flat outputs). */
#define TVO_MAX_ROBOTS (TVO_MAX_OUTPUT_DIM / 2)
/** Most equality constraints (Lagrange multipliers) one objective may carry; 0 compiles the saddle
 * (KKT) solve out, for a product without equality constraints (a formation offset needs two robots). */
#ifndef TVO_MAX_EQUALITIES
#define TVO_MAX_EQUALITIES 4
#endif
/** Largest primal-dual dimension z = (y, nu): the size of the law's linear solve. */
#define TVO_MAX_Z_DIM (TVO_MAX_OUTPUT_DIM + TVO_MAX_EQUALITIES)
/** The length of an array of up to n entries: ISO C has no zero-length array (a limit may be 0). */
#define TVO_ARRAY_LEN(n) ((n) > 0 ? (n) : 1)
/** Most objective terms one objective may sum. */
#ifndef TVO_MAX_TERMS
#define TVO_MAX_TERMS 16
#endif
/** Most disk obstacles one free-space term avoids. */
#ifndef TVO_MAX_OBSTACLES
#define TVO_MAX_OBSTACLES 8
#endif
/** Highest degree m_r of the relaxed barrier's Taylor continuation. */
#ifndef TVO_BARRIER_MAX_DEGREE
#define TVO_BARRIER_MAX_DEGREE 8
#endif
/** Highest polynomial degree of an on-board polynomial target. */
#ifndef TVO_POLY_MAX_DEGREE
#define TVO_POLY_MAX_DEGREE 7
#endif
/** Highest target derivative order a streamed target carries (position .. jerk). */
#ifndef TVO_STREAM_MAX_DERIV
#define TVO_STREAM_MAX_DERIV 3
#endif

/**
 * The workspace, in metres: every position the core accepts (a measurement, a target's value at the
 * epoch, a constraint's geometry) has |x| <= TVO_POSITION_LIMIT_M per axis, and every rate of that
 * geometry at most TVO_POSITION_LIMIT_M per second. float32 keeps about 1 mm at this magnitude, and
 * no product the law forms of such numbers can overflow. Override with -DTVO_POSITION_LIMIT_M_VALUE
 * (whole metres).
 */
#ifndef TVO_POSITION_LIMIT_M_VALUE
#define TVO_POSITION_LIMIT_M_VALUE 10000
#endif
#define TVO_POSITION_LIMIT_M ((tvo_real_t)(TVO_POSITION_LIMIT_M_VALUE))
/** A polynomial target's coefficients c_j (j >= 1, in m/s^j): any fit a robot can follow lies far inside. */
#define TVO_POLY_COEFF_LIMIT TVO_R(1.0e6)

/**
 * Speed over size: the core compiles its loop-heavy bodies a second time for the common shapes (the
 * k = 2 law for one robot or two) and unrolls loops that run at most 4 times (jet coefficients,
 * a robot's outputs). Optimising for size (-Os) turns both off; -DTVO_SPECIALIZE_SHAPES=0/1 overrides.
 */
#ifndef TVO_SPECIALIZE_SHAPES
#if defined(__OPTIMIZE_SIZE__)
#define TVO_SPECIALIZE_SHAPES 0
#else
#define TVO_SPECIALIZE_SHAPES 1
#endif
#endif
/* Before a short loop (a jet's coefficients, a robot's outputs, a part's entries, a small matrix's
 * rows): unrolled in full where its count is a constant, by up to 4 where it is not. */
#if TVO_SPECIALIZE_SHAPES && defined(__GNUC__)
#define TVO_UNROLL_SMALL _Pragma("GCC unroll 4")
#else
#define TVO_UNROLL_SMALL
#endif

/* The limits must make sense together. */
#if TVO_MAX_OUTPUT_DIM < 2 || TVO_MAX_OUTPUT_DIM > 64 || TVO_MAX_OUTPUT_DIM % 2 != 0
#error "TVO_MAX_OUTPUT_DIM must be an even number 2 .. 64 (2 per robot, up to 32 robots)"
#endif
#if TVO_MAX_TERMS < 1 || TVO_MAX_TERMS > 255
#error "TVO_MAX_TERMS must be 1 .. 255"
#endif
#if TVO_MAX_RELATIVE_DEGREE < 1 || TVO_MAX_RELATIVE_DEGREE > 3
#error "TVO_MAX_RELATIVE_DEGREE must be 1, 2 or 3"
#endif
#if TVO_POSITION_LIMIT_M_VALUE < 1 || TVO_POSITION_LIMIT_M_VALUE > 1000000
#error "TVO_POSITION_LIMIT_M_VALUE must be 1 .. 1000000 whole metres (float32 keeps 6 cm at 1e6)"
#endif
#if TVO_MAX_EQUALITIES < 0 || TVO_MAX_EQUALITIES % 2 != 0
#error "TVO_MAX_EQUALITIES must be 0 or a positive even number (a formation offset uses 2)"
#endif

#ifdef __cplusplus
}
#endif

#endif /* TVO_CONFIG_H */
