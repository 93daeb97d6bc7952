/*
 * Private to the core: compiling a loop-heavy body a second time for the common shapes.
 *
 * Loops over the law's order k, the output dimension and the robot count run a handful of times;
 * with those counts as constants the compiler unrolls them and keeps the values in registers.
 * A body written once as a TVO_SHAPE_BODY function is called with constants for the common shapes
 * (k = 2; one robot or two) and with the run-time counts for any other. TVO_SPECIALIZE_SHAPES
 * (tvo/config.h) turns the second copies off, as optimising for size (-Os) does.
 */
#ifndef TVO_SHAPE_H
#define TVO_SHAPE_H

#include "tvo/config.h"

/* The common shapes: the paper's unicycle law (relative degree 2) for one robot, and for a pair
 * (a formation or an escort, without equalities). */
#define TVO_SHAPE_ORDER 2u
#define TVO_SHAPE_OUTPUT_DIM 2u
#define TVO_SHAPE_PAIR_OUTPUT_DIM 4u

/* The copies exist where asked for (TVO_SPECIALIZE_SHAPES) and where the build's jets can hold the
 * common shapes' order. Without them a body is an ordinary inline function: one copy. */
#define TVO_SHAPE_COPIES (TVO_SPECIALIZE_SHAPES && TVO_JET_MAX_ORDER >= TVO_SHAPE_ORDER)
#if TVO_SHAPE_COPIES && defined(__GNUC__)
#define TVO_SHAPE_BODY static inline __attribute__((always_inline))
#else
#define TVO_SHAPE_BODY static inline
#endif

/* A piece of a step kept out of line when there is one copy (a size build), so the step's deepest
 * call chain, through the law, does not carry its frame; compiled into its caller with the copies. */
#if TVO_SHAPE_COPIES || !defined(__GNUC__)
#define TVO_OFF_CHAIN_BODY TVO_SHAPE_BODY
#else
#define TVO_OFF_CHAIN_BODY static __attribute__((noinline))
#endif

/* A rare branch's body (a limit's correction, a stop), kept out of line so the common path's
 * registers and layout do not pay for it. */
#if defined(__GNUC__)
#define TVO_COLD_BODY static __attribute__((noinline, cold))
#else
#define TVO_COLD_BODY static
#endif

/* Replaces a (leading n x n block, row stride `stride`) by (a + a^T) / 2: exactly symmetric. */
TVO_SHAPE_BODY void symmetrize(tvo_real_t *a, const unsigned stride, const unsigned n)
{
    TVO_UNROLL_SMALL
    for (unsigned i = 0; i < n; ++i) {
        TVO_UNROLL_SMALL
        for (unsigned j = 0; j < i; ++j) {
            const tvo_real_t avg = TVO_R(0.5) * (a[i * stride + j] + a[j * stride + i]);
            a[i * stride + j] = avg;
            a[j * stride + i] = avg;
        }
    }
}

#endif /* TVO_SHAPE_H */
