/*
 * TVO_ASSERT: the internal functions' preconditions (valid pointers, sizes within the limits), which
 * the public functions check once at the boundary (firmware/include/tvo). Compiled to nothing under
 * NDEBUG (every release and size build); in a debug build a failed assertion traps where it fails
 * (__builtin_trap: a fault on the board, SIGILL on the host), with no stdio, no abort() and no libc.
 */
#ifndef TVO_INTERNAL_ASSERT_H
#define TVO_INTERNAL_ASSERT_H

#if defined(NDEBUG)
#define TVO_ASSERT(condition) ((void)0)
#elif defined(__GNUC__)
#define TVO_ASSERT(condition) ((condition) ? (void)0 : __builtin_trap())
#else
#include <assert.h> /* other compilers: the host's assert (firmware builds use GCC or clang) */
#define TVO_ASSERT(condition) assert(condition)
#endif

#endif /* TVO_INTERNAL_ASSERT_H */
