/* The protocol's channel table; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

#include "tvo/status.h"
#include "tvo_lcm_command_t.h"
#include "tvo_lcm_session_ack_t.h"

/* The wire's codes (command_t.STATUS_* and FLAG_*, session_ack_t.PARAM_*, which every language's
 * generated code has) are the core's numbers: a build where one drifts from tvo/status.h fails here. */
#define WIRE_EQUALS_CORE(wire, core) _Static_assert((wire) == (core), #wire " must equal " #core)
#define STATUS_ON_WIRE(name) WIRE_EQUALS_CORE(TVO_LCM_COMMAND_T_STATUS_##name, TVO_##name)
#define FLAG_ON_WIRE(name) WIRE_EQUALS_CORE(TVO_LCM_COMMAND_T_FLAG_##name, TVO_FLAG_##name)
#define PARAM_ON_WIRE(name) WIRE_EQUALS_CORE(TVO_LCM_SESSION_ACK_T_PARAM_##name, TVO_PARAM_##name)
STATUS_ON_WIRE(OK); STATUS_ON_WIRE(ERR_NULL); STATUS_ON_WIRE(ERR_NOT_FINITE); STATUS_ON_WIRE(ERR_DIMENSION);
STATUS_ON_WIRE(ERR_PARAM); STATUS_ON_WIRE(ERR_CAPACITY); STATUS_ON_WIRE(ERR_NOT_INITIALIZED);
STATUS_ON_WIRE(ERR_NOT_POSITIVE_DEFINITE); STATUS_ON_WIRE(ERR_NUMERIC); STATUS_ON_WIRE(ERR_STALE);
STATUS_ON_WIRE(ERR_OUT_OF_ORDER); STATUS_ON_WIRE(ERR_FUTURE_STAMP); STATUS_ON_WIRE(ERR_NO_MEASUREMENT);
STATUS_ON_WIRE(ERR_MISSING_FIELD); STATUS_ON_WIRE(ERR_TARGET_NOT_READY); STATUS_ON_WIRE(ERR_WATCHDOG);
STATUS_ON_WIRE(ERR_IMPLAUSIBLE_STAMP); STATUS_ON_WIRE(ERR_SESSION_CONFLICT); STATUS_ON_WIRE(ERR_NO_SESSION);
STATUS_ON_WIRE(ERR_IMPLAUSIBLE_MEASUREMENT);
_Static_assert(TVO_STATUS_COUNT == TVO_LCM_COMMAND_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT + 1,
               "command_t.STATUS_* must reach the last tvo_status_t");
FLAG_ON_WIRE(OMEGA_SATURATED); FLAG_ON_WIRE(ACCEL_SATURATED); FLAG_ON_WIRE(SPEED_SATURATED); FLAG_ON_WIRE(LOW_SPEED);
FLAG_ON_WIRE(HOLDING); FLAG_ON_WIRE(SAFE_STOP); FLAG_ON_WIRE(PREDICTED); FLAG_ON_WIRE(REGULARIZED);
FLAG_ON_WIRE(SPEED_MISMATCH);
PARAM_ON_WIRE(NONE); PARAM_ON_WIRE(TICK_HZ); PARAM_ON_WIRE(PERIOD); PARAM_ON_WIRE(DELAY); PARAM_ON_WIRE(FILTER_TF);
PARAM_ON_WIRE(GAINS); PARAM_ON_WIRE(OMEGA_MAX); PARAM_ON_WIRE(ACCEL_MAX); PARAM_ON_WIRE(SPEED_MAX);
PARAM_ON_WIRE(MIN_SPEED); PARAM_ON_WIRE(WATCHDOG); PARAM_ON_WIRE(ROBOT_COUNT); PARAM_ON_WIRE(OBJECTIVE);
PARAM_ON_WIRE(VELOCITY_SOURCE); PARAM_ON_WIRE(INITIAL_SPEED); PARAM_ON_WIRE(EPOCH); PARAM_ON_WIRE(CLOCK_SOURCE);
PARAM_ON_WIRE(PLANT_KIND); PARAM_ON_WIRE(SESSION_ID);

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
    case TVO_PARAM_NONE: return "none";
    case TVO_PARAM_TICK_HZ: return "tick_hz (the node's: microseconds)";
    case TVO_PARAM_PERIOD: return "period_us";
    case TVO_PARAM_DELAY: return "delay_us (or delay_compensation/zoh_aware)";
    case TVO_PARAM_FILTER_TF: return "filter_tf_s";
    case TVO_PARAM_GAINS: return "gain_kp/gain_kd (chain: chain_relative_degree/chain_gains)";
    case TVO_PARAM_OMEGA_MAX: return "omega_max_radps";
    case TVO_PARAM_ACCEL_MAX: return "accel_max_mps2 (chain: chain_input_max)";
    case TVO_PARAM_SPEED_MAX: return "speed_max_mps";
    case TVO_PARAM_MIN_SPEED: return "min_speed_mps";
    case TVO_PARAM_WATCHDOG: return "watchdog_periods";
    case TVO_PARAM_ROBOT_COUNT: return "robot_count";
    case TVO_PARAM_OBJECTIVE: return "the problem (robot, barrier, distance, halfspace, obstacle, offset)";
    case TVO_PARAM_VELOCITY_SOURCE: return "velocity_source";
    case TVO_PARAM_INITIAL_SPEED: return "robot[].initial_speed_mps";
    case TVO_PARAM_EPOCH: return "epoch_utime (or utime)";
    case TVO_PARAM_CLOCK_SOURCE: return "clock_source";
    case TVO_PARAM_PLANT_KIND: return "plant_kind";
    case TVO_PARAM_SESSION_ID: return "session_id";
    default: return "unknown parameter";
    }
}
