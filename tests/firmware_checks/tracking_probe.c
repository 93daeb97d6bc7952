/*
 * Link probe for the footprint of a one-robot tracking firmware: what a board that tracks a target
 * links. The controller with the pose velocity source (tvo_controller_init_pose_velocity), or with
 * TRACKING_PROBE_BOTH_SOURCES either source chosen at run time (tvo_controller_init); one tracking
 * term added with tvo_tracking_add (so the law's general path is not linked); every target kind (a
 * target arrives at run time) and the streamed target's update. No status strings: a board reports
 * codes, and a host prints them. Not meant to run; inputs are volatile so nothing is constant-folded.
 */
#include <stdint.h>

#ifndef TRACKING_PROBE_BOTH_SOURCES
#define TRACKING_PROBE_BOTH_SOURCES 0
#endif

#include "tvo/controller.h"
#include "tvo/target.h"
#include "tvo/tracking.h"

int main(void);

static volatile uint32_t input_tick;
static volatile uint32_t input_kind;
static volatile tvo_real_t input_position;
static volatile uint32_t output_sink;

static tvo_target_t target;
static tvo_tracking_term_t term;
static tvo_objective_t objective;
static tvo_controller_t controller;

/* The target of the kind the (volatile) input names, as a START message would. */
static tvo_status_t setup_target(void)
{
    static const tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1] = {{TVO_R(0.0), TVO_R(1.0)},
                                                                  {TVO_R(0.5), TVO_R(0.0), TVO_R(0.1)}};
    static const tvo_target_ellipse_t ellipse = {
        {TVO_R(0.0), TVO_R(0.0)}, {TVO_R(2.0), TVO_R(1.0)}, TVO_R(0.5), TVO_R(0.0), TVO_R(0.3), 0u};
    const tvo_real_t center[2] = {TVO_R(1.0), TVO_R(-1.0)};
    const tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2] = {{(tvo_real_t)input_position, TVO_R(0.0)}};
    switch (input_kind) {
    case 0u:
        return tvo_target_init_polynomial(&target, coeff);
    case 1u:
        return tvo_target_init_ellipse(&target, &ellipse);
    case 2u:
        return tvo_target_init_circle(&target, center, TVO_R(1.5), TVO_R(0.7), TVO_R(0.0));
    default: {
        const tvo_status_t st = tvo_target_init_streamed(&target);
        return st != TVO_OK ? st : tvo_target_stream_update(&target, 0u, deriv);
    }
    }
}

int main(void)
{
    tvo_controller_config_t cfg;
    tvo_param_t bad_param = TVO_PARAM_NONE;
    const tvo_real_t weight[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_measurement_t meas = {0};
    tvo_command_t cmd = {0};
    uint32_t sink = 0u;

    sink += (uint32_t)tvo_controller_config_default(&cfg);
    cfg.robot_count = 1u;
#if TRACKING_PROBE_BOTH_SOURCES
    cfg.velocity_source = (input_tick & 1u) ? TVO_VELOCITY_FROM_POSITION : TVO_VELOCITY_FROM_POSE;
#endif
    sink += (uint32_t)setup_target();
    sink += (uint32_t)tvo_objective_init(&objective, 2u);
    sink += (uint32_t)tvo_tracking_init(&term, &target, weight, 0u);
    sink += (uint32_t)tvo_tracking_add(&objective, &term);
#if TRACKING_PROBE_BOTH_SOURCES
    sink += (uint32_t)tvo_controller_init(&controller, &cfg, &objective, input_tick, &bad_param);
#else
    sink += (uint32_t)tvo_controller_init_pose_velocity(&controller, &cfg, &objective, input_tick, &bad_param);
#endif
    for (uint32_t n = 1u; n <= 4u; ++n) {
        const uint32_t apply_tick = input_tick + n * cfg.period_ticks;
        uint32_t sample_tick = 0u;
        sink += (uint32_t)tvo_controller_sample_tick(&controller, apply_tick, &sample_tick);
        meas.stamp_tick = sample_tick;
        meas.position_m[0][0] = (tvo_real_t)input_position;
        meas.heading_valid = 1u;
        sink += (uint32_t)tvo_controller_step(&controller, (n == 3u) ? NULL : &meas, apply_tick, &cmd);
        sink += cmd.flags;
    }
    output_sink = sink + (uint32_t)bad_param;
    return 0;
}
