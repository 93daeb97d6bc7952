/*
 * The relaxed logarithmic barrier and its schedules (paper, "Inequality Constrained ...").
 *
 *   B_delta(sigma) = -log sigma                                            sigma >= delta
 *                  = -log delta + sum_{j=1..m_r} (1/j) ((delta - sigma)/delta)^j   sigma < delta
 *
 * enters the potential as Phi = f0 + (1/c(t)) sum_i B_delta(t)(s(t) - f_i(y, t)) with
 *   c(t) = min(c0 e^{alpha_c t}, c_max),  s(t) = s0 e^{-alpha_s t},  delta(t) = delta0 / c(t).
 *
 * A constraint term adds w(t) grad_y f_i to the gradient, with the barrier weight
 *   w = -(1/c) B'_delta(s - f_i) >= 0.
 * Because c delta = delta0, w depends on c and sigma = s - f_i only through x = c sigma / delta0 - 1:
 *   w = 1 / (c sigma)                          (x >= 0, the logarithm)
 *   w = (1/delta0) sum_{j=0..m_r-1} (-x)^j     (x < 0, the relaxation: bounded by m_r-ish / delta0)
 * so the weight stays finite for any sigma, even an infeasible one, and has m_r - 1 continuous
 * derivatives in sigma (B has m_r); m_r >= k + 1 gives the law the k + 1 it differentiates.
 *
 * The cap c_max: float32 cannot let c grow forever, and past the cap the schedule is constant.
 * The paper's error bound |f0(y_delta*) - f0(y*)| <= p / c(t) + sum lambda_i* s(t) then stops
 * shrinking at p / c_max: an active constraint is held back from its bound by about 1/(c_max
 * lambda_i) in units of f_i. The default c_max = 1e4 keeps that below 1e-3 m for the paper's scenarios
 * while the barrier's curvature (about c lambda^2 |grad f|^2) stays well inside float32's range.
 */
#ifndef TVO_BARRIER_H
#define TVO_BARRIER_H

#include "tvo/config.h"
#include "tvo/jet.h"
#include "tvo/objective.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tvo_real_t c0;                  /* c(0) > 0 */
    tvo_real_t alpha_c_per_s;       /* growth rate of c, >= 0 */
    tvo_real_t c_max;               /* cap of c, >= c0 */
    tvo_real_t delta0;              /* delta(t) = delta0 / c(t), > 0 */
    tvo_real_t alpha_s_per_s;       /* decay rate of the slack, > 0 */
    tvo_real_t slack_margin;        /* epsilon_s of the s0 rule, > 0 */
    uint8_t relaxation_degree;      /* m_r, relative degree + 1 .. TVO_BARRIER_MAX_DEGREE */
} tvo_barrier_config_t;

typedef struct {
    tvo_barrier_config_t cfg;
    tvo_real_t slack0;              /* s0, set by tvo_barrier_choose_slack (0 until then) */
    tvo_real_t cap_time_s;          /* t at which c reaches c_max (INFINITY-free: huge if alpha_c = 0) */
    uint8_t initialized;
} tvo_barrier_t;

/** Defaults: c0 = 1, alpha_c = 1/s, c_max = 1e4, delta0 = 0.05, alpha_s = 1/s, eps_s = 0.1, m_r = 4. */
tvo_status_t tvo_barrier_config_default(tvo_barrier_config_t *cfg);

#ifdef __cplusplus
}
#endif

#endif /* TVO_BARRIER_H */
