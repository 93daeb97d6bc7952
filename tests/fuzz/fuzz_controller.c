/*
 * The unicycle controller's step with fuzzed measurements (values, flags and stamps from the input).
 * Invariants: every command finite and within the limits (|v|, |omega|, and but for a safe stop
 * |v - v_in_force| <= accel_max h), a stop all zero, the outcome APPLIED exactly when the reason is
 * NONE (a delivered command; a call error only for an apply tick that does not advance) with finite
 * telemetry; tvo_controller_check says what the step does; a measurement it refuses leaves the velocity
 * filter, the speed state and the last stamp as they were.
 * The first byte chooses the velocity source (bit 0: position-only) and, for the pose source, the
 * init (bits 1..0 = 2: tvo_controller_init_pose_velocity). Then records: stamp step (2 bytes,
 * ticks), apply lead (2 bytes, ticks), flags (1 byte), position x, y, heading, speed (4 x 4-byte floats).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "tvo/controller.h"
#include "tvo/problem.h"

#define RECORD_BYTES 21

static void fail(const char *what)
{
    fprintf(stderr, "fuzz invariant broken: %s\n", what);
    abort();
}

static float read_float(const uint8_t *p)
{
    float v;
    memcpy(&v, p, sizeof(v));
    return v;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    static tvo_problem_t problem;
    static tvo_controller_t ctl;
    tvo_problem_desc_t desc;
    tvo_controller_config_t cfg;
    tvo_problem_culprit_t part;
    if (tvo_problem_desc_default(&desc) != TVO_OK || tvo_controller_config_default(&cfg) != TVO_OK) {
        fail("defaults");
    }
    desc.robot_count = 1;
    desc.tracking_weight[0][0] = TVO_R(1.0);
    desc.tracking_weight[0][1] = TVO_R(1.0);
    const tvo_target_ellipse_t ellipse = {{TVO_R(0.0), TVO_R(0.0)}, {TVO_R(3.0), TVO_R(1.5)}, TVO_R(0.6283), TVO_R(0.0),
                                          TVO_R(0.0), 0u};
    if (tvo_target_init_ellipse(&desc.target[0], &ellipse) != TVO_OK ||
        tvo_problem_init(&problem, &desc, 2u, &part) != TVO_OK) {
        fail("reference problem");
    }
    cfg.velocity_source = (size > 0 && (data[0] & 1u)) ? TVO_VELOCITY_FROM_POSITION : TVO_VELOCITY_FROM_POSE;
    /* The pose source also from the init that does not link the position-only one. */
    const int pose_init = size > 0 && (data[0] & 3u) == 2u;
    if ((pose_init ? tvo_controller_init_pose_velocity(&ctl, &cfg, &problem.objective, 0u, NULL)
                   : tvo_controller_init(&ctl, &cfg, &problem.objective, 0u, NULL)) != TVO_OK) {
        fail("reference controller");
    }
    uint32_t stamp = 0u;
    tvo_real_t speed_in_force = cfg.initial_speed_mps[0];
    const double speed_step_max = (double)cfg.accel_max_mps2 * (double)cfg.period_ticks / (double)cfg.tick_hz;
    for (size_t i = 1; i + RECORD_BYTES <= size; i += RECORD_BYTES) {
        const uint8_t *p = data + i;
        tvo_measurement_t meas;
        memset(&meas, 0, sizeof(meas));
        stamp += (uint32_t)p[0] | ((uint32_t)p[1] << 8);
        const uint32_t apply = stamp + ((uint32_t)p[2] | ((uint32_t)p[3] << 8));
        meas.stamp_tick = stamp;
        meas.heading_valid = (p[4] & 1u) ? 1u : 0u;
        meas.speed_valid = (p[4] & 2u) ? 1u : 0u;
        meas.position_m[0][0] = read_float(p + 5);
        meas.position_m[0][1] = read_float(p + 9);
        meas.heading_rad[0] = read_float(p + 13);
        meas.speed_mps[0] = read_float(p + 17);
        const tvo_measurement_t *given = (p[4] & 4u) ? NULL : &meas;
        tvo_reason_t verdict = TVO_REASON_COUNT;
        const tvo_status_t check_status = tvo_controller_check(&ctl, given, apply, &verdict);
        const tvo_dirty_derivative_t filter = ctl.internal.velocity_filter;
        const tvo_real_t speed = ctl.internal.speed_state_mps[0];
        const uint32_t last_stamp = ctl.internal.loop.clock.last_stamp_tick;
        tvo_command_t cmd;
        const tvo_status_t st = tvo_controller_step(&ctl, given, apply, &cmd);
        if (!isfinite(cmd.speed_mps[0]) || !isfinite(cmd.turn_rate_radps[0])) {
            fail("command not finite");
        }
        if (TVO_FABS(cmd.turn_rate_radps[0]) > cfg.omega_max_radps || TVO_FABS(cmd.speed_mps[0]) > cfg.speed_max_mps) {
            fail("command beyond its limits");
        }
        const int stopped = cmd.outcome == TVO_OUTCOME_STOPPED;
        if (stopped && (cmd.speed_mps[0] != TVO_R(0.0) || cmd.turn_rate_radps[0] != TVO_R(0.0))) {
            fail("safe stop not all zero");
        }
        if (st != check_status) {
            fail("the step's call error is not the check's");
        }
        if (st != TVO_OK && (st != TVO_ERR_TICK_NOT_ADVANCING && st != TVO_ERR_BEFORE_EPOCH)) {
            fail("a call error other than a misplaced apply tick");
        }
        if (st == TVO_OK && (cmd.outcome == TVO_OUTCOME_APPLIED) != (cmd.reason == TVO_REASON_NONE)) {
            fail("outcome and reason disagree");
        }
        if (st == TVO_OK && cmd.outcome == TVO_OUTCOME_HELD &&
            (cmd.reason == TVO_REASON_WATCHDOG || cmd.reason == TVO_REASON_SPEED_MISMATCH)) {
            fail("held for a stop's reason");
        }
        if (!stopped &&
            fabs((double)cmd.speed_mps[0] - (double)speed_in_force) > speed_step_max * (1.0 + 1e-5) + 1e-6) {
            fail("the speed moved by more than accel_max h from the command in force");
        }
        speed_in_force = cmd.speed_mps[0];
        if (st == TVO_OK && cmd.outcome == TVO_OUTCOME_APPLIED) {
            const tvo_controller_telemetry_t *tm = &ctl.telemetry;
            for (int axis = 0; axis < 2; ++axis) {
                if (!isfinite(tm->gradient[axis]) || !isfinite(tm->gradient_rate[axis]) ||
                    !isfinite(tm->output_accel_mps2[axis]) || !isfinite(tm->output_rate_mps[axis])) {
                    fail("status OK with telemetry not finite");
                }
            }
        }
        const int taken = st == TVO_OK && (cmd.reason == TVO_REASON_NONE || cmd.reason == TVO_REASON_SPEED_MISMATCH);
        if (verdict != TVO_REASON_NONE && taken) {
            fail("the step used a measurement its check refused");
        }
        if (st == TVO_OK && !taken && cmd.reason != TVO_REASON_WATCHDOG && verdict != TVO_REASON_NONE &&
            verdict != cmd.reason) {
            fail("the step refused for another reason than its check");
        }
        if (!taken && cmd.reason != TVO_REASON_WATCHDOG &&
            (memcmp(&filter, &ctl.internal.velocity_filter, sizeof(filter)) != 0 || speed != ctl.internal.speed_state_mps[0] ||
             last_stamp != ctl.internal.loop.clock.last_stamp_tick)) {
            fail("a refused measurement changed the filter, the speed state or the last stamp");
        }
    }
    return 0;
}
