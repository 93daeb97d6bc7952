/*
 * The unicycle (wheeled mobile robot) x1' = v cos(theta), x2' = v sin(theta), theta' = omega,
 * with flat output y = (x1, x2): its flat map with dynamic extension and its exact motion under a
 * held command.
 *
 * Dynamic extension: the speed v is a controller state with v' = a. Given the law's y'' and
 * y' = v e_theta:  a = y'' . e_theta,  omega = (y' x y'') / v^2 = (e_theta x y'') / v.
 * Near v = 0 the division is regularised: v is replaced by sign(v) max(|v|, min_speed) (sign(0) = +1),
 * so omega stays finite and a robot at rest turns toward y'' while a builds speed along it.
 */
#ifndef TVO_UNICYCLE_H
#define TVO_UNICYCLE_H

#include "tvo/config.h"
#include "tvo/status.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
    tvo_real_t position_m[2];
    tvo_real_t heading_rad;
} tvo_pose_t;

#ifdef __cplusplus
}
#endif

#endif /* TVO_UNICYCLE_H */
