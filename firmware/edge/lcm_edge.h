/*
 * The firmware edge: conversions between the LCM messages (package tvo_lcm) and the control core.
 *
 * Everything a session needs lives in one tvo_edge_session_t (controller and the problem: targets,
 * tracking terms, constraints, equalities), so the node holds no globals and the core's pointers
 * into it stay valid for the session's life. Times: the core's uint32 tick is the plant's utime in
 * microseconds, truncated.
 */
#ifndef TVO_LCM_EDGE_H
#define TVO_LCM_EDGE_H

#include <stdint.h>

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"
#include "tvo/target.h"

#include "channels.h"
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_measurement_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"

/** Ticks of the core's clock per second: ticks are microseconds, like LCM's utime. */
#define TVO_EDGE_TICK_HZ 1000000u

typedef struct {
    tvo_controller_t controller;
    tvo_chain_controller_t chain;  /* PLANT_CHAIN sessions run this controller instead */
    uint8_t plant_chain;           /* 1: the session's plant is the integrator chain */
    tvo_problem_t problem;      /* objective, targets and constraint terms the controller points into */
    int64_t session_id;
    int64_t period_us;
    int64_t delay_us;
    int64_t last_sequence;      /* last measurement sequence stepped, to detect missed periods */
    uint8_t robot_count;
    uint8_t has_sequence;
    uint8_t active;             /* a START was accepted and no STOP seen */
    tvo_status_t start_status;  /* outcome of the last START, re-sent on a duplicate */
    tvo_param_t start_bad_param;
    int32_t start_bad_part;
} tvo_edge_session_t;

/**
 * Builds the problem (targets and tracking terms per robot, distance bounds, half-spaces, obstacles,
 * formation offsets, barrier) and the controller configuration from a START message, then
 * initialises the controller with epoch_tick = (uint32_t)epoch_utime. On rejection *bad_param names
 * the parameter (TVO_PARAM_OBJECTIVE for the problem) and *bad_part the part of the problem
 * (TVO_LCM_SESSION_ACK_T_PART_*, PART_NONE when the problem was not at fault).
 */
tvo_status_t tvo_edge_session_start(tvo_edge_session_t *session, const tvo_lcm_session_t *msg,
                                    tvo_param_t *bad_param, int32_t *bad_part);

/**
 * Once, before the first step with a usable measurement: chooses the barrier slack s0 from the
 * measured positions at objective time 0 (the paper's rule; no-op without inequalities).
 */
tvo_status_t tvo_edge_choose_slack(tvo_edge_session_t *session, const tvo_measurement_t *meas);

/** Short name of a problem part (TVO_LCM_SESSION_ACK_T_PART_*), for logs. */
const char *tvo_edge_part_str(int32_t part);

/** Core measurement from an LCM one; TVO_ERR_DIMENSION if its robot count differs from the session's. */
tvo_status_t tvo_edge_measurement_from_lcm(const tvo_lcm_measurement_t *msg, uint8_t robot_count,
                                           tvo_measurement_t *meas);

/** Chain measurement (positions, and y', y'' when derivatives_valid) from an LCM one. */
tvo_status_t tvo_edge_chain_measurement_from_lcm(const tvo_lcm_measurement_t *msg, uint8_t robot_count,
                                                 tvo_chain_measurement_t *meas);

/** LCM command carrying a chain command u in input[]. */
void tvo_edge_chain_command_to_lcm(const tvo_chain_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                                   int64_t sequence, uint8_t robot_count, tvo_lcm_command_t *msg);

/** LCM command answering measurement `sequence`, applied at apply_utime. */
void tvo_edge_command_to_lcm(const tvo_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                             int64_t sequence, uint8_t robot_count, tvo_lcm_command_t *msg);

/** LCM telemetry of the session's last step (controller state, multipliers, barrier schedule). */
void tvo_edge_telemetry_to_lcm(const tvo_edge_session_t *session, tvo_status_t status, uint32_t flags,
                               int64_t apply_utime, int64_t sequence, tvo_lcm_telemetry_t *msg);

/** Feeds a streamed target sample to every robot's streamed target (stamp converted by the core). */
tvo_status_t tvo_edge_target_update(tvo_edge_session_t *session, const tvo_lcm_target_t *msg);

/** Session ack for a session message. */
void tvo_edge_ack_to_lcm(int64_t utime, int64_t session_id, int8_t action, tvo_status_t status,
                         tvo_param_t bad_param, int32_t bad_part, tvo_lcm_session_ack_t *msg);

#endif /* TVO_LCM_EDGE_H */
