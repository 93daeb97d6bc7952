/*
 * The firmware edge: conversions between the LCM messages (package tvo_lcm) and the control core.
 *
 * Everything a session needs lives in one tvo_edge_session_t (controller, objective, targets,
 * tracking terms), so the node holds no globals and the core's pointers into it stay valid for the
 * session's life. Times: the core's uint32 tick is the plant's utime in microseconds, truncated.
 */
#ifndef TVO_LCM_EDGE_H
#define TVO_LCM_EDGE_H

#include <stdint.h>

#include "tvo/controller.h"
#include "tvo/target.h"
#include "tvo/tracking.h"

#include "tvo_lcm_command_t.h"
#include "tvo_lcm_measurement_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"

/* LCM channels of the protocol (the host uses the same names). */
#define TVO_CHANNEL_SESSION "TVO_SESSION"
#define TVO_CHANNEL_SESSION_ACK "TVO_SESSION_ACK"
#define TVO_CHANNEL_MEASUREMENT "TVO_MEASUREMENT"
#define TVO_CHANNEL_TARGET "TVO_TARGET"
#define TVO_CHANNEL_COMMAND "TVO_COMMAND"
#define TVO_CHANNEL_TELEMETRY "TVO_TELEMETRY"

/** Ticks of the core's clock per second: ticks are microseconds, like LCM's utime. */
#define TVO_EDGE_TICK_HZ 1000000u

typedef struct {
    tvo_controller_t controller;
    tvo_objective_t objective;
    tvo_target_t targets[TVO_MAX_ROBOTS];
    tvo_tracking_term_t terms[TVO_MAX_ROBOTS];
    int64_t session_id;
    int64_t period_us;
    int64_t delay_us;
    int64_t last_sequence;      /* last measurement sequence stepped, to detect missed periods */
    uint8_t robot_count;
    uint8_t has_sequence;
    uint8_t active;             /* a START was accepted and no STOP seen */
    tvo_status_t start_status;  /* outcome of the last START, re-sent on a duplicate */
    tvo_param_t start_bad_param;
} tvo_edge_session_t;

/**
 * Builds targets, tracking terms (one per robot, offset 2r, weights from tracking_weight), the
 * objective and the controller configuration from a START message, then initialises the
 * controller with epoch_tick = (uint32_t)epoch_utime. *bad_param names the rejected parameter.
 */
tvo_status_t tvo_edge_session_start(tvo_edge_session_t *session, const tvo_lcm_session_t *msg,
                                    tvo_param_t *bad_param);

/** Core measurement from an LCM one; TVO_ERR_DIMENSION if its robot count differs from the session's. */
tvo_status_t tvo_edge_measurement_from_lcm(const tvo_lcm_measurement_t *msg, uint8_t robot_count,
                                           tvo_measurement_t *meas);

/** LCM command answering measurement `sequence`, applied at apply_utime. */
void tvo_edge_command_to_lcm(const tvo_command_t *cmd, tvo_status_t status, int64_t apply_utime,
                             int64_t sequence, uint8_t robot_count, tvo_lcm_command_t *msg);

/** LCM telemetry of the controller's last step. */
void tvo_edge_telemetry_to_lcm(const tvo_controller_t *ctl, tvo_status_t status, uint32_t flags,
                               int64_t apply_utime, int64_t sequence, tvo_lcm_telemetry_t *msg);

/** Feeds a streamed target sample to every robot's streamed target (stamp converted by the core). */
tvo_status_t tvo_edge_target_update(tvo_edge_session_t *session, const tvo_lcm_target_t *msg);

/** Session ack for a session message. */
void tvo_edge_ack_to_lcm(int64_t utime, int64_t session_id, int8_t action, tvo_status_t status,
                         tvo_param_t bad_param, tvo_lcm_session_ack_t *msg);

#endif /* TVO_LCM_EDGE_H */
