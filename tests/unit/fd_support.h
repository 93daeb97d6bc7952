/*
 * Finite differences, in double, of vector functions the core evaluates in tvo_real_t: the reference
 * the constraint and barrier tests hold jets against ("the term against itself").
 *
 * A function G(tau) in R^dim is sampled at tau = j h (|j| <= 3) and differentiated by 4th-order
 * central stencils:
 *   k = 1: (G-2 - 8 G-1 + 8 G1 - G2) / (12 h)                     roundoff gain 18/12
 *   k = 2: (-G-2 + 16 G-1 - 30 G0 + 16 G1 - G2) / (12 h^2)         roundoff gain 64/12
 *   k = 3: (G-3 - 8 G-2 + 13 G-1 - 13 G1 + 8 G2 - G3) / (8 h^3)    roundoff gain 44/8
 *
 * Tolerance of a derivative, per component (fd_check):
 *   tol = gain * FD_ULPS * eps * cond * Gmax / h^k     (each core evaluation is good to FD_ULPS ulps of
 *                                                       cond * Gmax; cond > 1 says where a cancellation
 *                                                       such as sigma = s - f amplifies it)
 *       + |D(h) - D(2h)|                               (the stencil's own error estimate: the truncation of
 *                                                       D(2h) is 16x that of D(h), so this bounds the
 *                                                       truncation of D(h) 15 times over; it does not
 *                                                       depend on the jet under test, so a wrong jet
 *                                                       still fails)
 * and fd_check also asserts that the largest tolerance is below FD_MAX_REL_TOL(k) of the largest
 * derivative, so a stencil that does not resolve the function cannot pass vacuously.
 *
 * Step h = L * FD_STEP_k with L the caller's length scale; the steps are powers of two so that
 * dyadic sample points are exact in float32 too. float32: h/L = 1/16, 1/8, 1/4 (k = 1, 2, 3), which
 * balances eps/h^k against h^4; double: 1/1024, 1/256, 1/128.
 */
#ifndef TVO_FD_SUPPORT_H
#define TVO_FD_SUPPORT_H

#include <stdlib.h>

#include "test_support.h"

#define FD_MAX_DIM 16
#define FD_ULPS 8.0
/*
 * How far below the derivative the tolerance must be for the check to count. double resolves every
 * order to better than 1e-4 here, so 1e-3 is demanded. float32 cannot: differences of k-th order
 * lose eps / (h/L)^k, i.e. ~eps^(4/(4+k)) of G/L^k at best (3e-6, 2e-5, 1e-4 of that scale for
 * k = 1, 2, 3), and a second or third derivative is often a small fraction of G/L^k (the terms are
 * nearly linear along the path). So float32 demands 5 % for k = 1 and only 35 % / 50 % for k = 2 / 3:
 * there the check proves magnitude and sign in float32, and the double build pins the same code.
 */
#if TVO_USE_DOUBLE
#define FD_MAX_REL_TOL(k) (1e-3)
#else
#define FD_MAX_REL_TOL(k) ((k) >= 3u ? 0.5 : (k) == 2u ? 0.35 : 0.05)
#endif

/** Evaluates G(tau) into out[0..dim-1]; returns 0 on success (nonzero aborts the check). */
typedef int (*fd_fn)(void *ctx, double tau, double *out);

static inline double fd_step_rel(unsigned k)
{
#if TVO_USE_DOUBLE
    static const double step[4] = {0.0, 1.0 / 1024.0, 1.0 / 256.0, 1.0 / 128.0};
#else
    static const double step[4] = {0.0, 1.0 / 16.0, 1.0 / 8.0, 1.0 / 4.0};
#endif
    return step[k];
}

static inline double fd_gain(unsigned k)
{
    static const double gain[4] = {0.0, 18.0 / 12.0, 64.0 / 12.0, 44.0 / 8.0};
    return gain[k];
}

/* D_k(h) of every component; *gmax = max |G| over the samples. Returns 0 on success. */
static inline int fd_derivative(fd_fn fn, void *ctx, unsigned dim, unsigned k, double h, double *d, double *gmax)
{
    static const double w1[7] = {0.0, 1.0, -8.0, 0.0, 8.0, -1.0, 0.0};
    static const double w2[7] = {0.0, -1.0, 16.0, -30.0, 16.0, -1.0, 0.0};
    static const double w3[7] = {1.0, -8.0, 13.0, 0.0, -13.0, 8.0, -1.0};
    const double *w = (k == 1u) ? w1 : (k == 2u) ? w2 : w3;
    const double denom = (k == 1u) ? 12.0 * h : (k == 2u) ? 12.0 * h * h : 8.0 * h * h * h;
    double g[FD_MAX_DIM];
    for (unsigned i = 0; i < dim; ++i) {
        d[i] = 0.0;
    }
    for (int j = -3; j <= 3; ++j) {
        if (w[j + 3] == 0.0 && !(k == 2u && j == 0)) {
            continue;
        }
        if (fn(ctx, (double)j * h, g) != 0) {
            return 1;
        }
        for (unsigned i = 0; i < dim; ++i) {
            d[i] += w[j + 3] * g[i];
            if (fabs(g[i]) > *gmax) {
                *gmax = fabs(g[i]);
            }
        }
    }
    for (unsigned i = 0; i < dim; ++i) {
        d[i] /= denom;
    }
    return 0;
}

/**
 * Asserts |expected_i - d^k G_i/dtau^k (0)| <= tol_i for i < dim (see the file comment), with step
 * L * fd_step_rel(k), cond the caller's roundoff amplification (>= 1) and noise an absolute error of
 * each evaluation on top of FD_ULPS * eps * cond * Gmax (0 unless the caller knows better).
 */
static inline void fd_check_line(fd_fn fn, void *ctx, unsigned dim, unsigned k, double length, double cond,
                                 double noise, const double *expected, const char *what, int line)
{
    static char msg[400];
    const double h = length * fd_step_rel(k);
    double d1[FD_MAX_DIM], d2[FD_MAX_DIM];
    double gmax = 0.0;
    if (fd_derivative(fn, ctx, dim, k, h, d1, &gmax) != 0 || fd_derivative(fn, ctx, dim, k, 2.0 * h, d2, &gmax) != 0) {
        (void)snprintf(msg, sizeof(msg), "%s: evaluation failed inside the stencil", what);
        UNITY_TEST_FAIL(line, msg);
    }
    const double round = fd_gain(k) * (FD_ULPS * TEST_EPS * cond * gmax + noise) / pow(h, (double)k);
    double dmax = 0.0, tolmax = 0.0;
    for (unsigned i = 0; i < dim; ++i) {
        const double tol = round + fabs(d1[i] - d2[i]);
        if (fabs(d1[i]) > dmax) {
            dmax = fabs(d1[i]);
        }
        if (tol > tolmax) {
            tolmax = tol;
        }
        if (!(fabs(expected[i] - d1[i]) <= tol)) {
            (void)snprintf(msg, sizeof(msg),
                           "%s: component %u, order %u: jet %.9g vs finite difference %.9g (|diff| %.3g > tol %.3g;"
                           " roundoff %.3g, D(h)-D(2h) %.3g)",
                           what, i, k, expected[i], d1[i], fabs(expected[i] - d1[i]), tol, round, fabs(d1[i] - d2[i]));
            UNITY_TEST_FAIL(line, msg);
        }
    }
    if (getenv("FD_DEBUG") != NULL) {
        printf("%s k=%u h=%g gmax=%g round=%g dmax=%g tolmax=%g\n", what, k, h, gmax, round, dmax, tolmax);
    }
    if (!(tolmax <= FD_MAX_REL_TOL(k) * dmax)) {
        (void)snprintf(msg, sizeof(msg), "%s: order %u: tolerance %.3g is not below %.2g of the largest derivative %.3g"
                       " (the stencil does not resolve the function)", what, k, tolmax, FD_MAX_REL_TOL(k), dmax);
        UNITY_TEST_FAIL(line, msg);
    }
}
#define FD_CHECK(fn, ctx, dim, k, length, cond, expected, what) \
    fd_check_line((fn), (ctx), (dim), (k), (length), (cond), 0.0, (expected), (what), __LINE__)
#define FD_CHECK_NOISE(fn, ctx, dim, k, length, noise, expected, what) \
    fd_check_line((fn), (ctx), (dim), (k), (length), 1.0, (noise), (expected), (what), __LINE__)

#endif /* TVO_FD_SUPPORT_H */
