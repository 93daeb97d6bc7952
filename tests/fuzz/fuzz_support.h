/*
 * Shared pieces of the libFuzzer harnesses: a reference session (the demo's, or a variant picked by
 * one input byte), the invariants every published command must hold, and an abort that names the
 * broken invariant (libFuzzer then keeps the input as a reproducer).
 */
#ifndef TVO_FUZZ_SUPPORT_H
#define TVO_FUZZ_SUPPORT_H

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "node.h"
#include "wire_real.h"

#define FUZZ_SESSION_ID 42
#define FUZZ_EPOCH_US 1000000
#define FUZZ_PERIOD_US 10000
#define FUZZ_DELAY_US 5000

static inline void fuzz_fail(const char *invariant)
{
    fprintf(stderr, "fuzz invariant broken: %s\n", invariant);
    abort();
}

/* The demo's session, varied by `variant`: clock source, plant kind, velocity source, constraints. */
static inline void fuzz_session(tvo_lcm_session_t *s, uint8_t variant)
{
    memset(s, 0, sizeof(*s));
    s->utime = FUZZ_EPOCH_US;
    s->session_id = FUZZ_SESSION_ID;
    s->action = TVO_LCM_SESSION_T_ACTION_START;
    s->clock_source = (variant & 1u) ? TVO_LCM_SESSION_T_CLOCK_NODE : TVO_LCM_SESSION_T_CLOCK_PLANT;
    s->epoch_utime = FUZZ_EPOCH_US;
    s->period_us = FUZZ_PERIOD_US;
    s->delay_us = FUZZ_DELAY_US;
    s->delay_compensation = 1;
    s->watchdog_periods = 4;
    s->plant_kind = (variant & 2u) ? TVO_LCM_SESSION_T_PLANT_CHAIN : TVO_LCM_SESSION_T_PLANT_UNICYCLE;
    s->velocity_source = (variant & 4u) ? TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION : TVO_LCM_SESSION_T_VELOCITY_FROM_POSE;
    s->filter_tf_s = 0.05;
    s->gain_kp = 40.0;
    s->gain_kd = 13.0;
    s->omega_max_radps = 6.283185307179586;
    s->accel_max_mps2 = 15.0;
    s->speed_max_mps = 5.0;
    s->min_speed_mps = 0.05;
    s->chain_relative_degree = 2;
    s->chain_gains[0] = 2.56;
    s->chain_gains[1] = 3.2;
    s->chain_input_max = 100.0;
    s->robot_count = (variant & 8u) ? 2 : 1;
    for (int r = 0; r < s->robot_count; ++r) {
        s->robot[r].tracking_weight[0] = 1.0;
        s->robot[r].tracking_weight[1] = 1.0;
        s->robot[r].target.kind = TVO_LCM_PATH_T_KIND_ELLIPSE;
        s->robot[r].target.center_m[0] = 2.0 * r;
        s->robot[r].target.semi_axis_m[0] = 3.0;
        s->robot[r].target.semi_axis_m[1] = 1.5;
        s->robot[r].target.omega_radps = 0.6283185307179586;
    }
    s->barrier.c0 = 1.0;
    s->barrier.alpha_c_per_s = 1.0;
    s->barrier.c_max = 1e4;
    s->barrier.delta0 = 0.05;
    s->barrier.alpha_s_per_s = 1.0;
    s->barrier.slack_margin = 0.1;
    s->barrier.relaxation_degree = 4;
    if ((variant & 16u) && s->robot_count == 2) {
        s->distance_count = 1;
        s->distance[0].robot_a = 0;
        s->distance[0].robot_b = 1;
        s->distance[0].min_m = 1.0;
        s->distance[0].max_m = 3.0;
    }
    if (variant & 32u) {
        s->robot_radius_m = 0.2;
        s->obstacle_count = 1;
        s->obstacle[0].center_m[0] = 0.5;
        s->obstacle[0].center_m[1] = 4.0;
        s->obstacle[0].radius_m = 0.5;
    }
}

/* A limit as the core holds it: the wire's double rounded to the core's scalar (tiny limits become
 * subnormal floats, whose relative rounding is far coarser than the slack below). */
static inline double fuzz_core_limit(double wire)
{
    return (double)tvo_wire_real(wire);
}

/* Every command the node publishes: finite, within the session's limits, a safe stop all zero, and
 * status 0 only with a computed command. */
static inline void fuzz_check_command(const tvo_lcm_command_t *m, const tvo_lcm_session_t *s)
{
    const double slack = 1e-6; /* the command's own float rounding against the limit */
    for (int r = 0; r < 4; ++r) {
        if (!isfinite(m->speed_mps[r]) || !isfinite(m->turn_rate_radps[r])) {
            fuzz_fail("command not finite");
        }
        if (s != NULL && s->plant_kind == TVO_LCM_SESSION_T_PLANT_UNICYCLE) {
            if (fabs(m->turn_rate_radps[r]) > fuzz_core_limit(s->omega_max_radps) * (1.0 + slack)) {
                fuzz_fail("|omega| beyond omega_max");
            }
            if (fabs(m->speed_mps[r]) > fuzz_core_limit(s->speed_max_mps) * (1.0 + slack)) {
                fuzz_fail("|v| beyond speed_max");
            }
        }
        if ((m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) && (m->speed_mps[r] != 0.0 || m->turn_rate_radps[r] != 0.0)) {
            fuzz_fail("safe stop not all zero");
        }
    }
    for (int i = 0; i < 8; ++i) {
        if (!isfinite(m->input[i])) {
            fuzz_fail("chain input not finite");
        }
        if (s != NULL && s->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN &&
            fabs(m->input[i]) > fuzz_core_limit(s->chain_input_max) * (1.0 + slack)) {
            fuzz_fail("|u| beyond chain_input_max");
        }
        if ((m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) && m->input[i] != 0.0) {
            fuzz_fail("safe stop not all zero (chain)");
        }
    }
    /* Status 0 is a computed command, or the speed mismatch's stop (the measurement was accepted). */
    const int32_t mismatch_stop = (int32_t)(TVO_LCM_COMMAND_T_FLAG_SAFE_STOP | TVO_FLAG_SPEED_MISMATCH);
    if (m->status == 0 && ((m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_HOLDING) != 0 ||
                           ((m->flags & (int32_t)TVO_LCM_COMMAND_T_FLAG_SAFE_STOP) != 0 && (m->flags & mismatch_stop) != mismatch_stop))) {
        fuzz_fail("status OK on a holding or stop command");
    }
}

/* Statuses the node gives before the controller steps: such a refusal must change nothing. */
static inline int fuzz_refused_before_step(int32_t status)
{
    switch (status) {
    case TVO_LCM_COMMAND_T_STATUS_ERR_DIMENSION:
    case TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_STAMP:
    case TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER:
    case TVO_LCM_COMMAND_T_STATUS_ERR_STALE:
    case TVO_LCM_COMMAND_T_STATUS_ERR_FUTURE_STAMP:
    case TVO_LCM_COMMAND_T_STATUS_ERR_NOT_FINITE:
    case TVO_LCM_COMMAND_T_STATUS_ERR_MISSING_FIELD:
        return 1;
    default:
        return 0;
    }
}

#endif /* TVO_FUZZ_SUPPORT_H */
