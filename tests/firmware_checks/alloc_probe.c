/*
 * Link probe for the allocation check: a bare-metal program that uses the whole control core
 * (controller, law, objective, tracking term, every target kind, the problem assembly with every
 * constraint kind and an equality, status strings) so that a
 * --gc-sections link keeps everything the firmware would keep. The check then looks for allocator
 * symbols in the ELF. Not meant to run; inputs are volatile so nothing is constant-folded away.
 */
#include <stdint.h>

#include "tvo/controller.h"
#include "tvo/problem.h"
#include "tvo/status.h"
#include "tvo/target.h"
#include "tvo/tracking.h"

int main(void);

/* Robots the probe drives: three, or fewer in a build sized for fewer (-DTVO_MAX_OUTPUT_DIM=2). */
#define PROBE_ROBOTS (TVO_MAX_ROBOTS < 3 ? TVO_MAX_ROBOTS : 3)

static volatile uint32_t input_tick;
static volatile tvo_real_t input_position;
static volatile uint32_t output_sink;

static tvo_target_t targets[3];
static tvo_tracking_term_t terms[PROBE_ROBOTS];
static tvo_objective_t objective;
static tvo_controller_t controller;
#if TVO_MAX_ROBOTS >= 2
static tvo_problem_t problem;
static tvo_controller_t constrained_controller;
#endif

static uint32_t failures;

/* Instance sizes as section sizes, which tools/footprint.py reads from the link map. */
const uint8_t tvo_sizeof_controller[sizeof(tvo_controller_t)] = {1u};
const uint8_t tvo_sizeof_problem[sizeof(tvo_problem_t)] = {1u};

static void check(tvo_status_t status)
{
    if (status != TVO_OK) {
        ++failures;
    }
}

static void setup_targets(void)
{
    static const tvo_real_t coeff[2][TVO_POLY_MAX_DEGREE + 1] = {
        {TVO_R(0.0), TVO_R(1.0)}, {TVO_R(0.5), TVO_R(0.0), TVO_R(0.1)}};
    static const tvo_target_ellipse_t ellipse = {
        {TVO_R(0.0), TVO_R(0.0)}, {TVO_R(2.0), TVO_R(1.0)}, TVO_R(0.5), TVO_R(0.0), TVO_R(0.3), 0u};
    const tvo_real_t center[2] = {TVO_R(1.0), TVO_R(-1.0)};
    const tvo_real_t deriv[TVO_STREAM_MAX_DERIV + 1][2] = {{(tvo_real_t)input_position, TVO_R(0.0)}};
    check(tvo_target_init_polynomial(&targets[0], coeff));
    check(tvo_target_init_ellipse(&targets[1], &ellipse));
    check(tvo_target_init_circle(&targets[1], center, TVO_R(1.5), TVO_R(0.7), TVO_R(0.0)));
    check(tvo_target_init_streamed(&targets[2]));
    check(tvo_target_stream_update(&targets[2], 0u, deriv));
}

int main(void)
{
    tvo_controller_config_t cfg;
    tvo_param_t bad_param = TVO_PARAM_NONE;
    const tvo_real_t weight[2] = {TVO_R(1.0), TVO_R(1.0)};
    tvo_measurement_t meas = {0};
    tvo_command_t cmd;
    uint32_t flags = 0u;
    uint8_t r;

    tvo_status_t status = TVO_OK;

    check(tvo_controller_config_default(&cfg));
    cfg.robot_count = (uint8_t)PROBE_ROBOTS;
    cfg.velocity_source = (input_tick & 1u) ? TVO_VELOCITY_FROM_POSITION : TVO_VELOCITY_FROM_POSE;
    setup_targets();
    check(tvo_objective_init(&objective, (uint8_t)(2u * cfg.robot_count)));
    for (r = 0u; r < cfg.robot_count; ++r) {
        check(tvo_tracking_init(&terms[r], &targets[r], weight, (uint8_t)(2u * r)));
        check(tvo_objective_add_term(&objective, tvo_tracking_gradient_jet, &terms[r]));
    }
    /* Either init, as a board would call one (the pose-only one links less, not more). */
    if (input_tick & 2u) {
        check(tvo_controller_init_pose_velocity(&controller, &cfg, &objective, input_tick, &bad_param));
    } else {
        check(tvo_controller_init(&controller, &cfg, &objective, input_tick, &bad_param));
    }

    for (uint32_t n = 1u; n <= 4u; ++n) {
        uint32_t apply_tick = input_tick + n * cfg.period_ticks;
        uint32_t sample_tick = 0u;
        check(tvo_controller_sample_tick(&controller, apply_tick, &sample_tick));
        meas.stamp_tick = sample_tick;
        for (r = 0u; r < cfg.robot_count; ++r) {
            meas.position_m[r][0] = (tvo_real_t)input_position;
            meas.position_m[r][1] = (tvo_real_t)r;
        }
        meas.heading_valid = 1u;
        status = tvo_controller_step(&controller, (n == 3u) ? NULL : &meas, apply_tick, &cmd);
        flags |= cmd.flags;
    }
#if TVO_MAX_ROBOTS >= 2
    /* Every constraint kind and an equality, through the problem assembly. */
    static tvo_problem_desc_t desc;
    tvo_problem_culprit_t bad_part;
    check(tvo_problem_desc_default(&desc));
    desc.robot_count = 2u;
    desc.target[0] = targets[0];
    desc.target[1] = targets[1];
    desc.distance_count = 1u;
    desc.distance[0].robot_b = 1u;
    desc.distance[0].min_m = TVO_R(0.5);
    desc.distance[0].max_m = TVO_R(3.0);
    desc.halfspace_count = 1u;
    desc.halfspace[0].normal[0] = TVO_R(1.0);
    desc.halfspace[0].bound_m = TVO_R(10.0);
    desc.obstacle_count = 1u;
    desc.robot_radius_m = TVO_R(0.2);
    desc.obstacle[0].center_m[0] = TVO_R(5.0);
    desc.obstacle[0].radius_m = TVO_R(1.0);
    desc.offset_count = 1u;
    desc.offset[0].robot_b = 1u;
    desc.offset[0].offset = targets[2];
    check(tvo_problem_init(&problem, &desc, 2u, &bad_part));
    cfg.robot_count = 2u;
    check(tvo_controller_init(&constrained_controller, &cfg, &problem.objective, input_tick, &bad_param));
    const tvo_real_t y0[4] = {(tvo_real_t)input_position, TVO_R(0.0), TVO_R(1.0), TVO_R(0.0)};
    check(tvo_problem_choose_slack(&problem, y0, TVO_R(0.0)));
    meas.stamp_tick = input_tick + cfg.period_ticks - cfg.delay_ticks;
    status = tvo_controller_step(&constrained_controller, &meas, input_tick + cfg.period_ticks, &cmd);
    flags |= cmd.flags + bad_part.part;
#endif

    output_sink = flags + failures + tvo_sizeof_controller[input_tick & 0u] + tvo_sizeof_problem[input_tick & 0u] + (uint32_t)tvo_status_str(status)[0] + (uint32_t)tvo_param_str(bad_param)[0];
    return (int)status;
}
