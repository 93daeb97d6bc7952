/*
 * Private to the core: compiling a loop-heavy body a second time for the unicycle's shape.
 *
 * Loops over the law's order k, the output dimension and the robot count run a handful of times;
 * with those counts as constants the compiler unrolls them and keeps the values in registers.
 * A body written once as a TVO_SHAPE_BODY function is called with constants for the common shapes
 * (k = 2; one robot or two) and with the run-time counts for any other. Optimising for size (-Os) keeps
 * one copy; -DTVO_SPECIALIZE_SHAPES=0/1 overrides.
 */
#ifndef TVO_SHAPE_H
#define TVO_SHAPE_H

#ifndef TVO_SPECIALIZE_SHAPES
#if defined(__OPTIMIZE_SIZE__)
#define TVO_SPECIALIZE_SHAPES 0
#else
#define TVO_SPECIALIZE_SHAPES 1
#endif
#endif

#if defined(__GNUC__)
#define TVO_SHAPE_BODY static inline __attribute__((always_inline))
#else
#define TVO_SHAPE_BODY static inline
#endif

/* Before a loop of a shape body whose count is at most 4: unrolled in full when the count is a constant. */
#if TVO_SPECIALIZE_SHAPES && defined(__GNUC__)
#define TVO_SHAPE_UNROLL _Pragma("GCC unroll 4")
#else
#define TVO_SHAPE_UNROLL
#endif

/* The common shapes: the paper's unicycle law (relative degree 2) for one robot, and for a pair
 * (a formation or an escort, without equalities). */
#define TVO_SHAPE_ORDER 2u
#define TVO_SHAPE_OUTPUT_DIM 2u
#define TVO_SHAPE_PAIR_OUTPUT_DIM 4u

#endif /* TVO_SHAPE_H */
