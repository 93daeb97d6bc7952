/*
 * Step codec: one period's messages between the wire and the core — a measurement into the core's
 * measurement, a command and the step's telemetry out, a streamed target sample in. Stamps arrive
 * already converted to the core's ticks (the node owns time). Pure functions: no state.
 */
#ifndef TVO_STEP_CODEC_H
#define TVO_STEP_CODEC_H

#include <stdint.h>

#include "tvo/chain_controller.h"
#include "tvo/controller.h"
#include "tvo/problem.h"

#include "channels.h"
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_measurement_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"

#ifdef __cplusplus
extern "C" {
#endif

/** Robots the per-period messages carry (measurement_t, command_t, target_t, telemetry_t). A build may
 *  drive more (TVO_MAX_ROBOTS): only a node that answers through a joint answer (a fleet link, node.h)
 *  serves such sessions, from per-robot samples. */
#define TVO_WIRE_MAX_ROBOTS TVO_LCM_MEASUREMENT_T_MAX_ROBOTS
/** Robots a session answered in the per-period messages may have: the wire's, or fewer if the build drives fewer. */
#define TVO_WIRE_SESSION_ROBOTS (TVO_WIRE_MAX_ROBOTS < TVO_MAX_ROBOTS ? TVO_WIRE_MAX_ROBOTS : TVO_MAX_ROBOTS)

/** One robot's sample, in the wire's units. */
typedef struct {
    double position_m[2];
    double heading_rad;
    double speed_mps;
    double output_rate_mps[2];     /* chain sessions: y', y'' when derivatives_valid */
    double output_accel_mps2[2];
} tvo_step_robot_sample_t;

/** A joint measurement of the build's robots, as the node judges and steps it: a measurement_t
 *  (tvo_step_measurement_from_wire), or a fleet link's per-robot samples gathered for a period. */
typedef struct {
    int64_t utime;
    int64_t session_id;
    int64_t sequence;
    int32_t robot_count;           /* -1: negative, or more than the message carried (never a session's) */
    uint8_t heading_valid;
    uint8_t speed_valid;
    uint8_t derivatives_valid;
    tvo_step_robot_sample_t robot[TVO_MAX_ROBOTS];
} tvo_step_measurement_t;

/** The joint measurement a measurement_t carries (a negative robot_count, or one beyond its arrays, becomes -1). */
void tvo_step_measurement_from_wire(const tvo_lcm_measurement_t *msg, tvo_step_measurement_t *out);

/** Unicycle measurement (poses, headings, speeds) of robot_count robots, stamped stamp_tick. */
tvo_status_t tvo_step_unicycle_measurement(const tvo_step_measurement_t *msg, uint8_t robot_count, uint32_t stamp_tick,
                                           tvo_measurement_t *meas);

/** Chain measurement: positions, and y', y'' when derivatives_valid. */
tvo_status_t tvo_step_chain_measurement(const tvo_step_measurement_t *msg, uint8_t robot_count, uint32_t stamp_tick,
                                        tvo_chain_measurement_t *meas);

/** Why a command (or an ack) went out as it did: the edge's own status if not TVO_NODE_OK, else the
 *  core's call error if not TVO_OK, else the command's reason. */
typedef struct {
    tvo_node_status_t node;
    tvo_status_t error;
    tvo_reason_t reason;
} tvo_step_why_t;

/** command_t.status (also session_ack_t's and telemetry_t's) for `why`: the one mapping from the core's
 *  and the edge's vocabularies to the wire's numbers (a table per vocabulary, step_codec.c). */
int32_t tvo_step_wire_status(const tvo_step_why_t *why);

/** command_t.flags of a command: the core's flags with the wire's HOLDING and SAFE_STOP bits, which
 *  say the command's outcome (held, stopped). */
uint32_t tvo_step_wire_flags(uint32_t flags, tvo_outcome_t outcome);

/** The wire fields every command carries: when, which session, which measurement, why. */
typedef struct {
    int64_t utime;
    int64_t session_id;
    int64_t sequence;       /* measurement answered, -1 for the node's own safe stop */
    tvo_step_why_t why;
    uint8_t robot_count;
} tvo_step_stamp_t;

/** LCM command carrying a unicycle command (speed and turn rate per robot). */
void tvo_step_command_to_lcm(const tvo_command_t *cmd, const tvo_step_stamp_t *stamp, tvo_lcm_command_t *msg);

/** LCM command carrying a chain command u in input[]. */
void tvo_step_chain_command_to_lcm(const tvo_chain_command_t *cmd, const tvo_step_stamp_t *stamp,
                                   tvo_lcm_command_t *msg);

/** The stamp fields of the telemetry that follows a command (wire_flags: the command's, as
 *  tvo_step_wire_flags gives them; the controller's part is separate). */
void tvo_step_telemetry_stamp(const tvo_step_stamp_t *stamp, uint32_t wire_flags, tvo_lcm_telemetry_t *msg);

/** Telemetry of the unicycle controller's last good step (its telemetry for robot_count robots, their
 *  speed states, the problem's multipliers and barrier). */
void tvo_step_telemetry_to_lcm(const tvo_controller_telemetry_t *tel, uint8_t robot_count,
                               const tvo_real_t *speed_state_mps, const tvo_problem_t *problem,
                               tvo_lcm_telemetry_t *msg);

/**
 * Feeds a streamed target sample, valid at objective_ticks (ticks from the epoch), to every robot's
 * streamed target. TVO_ERR_DIMENSION if the robot count differs, TVO_ERR_PARAM if a robot's target
 * is not streamed.
 */
tvo_status_t tvo_step_target_from_lcm(const tvo_lcm_target_t *msg, uint8_t robot_count, uint64_t objective_ticks,
                                      tvo_problem_t *problem);

/**
 * The same for a sample stamped carry_s seconds before objective_ticks (0 <= carry_s <= 1 s): its
 * derivatives are first carried forward along their own cubic Taylor series, as the target would
 * evaluate the sample there anyway (a plant samples its target with the measurement, at epoch - tau).
 */
tvo_status_t tvo_step_target_from_lcm_carried(const tvo_lcm_target_t *msg, uint8_t robot_count,
                                              uint64_t objective_ticks, double carry_s, tvo_problem_t *problem);

#ifdef __cplusplus
}
#endif

#endif /* TVO_STEP_CODEC_H */
