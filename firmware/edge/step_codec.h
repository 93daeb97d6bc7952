/*
 * Step codec: one period's messages between the wire and the core. Samples go straight from the
 * decoded message into the core's measurement (one conversion, robot by robot, or from a robot's
 * predicted state); a command, its telemetry and a streamed target sample the other way. Stamps
 * arrive already converted to the core's ticks (the node owns time). Pure functions: no state.
 */
#ifndef TVO_STEP_CODEC_H
#define TVO_STEP_CODEC_H

#include <stdint.h>

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#include "channels.h"
#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** What the node knows of one robot at a sampling instant: from its sample, or predicted. */
typedef struct {
    double position_m[2];
    double heading_rad;
    double speed_mps;
    int64_t sequence;              /* the period of that instant (the sample's sequence); -1: never heard */
} tvo_step_robot_state_t;

/** A period's joint unicycle measurement: robot r's row is its sample, sample[r], or where that is NULL
 *  its predicted state, predicted[r] (heading and speed both valid). */
typedef struct {
    const tvo_lcm_unicycle_sample_t *sample[TVO_MAX_ROBOTS];
    tvo_step_robot_state_t predicted[TVO_MAX_ROBOTS];
} tvo_step_period_t;

/** A sample's state (its heading and speed 0 where it has none), for the next prediction. */
void tvo_step_state_of(const tvo_lcm_unicycle_sample_t *sample, tvo_step_robot_state_t *state);

/** 1 if every value of the sample a controller may read is finite (the position; heading, speed as
 *  its has bits say). */
int tvo_step_unicycle_sample_finite(const tvo_lcm_unicycle_sample_t *sample);

/**
 * The core's unicycle measurement of robot_count robots, stamped stamp_tick, from the period's rows:
 * the wire's values rounded once to the core's scalar. heading_valid (speed_valid) holds if every
 * sampled robot has a heading (a speed); a predicted row has both.
 */
tvo_status_t tvo_step_unicycle_measurement(const tvo_step_period_t *period, uint8_t robot_count, uint32_t stamp_tick,
                                           tvo_measurement_t *meas);

/** The core's chain measurement (one robot): the position, and y', y'' when the sample has them. */
tvo_status_t tvo_step_chain_measurement(const tvo_lcm_chain_sample_t *sample, uint32_t stamp_tick,
                                        tvo_chain_measurement_t *meas);

/** Why a command (or an ack) went out as it did: the edge's own status if not TVO_NODE_OK, else the
 *  core's call error if not TVO_OK, else the command's reason. */
typedef struct {
    tvo_node_status_t node;
    tvo_status_t error;
    tvo_reason_t reason;
} tvo_step_why_t;

/** command_header_t.status (also session_ack_t's) for `why`: the one mapping from the core's and the
 *  edge's vocabularies to the wire's numbers (a table per vocabulary, step_codec.c). */
int32_t tvo_step_wire_status(const tvo_step_why_t *why);

/** command_header_t.flags of a command: the core's flags with the wire's HOLDING and SAFE_STOP bits,
 *  which say the command's outcome (held, stopped). */
uint32_t tvo_step_wire_flags(uint32_t flags, tvo_outcome_t outcome);

/** The fields every answer of one period carries, whichever robot's it is: when, which session and
 *  sample, why (the flags are the command's). */
typedef struct {
    int64_t utime;
    int32_t session_id;
    int32_t sequence;       /* the sample answered, -1 for the node's own safe stop */
    tvo_step_why_t why;
} tvo_step_stamp_t;

/** A command's header for `robot` (wire_flags: tvo_step_wire_flags of the command). */
void tvo_step_header(const tvo_step_stamp_t *stamp, uint32_t wire_flags, int32_t robot, tvo_lcm_command_header_t *out);

/** Robot `robot`'s row of a unicycle command (the header's flags from the command's flags and outcome). */
void tvo_step_unicycle_command(const tvo_command_t *cmd, const tvo_step_stamp_t *stamp, int32_t robot,
                               tvo_lcm_unicycle_command_t *msg);

/** The chain's command (one robot: u of its two outputs). */
void tvo_step_chain_command(const tvo_chain_command_t *cmd, const tvo_step_stamp_t *stamp,
                            tvo_lcm_chain_command_t *msg);

/** The joint command's digest (tvo_joint_digest) of a unicycle command's robot_count rows, as the wire
 *  carries them (float32 values as doubles). */
uint64_t tvo_step_unicycle_digest(const tvo_command_t *cmd, uint8_t robot_count);

/** The chain command's digest: its two inputs in the place of a robot's speed and turn rate. */
uint64_t tvo_step_chain_digest(const tvo_chain_command_t *cmd);

/** Robot `robot`'s rows of the unicycle controller's last good step in a telemetry message (its
 *  speed state, the problem's barrier schedule at that step's time); the header is the caller's. */
void tvo_step_telemetry_to_lcm(const tvo_controller_telemetry_t *tel, uint8_t robot, const tvo_real_t *speed_state_mps,
                               const tvo_problem_t *problem, tvo_lcm_telemetry_t *msg);

/**
 * Feeds a streamed target sample of robot msg->header.robot, valid carry_s seconds (0 .. 1 s) before
 * objective_ticks (ticks from the epoch), to that robot's streamed target: its derivatives are first
 * carried forward along their own cubic Taylor series (a plant samples its target with its first
 * sample, at epoch - tau). TVO_ERR_DIMENSION if the robot is not one of robot_count, TVO_ERR_PARAM if
 * its target is not streamed, TVO_ERR_NOT_FINITE for a value that is not; nothing changes then.
 */
tvo_status_t tvo_step_target_from_lcm_carried(const tvo_lcm_target_t *msg, uint8_t robot_count,
                                              uint64_t objective_ticks, double carry_s, tvo_problem_t *problem);

#ifdef __cplusplus
}
#endif

#endif /* TVO_STEP_CODEC_H */
