/* The protocol's channel table and the names of its codes; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

#include "tvo/defaults.h"
#include "tvo/status.h"
#include "tvo_lcm_chain_command_t.h"
#include "tvo_lcm_chain_sample_t.h"
#include "tvo_lcm_command_header_t.h"
#include "tvo_lcm_node_counters_t.h"
#include "tvo_lcm_node_status_t.h"
#include "tvo_lcm_session_ack_t.h"
#include "tvo_lcm_session_t.h"
#include "tvo_lcm_target_t.h"
#include "tvo_lcm_telemetry_t.h"
#include "tvo_lcm_unicycle_command_t.h"
#include "tvo_lcm_unicycle_sample_t.h"

/* The wire's flags that shape a command are the core's bits (the HOLDING and SAFE_STOP bits are the
 * wire's own, derived from the outcome in step_codec.c): a build where one drifts fails here. The
 * statuses and parameters are the wire's own numbers, mapped in the codecs. */
#define WIRE_EQUALS_CORE(wire, core) _Static_assert((wire) == (core), #wire " must equal " #core)
#define FLAG_ON_WIRE(name) WIRE_EQUALS_CORE(TVO_LCM_COMMAND_HEADER_T_FLAG_##name, TVO_FLAG_##name)
FLAG_ON_WIRE(OMEGA_SATURATED); FLAG_ON_WIRE(ACCEL_SATURATED); FLAG_ON_WIRE(SPEED_SATURATED); FLAG_ON_WIRE(LOW_SPEED);
FLAG_ON_WIRE(PREDICTED); FLAG_ON_WIRE(REGULARIZED); FLAG_ON_WIRE(SPEED_MISMATCH);
/* The core's flags fit the wire's int16 field, and none of them takes the wire's own two bits. */
_Static_assert((TVO_FLAG_OMEGA_SATURATED | TVO_FLAG_ACCEL_SATURATED | TVO_FLAG_SPEED_SATURATED | TVO_FLAG_LOW_SPEED |
                TVO_FLAG_PREDICTED | TVO_FLAG_REGULARIZED | TVO_FLAG_SPEED_MISMATCH) <= 0x7fff,
               "command_header_t.flags is an int16");
_Static_assert(((TVO_FLAG_OMEGA_SATURATED | TVO_FLAG_ACCEL_SATURATED | TVO_FLAG_SPEED_SATURATED | TVO_FLAG_LOW_SPEED |
                 TVO_FLAG_PREDICTED | TVO_FLAG_REGULARIZED | TVO_FLAG_SPEED_MISMATCH) &
                (TVO_LCM_COMMAND_HEADER_T_FLAG_HOLDING | TVO_LCM_COMMAND_HEADER_T_FLAG_SAFE_STOP)) == 0,
               "HOLDING and SAFE_STOP are the wire's own bits");
/* Every wire status has a slot in node_counters_t.refused. */
_Static_assert(TVO_LCM_COMMAND_HEADER_T_STATUS_ERR_IMPLAUSIBLE_MEASUREMENT < TVO_LCM_NODE_COUNTERS_T_STATUS_SLOTS,
               "node_counters_t.refused has a slot per wire status");
/* One limit for the whole wire (session_codec.c checks that it holds the build's robots). */
_Static_assert(TVO_LCM_SESSION_T_MAX_ROBOTS <= INT8_MAX, "a robot index is an int8 on the wire");

/* The encoded sizes (lcm-gen's _encoded_size of each type: fixed arrays only, so one size per type;
 * test_channels checks each against the generated code). */
#define BYTES_SESSION 11427u
#define BYTES_SESSION_ACK 47u
#define BYTES_UNICYCLE_SAMPLE 50u
#define BYTES_TARGET 65u
#define BYTES_UNICYCLE_COMMAND 36u
#define BYTES_TELEMETRY 109u
#define BYTES_NODE_STATUS 211u
#define BYTES_CHAIN_SAMPLE 58u
#define BYTES_CHAIN_COMMAND 36u
_Static_assert(BYTES_SESSION == TVO_NODE_LARGEST_MESSAGE_BYTES, "session_t is the largest message");

typedef struct {
    const char *name;
    uint32_t message_bytes;
    int64_t (*fingerprint)(void); /* lcm-gen's hash of the channel's type: its first 8 encoded bytes */
    uint8_t input;                /* a node takes it */
} channel_t;

static const channel_t channels[TVO_NODE_CH_LAST + 1] = {
    [TVO_NODE_CH_SESSION] = {TVO_CHANNEL_SESSION, BYTES_SESSION, __tvo_lcm_session_t_get_hash, 1u},
    [TVO_NODE_CH_SESSION_ACK] = {TVO_CHANNEL_SESSION_ACK, BYTES_SESSION_ACK, __tvo_lcm_session_ack_t_get_hash, 0u},
    [TVO_NODE_CH_SAMPLE] = {TVO_CHANNEL_SAMPLE, BYTES_UNICYCLE_SAMPLE, __tvo_lcm_unicycle_sample_t_get_hash, 1u},
    [TVO_NODE_CH_TARGET] = {TVO_CHANNEL_TARGET, BYTES_TARGET, __tvo_lcm_target_t_get_hash, 1u},
    [TVO_NODE_CH_COMMAND] = {TVO_CHANNEL_COMMAND, BYTES_UNICYCLE_COMMAND, __tvo_lcm_unicycle_command_t_get_hash, 0u},
    [TVO_NODE_CH_TELEMETRY] = {TVO_CHANNEL_TELEMETRY, BYTES_TELEMETRY, __tvo_lcm_telemetry_t_get_hash, 0u},
    [TVO_NODE_CH_NODE] = {TVO_CHANNEL_NODE, BYTES_NODE_STATUS, __tvo_lcm_node_status_t_get_hash, 0u},
    [TVO_NODE_CH_CHAIN_SAMPLE] = {TVO_CHANNEL_CHAIN_SAMPLE, BYTES_CHAIN_SAMPLE, __tvo_lcm_chain_sample_t_get_hash, 1u},
    [TVO_NODE_CH_CHAIN_COMMAND] = {TVO_CHANNEL_CHAIN_COMMAND, BYTES_CHAIN_COMMAND, __tvo_lcm_chain_command_t_get_hash,
                                   0u},
};

static const channel_t *channel_of(int channel)
{
    return (channel >= TVO_NODE_CH_FIRST && channel <= TVO_NODE_CH_LAST) ? &channels[channel] : NULL;
}

const char *tvo_node_channel_name(int channel)
{
    const channel_t *c = channel_of(channel);
    return c != NULL ? c->name : NULL;
}

int tvo_node_channel_of(const char *name)
{
    for (int channel = TVO_NODE_CH_FIRST; name != NULL && channel <= TVO_NODE_CH_LAST; ++channel) {
        if (strcmp(name, channels[channel].name) == 0) {
            return channel;
        }
    }
    return 0;
}

int tvo_node_channel_is_input(int channel)
{
    const channel_t *c = channel_of(channel);
    return c != NULL && c->input;
}

uint32_t tvo_node_channel_message_bytes(int channel)
{
    const channel_t *c = channel_of(channel);
    return c != NULL ? c->message_bytes : 0u;
}

uint64_t tvo_node_channel_fingerprint(int channel)
{
    const channel_t *c = channel_of(channel);
    return c != NULL ? (uint64_t)c->fingerprint() : 0u;
}

static uint64_t fnv_double(uint64_t hash, double value)
{
    uint64_t bits = 0u;
    memcpy(&bits, &value, sizeof(bits));
    for (int b = 0; b < 8; ++b) {
        hash ^= (bits >> (8 * b)) & 0xffu;
        hash *= 0x100000001b3ull;
    }
    return hash;
}

uint64_t tvo_joint_digest(const double *speed_mps, const double *turn_rate_radps, int32_t robot_count)
{
    if (speed_mps == NULL || turn_rate_radps == NULL || robot_count < 0) {
        return 0u;
    }
    uint64_t hash = 0xcbf29ce484222325ull;
    for (int32_t r = 0; r < robot_count && r < TVO_LCM_SESSION_T_MAX_ROBOTS; ++r) {
        hash = fnv_double(hash, speed_mps[r]);
        hash = fnv_double(hash, turn_rate_radps[r]);
    }
    return hash;
}

int tvo_protocol_default_start(tvo_lcm_session_t *start, int32_t robot_count)
{
    if (start == NULL || robot_count < 1 || robot_count > TVO_LCM_SESSION_T_MAX_ROBOTS) {
        return -1;
    }
    memset(start, 0, sizeof(*start));
    start->protocol_version = TVO_LCM_NODE_STATUS_T_PROTOCOL_VERSION;
    start->action = TVO_LCM_SESSION_T_ACTION_START;
    start->clock_source = TVO_LCM_SESSION_T_CLOCK_PLANT;
    start->period_us = TVO_DEFAULT_PERIOD_US;
    start->delay_us = TVO_DEFAULT_DELAY_US;
    start->delay_compensation = 1;
    start->watchdog_periods = TVO_DEFAULT_WATCHDOG_PERIODS;
    start->plant_kind = TVO_LCM_SESSION_T_PLANT_UNICYCLE;
    start->velocity_source = TVO_LCM_SESSION_T_VELOCITY_FROM_POSE;
    start->filter_tf_s = TVO_DEFAULT_FILTER_TF_S;
    start->gain_kp = TVO_DEFAULT_GAIN_KP;
    start->gain_kd = TVO_DEFAULT_GAIN_KD;
    start->omega_max_radps = TVO_DEFAULT_OMEGA_MAX_RADPS;
    start->accel_max_mps2 = TVO_DEFAULT_ACCEL_MAX_MPS2;
    start->speed_max_mps = TVO_DEFAULT_SPEED_MAX_MPS;
    start->min_speed_mps = TVO_DEFAULT_MIN_SPEED_MPS;
    start->robot_count = robot_count;
    for (int32_t r = 0; r < robot_count; ++r) {
        start->robot[r].tracking_weight[0] = 1.0;
        start->robot[r].tracking_weight[1] = 1.0;
    }
    start->barrier.c0 = TVO_DEFAULT_BARRIER_C0;
    start->barrier.alpha_c_per_s = TVO_DEFAULT_BARRIER_ALPHA_C_PER_S;
    start->barrier.c_max = TVO_DEFAULT_BARRIER_C_MAX;
    start->barrier.delta0 = TVO_DEFAULT_BARRIER_DELTA0;
    start->barrier.alpha_s_per_s = TVO_DEFAULT_BARRIER_ALPHA_S_PER_S;
    start->barrier.slack_margin = TVO_DEFAULT_BARRIER_SLACK_MARGIN;
    start->barrier.relaxation_degree = TVO_DEFAULT_BARRIER_RELAXATION_DEGREE;
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
    case TVO_LCM_SESSION_ACK_T_PARAM_ROBOT_COUNT: return "robot_count (at most the node's max_robots; a chain: 1)";
    case TVO_LCM_SESSION_ACK_T_PARAM_OBJECTIVE: return "the problem (robot, barrier, distance, halfspace, obstacle, offset)";
    case TVO_LCM_SESSION_ACK_T_PARAM_VELOCITY_SOURCE: return "velocity_source";
    case TVO_LCM_SESSION_ACK_T_PARAM_INITIAL_SPEED: return "robot[].initial_speed_mps";
    case TVO_LCM_SESSION_ACK_T_PARAM_EPOCH: return "epoch_utime (or utime)";
    case TVO_LCM_SESSION_ACK_T_PARAM_CLOCK_SOURCE: return "clock_source";
    case TVO_LCM_SESSION_ACK_T_PARAM_PLANT_KIND: return "plant_kind";
    case TVO_LCM_SESSION_ACK_T_PARAM_SESSION_ID: return "session_id";
    case TVO_LCM_SESSION_ACK_T_PARAM_PROTOCOL_VERSION: return "protocol_version (node_status_t.PROTOCOL_VERSION)";
    case TVO_LCM_SESSION_ACK_T_PARAM_TELEMETRY_EVERY: return "telemetry_every (0 .. 2^20)";
    default: return "unknown parameter";
    }
}
