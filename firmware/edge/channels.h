/*
 * The protocol's names, written once: LCM channel names, the numbers that tag frames on a serial
 * link, which channels a node takes, each channel's fixed message size, the edge's own statuses and
 * the names of the wire's codes. No dependencies but the generated message constants, so every
 * transport (the LCM node, the PIL program, the bridge) and the host (C++, through extern "C") share
 * one table. lcm_types/README.md is the contract.
 */
#ifndef TVO_CHANNELS_H
#define TVO_CHANNELS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Every time on the wire lies in [0, TVO_WIRE_TIME_MAX_US]: sums of two never overflow int64. */
#define TVO_WIRE_TIME_MAX_US ((int64_t)1 << 60)

/**
 * How far a session's epoch may lie from its START's utime, either way: half the controller's clock
 * span (TVO_MAX_TICK_SPAN / 2 us, 8.9 min; checked in session_codec.c), so that a first sample up to
 * another as much after the START is still served.
 */
#define TVO_SESSION_EPOCH_SPAN_US ((int64_t)536870911)

/* LCM channels of the protocol (the host uses the same names). */
#define TVO_CHANNEL_SESSION "TVO_SESSION"
#define TVO_CHANNEL_SESSION_ACK "TVO_SESSION_ACK"
#define TVO_CHANNEL_SAMPLE "TVO_SAMPLE"
#define TVO_CHANNEL_TARGET "TVO_TARGET"
#define TVO_CHANNEL_COMMAND "TVO_COMMAND"
#define TVO_CHANNEL_TELEMETRY "TVO_TELEMETRY"
#define TVO_CHANNEL_NODE "TVO_NODE"
#define TVO_CHANNEL_CHAIN_SAMPLE "TVO_CHAIN_SAMPLE"
#define TVO_CHANNEL_CHAIN_COMMAND "TVO_CHAIN_COMMAND"

/** Channel numbers; they also tag frames on a serial link. */
typedef enum {
    TVO_NODE_CH_SESSION = 1,        /* session_t, plant -> nodes (in) */
    TVO_NODE_CH_SESSION_ACK = 2,    /* session_ack_t, node -> plant */
    TVO_NODE_CH_SAMPLE = 3,         /* unicycle_sample_t, plant -> nodes (in) */
    TVO_NODE_CH_TARGET = 4,         /* target_t, plant -> nodes (in) */
    TVO_NODE_CH_COMMAND = 5,        /* unicycle_command_t, node -> plant */
    TVO_NODE_CH_TELEMETRY = 6,      /* telemetry_t, node -> plant */
    TVO_NODE_CH_NODE = 7,           /* node_status_t, node -> plants */
    TVO_NODE_CH_CHAIN_SAMPLE = 8,   /* chain_sample_t, plant -> node (in) */
    TVO_NODE_CH_CHAIN_COMMAND = 9   /* chain_command_t, node -> plant */
} tvo_node_channel_t;

/** The first and last channel numbers (every number between is a channel). */
#define TVO_NODE_CH_FIRST TVO_NODE_CH_SESSION
#define TVO_NODE_CH_LAST TVO_NODE_CH_CHAIN_COMMAND

/** LCM channel name of a channel, or NULL. */
const char *tvo_node_channel_name(int channel);
/** Channel of an LCM channel name, or 0. */
int tvo_node_channel_of(const char *name);
/** 1 if a node takes the channel (SESSION, SAMPLE, TARGET, CHAIN_SAMPLE), else 0. */
int tvo_node_channel_is_input(int channel);
/**
 * The encoded size in bytes of the one message type a channel carries (every type has fixed arrays
 * only, so each has one size, the 8-byte fingerprint included), or 0 for no channel. A frame of
 * another length (a keyed one: plus the 28-byte trailer) is no message of that channel.
 */
uint32_t tvo_node_channel_message_bytes(int channel);

/** The LCM fingerprint of the type a channel carries (its first 8 encoded bytes, big-endian), 0 for no channel. */
uint64_t tvo_node_channel_fingerprint(int channel);
/** The largest of them: session_t's. */
#define TVO_NODE_LARGEST_MESSAGE_BYTES 11427u

/**
 * FNV-1a 64 of a joint command, the digest in telemetry_t.joint_digest: speed then turn rate of robots
 * 0 .. robot_count-1 (a chain's two inputs in their place), each as an IEEE-754 double's bits, least
 * significant byte first, so the same on every machine. 0 for NULL arrays or a negative count.
 */
uint64_t tvo_joint_digest(const double *speed_mps, const double *turn_rate_radps, int32_t robot_count);

/**
 * The edge's own answers, apart from the core's (tvo/status.h): what the node refuses or answers with
 * before, beside or instead of the core's step. The codec maps them, with the core's errors and
 * reasons, to command_header_t.status (step_codec.c: tvo_step_wire_status).
 */
typedef enum {
    TVO_NODE_OK = 0,
    TVO_NODE_WRONG_ROBOT = 1,         /* a sample's or target's robot is not one of the session's */
    TVO_NODE_IMPLAUSIBLE_STAMP = 2,   /* the stamp (or stamp and sequence) does not fit the schedule */
    TVO_NODE_NOT_LATER_PERIOD = 3,    /* the sample serves no later period than the last accepted one */
    TVO_NODE_STALE = 4,               /* the sample is too old for the period it would serve */
    TVO_NODE_MISSING_DERIVATIVES = 5, /* a chain session reads derivatives the sample does not carry */
    TVO_NODE_SESSION_CONFLICT = 6,    /* a START reuses the running session's id with other content */
    TVO_NODE_NO_SESSION = 7,          /* no such session is running (a STOP of another id) */
    TVO_NODE_UNKNOWN_ACTION = 8,      /* a session message that is neither START nor STOP */
    TVO_NODE_ROBOT_UNHEARD = 9,       /* a robot of the period has no sample and cannot be predicted */
    TVO_NODE_WRONG_PLANT = 10,        /* a sample of another plant than the session's (unicycle, chain) */
    TVO_NODE_NOT_FINITE = 11,         /* a robot's sample, checked on arrival, has a NaN or infinite value */
    TVO_NODE_STATUS_COUNT
} tvo_node_status_t;

/** Short English description of a wire status (command_header_t.STATUS_*), for a plant's or the node's logs
 *  (wire_status.c: the core's texts where the code is the core's; link a core). A node status reads as
 *  the wire code it goes out as (tvo_step_wire_status). */
const char *tvo_protocol_status_str(int32_t status);

struct _tvo_lcm_session_t;

/**
 * A START of the paper's loop (tvo/defaults.h) for robot_count robots, lockstep (CLOCK_PLANT): the
 * protocol version, the action, h, tau with its compensation, the watchdog, the unicycle's gains and
 * limits, tracking weights 1 and the barrier's defaults; every other field zero (the session id, the
 * nodes' boots, utime, epoch and targets are the caller's). 0, or -1 (start untouched) for a NULL start
 * or a robot_count outside 1 .. session_t.MAX_ROBOTS. One place for every C plant, bench and test.
 */
int tvo_protocol_default_start(struct _tvo_lcm_session_t *start, int32_t robot_count);

/** Short name of a problem part named by a session ack (session_ack_t.PART_*), for logs. */
const char *tvo_protocol_part_str(int32_t part);

/**
 * The session_t field(s) a session ack's bad_param (session_ack_t.PARAM_*, tvo_session_param_t) stands
 * for, as a plant writes them: "epoch_utime", "period_us", ... (the core's configurations name their
 * own fields: tvo_param_str, tvo_chain_param_str).
 */
const char *tvo_protocol_param_str(int32_t param);

#ifdef __cplusplus
}
#endif

#endif /* TVO_CHANNELS_H */
