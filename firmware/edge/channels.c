/* The protocol's channel table; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

#include "tvo/status.h"
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_session_ack_t.h"

/* The wire's flags that shape a command are the core's bits (the HOLDING and SAFE_STOP bits are the
 * wire's own, derived from the outcome in step_codec.c): a build where one drifts fails here. The
 * statuses and parameters are the wire's own numbers, mapped in the codecs. */
#define WIRE_EQUALS_CORE(wire, core) _Static_assert((wire) == (core), #wire " must equal " #core)
#define FLAG_ON_WIRE(name) WIRE_EQUALS_CORE(TVO_LCM_COMMAND_T_FLAG_##name, TVO_FLAG_##name)
FLAG_ON_WIRE(OMEGA_SATURATED); FLAG_ON_WIRE(ACCEL_SATURATED); FLAG_ON_WIRE(SPEED_SATURATED); FLAG_ON_WIRE(LOW_SPEED);
FLAG_ON_WIRE(PREDICTED); FLAG_ON_WIRE(REGULARIZED); FLAG_ON_WIRE(SPEED_MISMATCH);

static const char *const channel_names[] = {
    NULL, TVO_CHANNEL_SESSION, TVO_CHANNEL_SESSION_ACK, TVO_CHANNEL_MEASUREMENT,
    TVO_CHANNEL_TARGET, TVO_CHANNEL_COMMAND, TVO_CHANNEL_TELEMETRY};

const char *tvo_node_channel_name(int channel)
{
    if (channel < TVO_NODE_CH_SESSION || channel > TVO_NODE_CH_TELEMETRY) {
        return NULL;
    }
    return channel_names[channel];
}

int tvo_node_channel_of(const char *name)
{
    for (int channel = TVO_NODE_CH_SESSION; name != NULL && channel <= TVO_NODE_CH_TELEMETRY; ++channel) {
        if (strcmp(name, channel_names[channel]) == 0) {
            return channel;
        }
    }
    return 0;
}

const char *tvo_protocol_part_str(int32_t part)
{
    switch (part) {
    case TVO_LCM_SESSION_ACK_T_PART_NONE: return "none";
    case TVO_LCM_SESSION_ACK_T_PART_ROBOTS: return "robots/targets";
    case TVO_LCM_SESSION_ACK_T_PART_BARRIER: return "barrier";
    case TVO_LCM_SESSION_ACK_T_PART_DISTANCE: return "distance bounds";
    case TVO_LCM_SESSION_ACK_T_PART_HALFSPACE: return "half-spaces";
    case TVO_LCM_SESSION_ACK_T_PART_OBSTACLES: return "obstacles";
    case TVO_LCM_SESSION_ACK_T_PART_OFFSETS: return "formation offsets";
    default: return "unknown part";
    }
}

const char *tvo_protocol_param_str(int32_t param)
{
    switch (param) {
    case TVO_LCM_SESSION_ACK_T_PARAM_NONE: return "none";
    case TVO_LCM_SESSION_ACK_T_PARAM_TICK_HZ: return "tick_hz (the node's: microseconds)";
    case TVO_LCM_SESSION_ACK_T_PARAM_PERIOD: return "period_us";
    case TVO_LCM_SESSION_ACK_T_PARAM_DELAY: return "delay_us (or delay_compensation/zoh_aware)";
    case TVO_LCM_SESSION_ACK_T_PARAM_FILTER_TF: return "filter_tf_s";
    case TVO_LCM_SESSION_ACK_T_PARAM_GAINS: return "gain_kp/gain_kd (chain: chain_relative_degree/chain_gains)";
    case TVO_LCM_SESSION_ACK_T_PARAM_OMEGA_MAX: return "omega_max_radps";
    case TVO_LCM_SESSION_ACK_T_PARAM_ACCEL_MAX: return "accel_max_mps2 (chain: chain_input_max)";
    case TVO_LCM_SESSION_ACK_T_PARAM_SPEED_MAX: return "speed_max_mps";
    case TVO_LCM_SESSION_ACK_T_PARAM_MIN_SPEED: return "min_speed_mps";
    case TVO_LCM_SESSION_ACK_T_PARAM_WATCHDOG: return "watchdog_periods";
    case TVO_LCM_SESSION_ACK_T_PARAM_ROBOT_COUNT: return "robot_count";
    case TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE: return "the problem (robot, barrier, distance, halfspace, obstacle, offset)";
    case TVO_LCM_SESSION_ACK_T_PARAM_VELOCITY_SOURCE: return "velocity_source";
    case TVO_LCM_SESSION_ACK_T_PARAM_INITIAL_SPEED: return "robot[].initial_speed_mps";
    case TVO_LCM_SESSION_ACK_T_PARAM_EPOCH: return "epoch_utime (or utime)";
    case TVO_LCM_SESSION_ACK_T_PARAM_CLOCK_SOURCE: return "clock_source";
    case TVO_LCM_SESSION_ACK_T_PARAM_PLANT_KIND: return "plant_kind";
    case TVO_LCM_SESSION_ACK_T_PARAM_SESSION_ID: return "session_id";
    default: return "unknown parameter";
    }
}

const char *tvo_node_status_str(tvo_node_status_t status)
{
    switch (status) {
    case TVO_NODE_OK: return "ok";
    case TVO_NODE_WRONG_ROBOT_COUNT: return "measurement for another robot count than the session's";
    case TVO_NODE_IMPLAUSIBLE_STAMP: return "stamp does not fit the session's schedule";
    case TVO_NODE_NOT_LATER_PERIOD: return "sample serves no later period than the last accepted one";
    case TVO_NODE_STALE: return "sample too old for the period it would serve";
    case TVO_NODE_MISSING_DERIVATIVES: return "chain session reads derivatives the sample lacks";
    case TVO_NODE_REFUSAL_STREAK: return "refusals in a row: safe stop";
    case TVO_NODE_SESSION_CONFLICT: return "session id already running with other parameters";
    case TVO_NODE_NO_SESSION: return "no such session running (send START)";
    case TVO_NODE_UNKNOWN_ACTION: return "session action neither START nor STOP";
    case TVO_NODE_STATUS_COUNT: break;
    }
    return "unknown edge status";
}

const char *tvo_protocol_status_str(int32_t status)
{
    switch (status) {
    case TVO_LCM_COMMAND_T_STATUS_OK: return "ok";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NULL: return "null pointer";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NOT_FINITE: return "input not finite (NaN or Inf)";
    case TVO_LCM_COMMAND_T_STATUS_ERR_DIMENSION: return "dimension out of range";
    case TVO_LCM_COMMAND_T_STATUS_ERR_PARAM: return "parameter out of range";
    case TVO_LCM_COMMAND_T_STATUS_ERR_CAPACITY: return "fixed-size table full";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NOT_INITIALIZED: return "not initialised";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NOT_POSITIVE_DEFINITE: return "Hessian not positive definite";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NUMERIC: return "result not finite";
    case TVO_LCM_COMMAND_T_STATUS_ERR_STALE: return "measurement stale (older than one period)";
    case TVO_LCM_COMMAND_T_STATUS_ERR_OUT_OF_ORDER: return "timestamp did not advance";
    case TVO_LCM_COMMAND_T_STATUS_ERR_FUTURE_STAMP: return "timestamp in the future";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NO_MEASUREMENT: return "no measurement this period";
    case TVO_LCM_COMMAND_T_STATUS_ERR_MISSING_FIELD: return "measurement lacks a field the configuration needs";
    case TVO_LCM_COMMAND_T_STATUS_ERR_TARGET_NOT_READY: return "streamed target has no sample yet";
    case TVO_LCM_COMMAND_T_STATUS_ERR_WATCHDOG: return "watchdog expired: safe stop";
    case TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_STAMP: return "stamp does not fit the session's schedule";
    case TVO_LCM_COMMAND_T_STATUS_ERR_SESSION_CONFLICT: return "session id already running with other parameters";
    case TVO_LCM_COMMAND_T_STATUS_ERR_NO_SESSION: return "no such session running (send START)";
    case TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT:
        return "measurement beyond the robot's workspace, heading range or speed";
    default: return "unknown status";
    }
}
