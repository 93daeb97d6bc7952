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
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "wire_real.h"

#define FUZZ_SESSION_ID 42
#define FUZZ_BOOT ((int64_t)4711) /* the fuzzed node's boot, which the reference STARTs name */
#define FUZZ_EPOCH_US 1000000

static inline void fuzz_fail(const char *invariant)
{
    fprintf(stderr, "fuzz invariant broken: %s\n", invariant);
    abort();
}

/* The demo's session, varied by `variant`: clock source, plant kind, velocity source, constraints,
 * robots (a chain has one), telemetry after every answer or at the default rate (bit 6). */
static inline void fuzz_session(tvo_lcm_session_t *s, uint8_t variant)
{
    const int32_t robots = ((variant & 8u) && !(variant & 2u)) ? 2 : 1; /* a chain has one robot */
    (void)tvo_protocol_default_start(s, robots);                        /* 1 or 2: in range */
    s->utime = FUZZ_EPOCH_US;
    s->session_id = FUZZ_SESSION_ID;
    for (int r = 0; r < TVO_LCM_SESSION_T_MAX_ROBOTS; ++r) {
        s->node_boot_id[r] = FUZZ_BOOT;
    }
    s->telemetry_every = (variant & 64u) ? 0 : 1;
    s->clock_source = (variant & 1u) ? TVO_LCM_SESSION_T_CLOCK_NODE : TVO_LCM_SESSION_T_CLOCK_PLANT;
    s->epoch_utime = FUZZ_EPOCH_US;
    s->watchdog_periods = 4;
    s->plant_kind = (variant & 2u) ? TVO_LCM_SESSION_T_PLANT_CHAIN : TVO_LCM_SESSION_T_PLANT_UNICYCLE;
    s->velocity_source = (variant & 4u) ? TVO_LCM_SESSION_T_VELOCITY_FROM_POSITION : TVO_LCM_SESSION_T_VELOCITY_FROM_POSE;
    s->chain_relative_degree = 2;
    s->chain_gains[0] = 2.56;
    s->chain_gains[1] = 3.2;
    s->chain_input_max = 100.0;
    for (int r = 0; r < s->robot_count; ++r) {
        s->robot[r].target.kind = TVO_LCM_PATH_T_KIND_ELLIPSE;
        s->robot[r].target.center_m[0] = 2.0 * r;
        s->robot[r].target.semi_axis_m[0] = 3.0;
        s->robot[r].target.semi_axis_m[1] = 1.5;
        s->robot[r].target.omega_radps = 0.6283185307179586;
    }
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

/* What every command's header must say: status 0 is a computed command, or the speed mismatch's stop
 * (its sample was accepted), never a held or stopped one. */
static inline void fuzz_check_header(const tvo_lcm_command_header_t *h)
{
    const int32_t flags = h->flags;
    const int32_t mismatch_stop = (int32_t)(TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP | TVO_FLAG_SPEED_MISMATCH);
    if (h->status == 0 && ((flags & (int32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING) != 0 ||
                           ((flags & (int32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) != 0 &&
                            (flags & mismatch_stop) != mismatch_stop))) {
        fuzz_fail("status OK on a holding or stop command");
    }
    if (h->utime < 0 || h->utime > TVO_WIRE_TIME_MAX_US) {
        fuzz_fail("a command stamped outside the wire's range");
    }
}

/* A unicycle command the node publishes: finite, within the session's limits (s, when its limits
 * bind), a safe stop all zero. */
static inline void fuzz_check_unicycle_command(const tvo_lcm_unicycle_command_t *m, const tvo_lcm_session_t *s)
{
    const double slack = 1e-6; /* the command's own float rounding against the limit */
    const double v = (double)m->speed_mps, w = (double)m->turn_rate_radps;
    fuzz_check_header(&m->header);
    if (!isfinite(v) || !isfinite(w)) {
        fuzz_fail("command not finite");
    }
    if (s != NULL && s->plant_kind == TVO_LCM_SESSION_T_PLANT_UNICYCLE) {
        if (fabs(w) > fuzz_core_limit(s->omega_max_radps) * (1.0 + slack)) {
            fuzz_fail("|omega| beyond omega_max");
        }
        if (fabs(v) > fuzz_core_limit(s->speed_max_mps) * (1.0 + slack)) {
            fuzz_fail("|v| beyond speed_max");
        }
    }
    if ((m->header.flags & (int32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) && (v != 0.0 || w != 0.0)) {
        fuzz_fail("safe stop not all zero");
    }
}

/* The chain's command, likewise (its limit: chain_input_max). */
static inline void fuzz_check_chain_command(const tvo_lcm_chain_command_t *m, const tvo_lcm_session_t *s)
{
    const double slack = 1e-6;
    fuzz_check_header(&m->header);
    for (int i = 0; i < 2; ++i) {
        const double u = (double)m->input[i];
        if (!isfinite(u)) {
            fuzz_fail("chain input not finite");
        }
        if (s != NULL && s->plant_kind == TVO_LCM_SESSION_T_PLANT_CHAIN &&
            fabs(u) > fuzz_core_limit(s->chain_input_max) * (1.0 + slack)) {
            fuzz_fail("|u| beyond chain_input_max");
        }
        if ((m->header.flags & (int32_t)TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP) && u != 0.0) {
            fuzz_fail("safe stop not all zero (chain)");
        }
    }
}

/* A published frame's command (either plant's), checked; 1 if it was one. */
static inline int fuzz_check_published_command(int channel, const uint8_t *data, uint32_t length,
                                               const tvo_lcm_session_t *s, tvo_lcm_command_header_t *header)
{
    if (channel == TVO_NODE_CH_COMMAND) {
        tvo_lcm_unicycle_command_t m;
        if (tvo_lcm_unicycle_command_t_decode(data, 0, (int)length, &m) != (int)length) {
            fuzz_fail("the node published a command that does not decode");
        }
        fuzz_check_unicycle_command(&m, s);
        *header = m.header;
        return 1;
    }
    if (channel == TVO_NODE_CH_CHAIN_COMMAND) {
        tvo_lcm_chain_command_t m;
        if (tvo_lcm_chain_command_t_decode(data, 0, (int)length, &m) != (int)length) {
            fuzz_fail("the node published a chain command that does not decode");
        }
        fuzz_check_chain_command(&m, s);
        *header = m.header;
        return 1;
    }
    return 0;
}

/* Refusals that must change nothing of the session but the schedule's votes and refusal streak: the
 * node's own (before the core's step) and the core's (a transaction). Not these: a safe stop (the
 * watchdog's, which a refusal may commit), and the law's refusals (TARGET_NOT_READY, NUMERIC,
 * NOT_POSITIVE_DEFINITE), after which a re-anchor the samples voted for is kept. */
static inline int fuzz_refused_before_step(int32_t status)
{
    switch (status) {
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NO_MEASUREMENT:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_DIMENSION:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_STAMP:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_OUT_OF_ORDER:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_STALE:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_FUTURE_STAMP:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_NOT_FINITE:
    case TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_MISSING_FIELD:
        return 1;
    default:
        return 0;
    }
}

#endif /* TVO_FUZZ_SUPPORT_H */
