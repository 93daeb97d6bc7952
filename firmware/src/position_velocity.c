/*
 * The unicycle controller's position-only velocity source: y' from a dirty-derivative filter on the
 * measured positions, and a heading dead-reckoned with the held turn rate and pulled toward the
 * filtered velocity direction (see tvo/controller.h).
 */
#include "position_velocity.h"

#include "internal/sample_clock.h"
#include "internal/dirty_derivative.h"
#include "internal/trig.h"
#include "internal/unicycle.h"

/* The velocity direction corrects dead reckoning with this many T_f. */
#define TVO_HEADING_CORRECTION_TF_MULTIPLE TVO_R(10.0)

/* Filtered y' and the heading estimate at the sample, from the filter's working copy. */
static tvo_status_t estimate_at_sample(const tvo_controller_t *ctl, tvo_dirty_derivative_t *filter,
                                       const tvo_measurement_t *meas, tvo_real_t *rate_at_sample,
                                       tvo_real_t *heading_at_sample)
{
    const uint8_t n = ctl->cfg.robot_count;
    tvo_real_t position[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
    for (uint8_t r = 0; r < n; ++r) {
        position[2u * r] = meas->position_m[r][0];
        position[2u * r + 1u] = meas->position_m[r][1];
    }
    tvo_status_t st;
    if (!filter->primed) {
        /* Start as if moving at the speed state along the (first measured, else estimated) heading. */
        tvo_real_t rate0[TVO_MAX_OUTPUT_DIM] = {TVO_R(0.0)};
        for (uint8_t r = 0; r < n; ++r) {
            heading_at_sample[r] = meas->heading_valid ? meas->heading_rad[r] : ctl->internal.heading_estimate_rad[r];
            tvo_real_t sin_heading;
            tvo_real_t cos_heading;
            tvo_sincos(heading_at_sample[r], &sin_heading, &cos_heading);
            const tvo_real_t speed_mps = ctl->internal.work.from_rest ? TVO_R(0.0) : ctl->internal.speed_state_mps[r];
            rate0[2u * r] = speed_mps * cos_heading;
            rate0[2u * r + 1u] = speed_mps * sin_heading;
        }
        st = tvo_dirty_derivative_reset(filter, position, rate0);
        for (uint8_t i = 0; i < 2u * n; ++i) {
            rate_at_sample[i] = rate0[i];
        }
        return st;
    }
    const tvo_real_t dt_s = ticks_to_seconds32(meas->stamp_tick - ctl->internal.loop.clock.last_stamp_tick, ctl->cfg.tick_hz);
    st = tvo_dirty_derivative_step(filter, position, dt_s, rate_at_sample);
    if (st != TVO_OK) {
        return st;
    }
    /* Signed time from the last application instant (where the estimate lives) to this sample. */
    const int32_t since_apply_ticks = (int32_t)(meas->stamp_tick - ctl->internal.loop.clock.last_apply_tick);
    const tvo_real_t since_apply_s = (tvo_real_t)since_apply_ticks / (tvo_real_t)ctl->cfg.tick_hz;
    const tvo_real_t correction = ctl->internal.loop.period_s / (TVO_HEADING_CORRECTION_TF_MULTIPLE * ctl->cfg.filter_tf_s);
    for (uint8_t r = 0; r < n; ++r) {
        /* Dead-reckon with the held turn rate, then pull toward the velocity direction when the
         * robot moves fast enough for that direction to mean something. */
        tvo_real_t heading = ctl->internal.heading_estimate_rad[r] + ctl->internal.work.in_force->turn_rate_radps[r] * since_apply_s;
        const tvo_real_t vx = rate_at_sample[2u * r];
        const tvo_real_t vy = rate_at_sample[2u * r + 1u];
        if (vx * vx + vy * vy > TVO_R(4.0) * ctl->cfg.min_speed_mps * ctl->cfg.min_speed_mps) {
            tvo_real_t direction = TVO_ATAN2(vy, vx);
            if (ctl->internal.speed_state_mps[r] < TVO_R(0.0)) {
                direction += TVO_PI; /* reversing: the robot faces against its velocity */
            }
            heading += (correction < TVO_R(1.0) ? correction : TVO_R(1.0)) * tvo_wrap_angle(direction - heading);
        }
        heading_at_sample[r] = tvo_wrap_angle(heading);
    }
    return TVO_OK;
}

tvo_status_t controller_position_velocity(tvo_controller_t *ctl, const tvo_measurement_t *meas)
{
    tvo_controller_work_t *work = &ctl->internal.work;
    tvo_dirty_derivative_t *filter = &work->velocity_filter; /* kept only if the step succeeds */
    *filter = ctl->internal.velocity_filter;
    if (work->from_rest) {
        filter->primed = 0; /* the gap makes old filter state meaningless */
    }
    tvo_real_t *rate = work->rate_filtered;
    const tvo_status_t st = estimate_at_sample(ctl, filter, meas, rate, work->heading_at_sample);
    for (uint8_t r = 0; r < ctl->cfg.robot_count && st == TVO_OK; ++r) {
        /* The held turn rate rotates the velocity over the carry to the law's instant, like the heading. */
        tvo_real_t s;
        tvo_real_t c;
        tvo_sincos(work->in_force->turn_rate_radps[r] * work->period.carry_s, &s, &c);
        const tvo_real_t x = rate[2u * r];
        rate[2u * r] = c * x - s * rate[2u * r + 1u];
        rate[2u * r + 1u] = s * x + c * rate[2u * r + 1u];
    }
    return st;
}

void controller_position_velocity_commit(tvo_controller_t *ctl)
{
    const tvo_controller_work_t *work = &ctl->internal.work;
    const tvo_period_t *period = &work->period;
    ctl->internal.velocity_filter = work->velocity_filter;
    for (uint8_t r = 0; r < ctl->cfg.robot_count; ++r) {
        ctl->internal.heading_estimate_rad[r] = unicycle_wrap_angle_near(work->heading[r] + work->in_force->turn_rate_radps[r] *
                                                                                  (period->age_s - period->carry_s));
    }
}

const tvo_position_velocity_t controller_position_velocity_plan = {controller_position_velocity,
                                                                    controller_position_velocity_commit};
