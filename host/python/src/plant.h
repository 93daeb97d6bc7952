/*
 * The `tvo` Python module's closed-loop plant: exact unicycle arcs in double, shared by the module
 * and by the C program its bit-identity test compares against (tests/closed_loop_ref.c), so the two
 * loops feed the core the same measurements.
 */
#ifndef TVO_PY_PLANT_H
#define TVO_PY_PLANT_H

#include <stdint.h>

/** pose = (x, y, heading) moved along the arc of (speed, turn rate) held for ticks / tick_hz seconds. */
void tvo_py_unicycle_arc(double *pose, double speed_mps, double turn_rate_radps, uint32_t ticks, uint32_t tick_hz);

#endif /* TVO_PY_PLANT_H */
