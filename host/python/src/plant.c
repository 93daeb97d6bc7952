/* Exact unicycle arcs in double (plant.h). */
#include "plant.h"

#include <math.h>

void tvo_py_unicycle_arc(double *pose, double speed_mps, double turn_rate_radps, uint32_t ticks, uint32_t tick_hz)
{
    const double dt = (double)ticks / (double)tick_hz;
    const double th = pose[2];
    if (fabs(turn_rate_radps) > 1e-12) {
        const double r = speed_mps / turn_rate_radps;
        pose[0] += r * (sin(th + turn_rate_radps * dt) - sin(th));
        pose[1] -= r * (cos(th + turn_rate_radps * dt) - cos(th));
    } else {
        pose[0] += speed_mps * dt * cos(th);
        pose[1] += speed_mps * dt * sin(th);
    }
    pose[2] = th + turn_rate_radps * dt;
}
