/*
 * Private to the core: the unicycle controller's position-only velocity source
 * (TVO_VELOCITY_FROM_POSITION), apart from the controller so that a firmware which never asks for
 * it (tvo_controller_init_pose_velocity) links neither it nor the dirty-derivative filter.
 */
#ifndef TVO_POSITION_VELOCITY_H
#define TVO_POSITION_VELOCITY_H

#include "tvo/controller.h"

/* The plan's estimate, called once the period is located (work.period): the step's trial
 * copy of the filter advanced to the measurement (restarted after a stop), the heading at the
 * sample, and the filtered y' rotated by the held turn rate over the carry to the law's instant,
 * all in ctl->work; the controller's own filter is untouched (the step commits the copy only when
 * it succeeds). */
tvo_status_t controller_position_velocity(tvo_controller_t *ctl, const tvo_measurement_t *meas);

/* The plan's commit, for an accepted period: the filter's copy kept, and the heading estimate carried
 * to the application instant (the next sample dead-reckons from there). */
void controller_position_velocity_commit(tvo_controller_t *ctl);

/* The plan tvo_controller_init picks for TVO_VELOCITY_FROM_POSITION (the only reference to both). */
extern const tvo_position_velocity_t controller_position_velocity_plan;

#endif /* TVO_POSITION_VELOCITY_H */
