/* The protocol's channel table; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

#include "tvo/status.h"
#include "tvo_lcm_session_ack_t.h"

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
