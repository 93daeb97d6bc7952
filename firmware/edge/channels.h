/*
 * The protocol's names, written once: LCM channel names, the numbers that tag frames on a serial
 * link, and the names of the problem's parts in a session ack. No dependencies but the generated
 * message constants, so every transport (the LCM node, the PIL program, the bridge) and the host
 * (C++, through extern "C") share one table.
 */
#ifndef TVO_CHANNELS_H
#define TVO_CHANNELS_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Every time and sequence on the wire lies in [0, TVO_WIRE_TIME_MAX_US]: sums of two never overflow int64. */
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
#define TVO_CHANNEL_MEASUREMENT "TVO_MEASUREMENT"
#define TVO_CHANNEL_TARGET "TVO_TARGET"
#define TVO_CHANNEL_COMMAND "TVO_COMMAND"
#define TVO_CHANNEL_TELEMETRY "TVO_TELEMETRY"
/* A fleet's per-robot messages (fleet_sample_t, fleet_command_t): on the fleet bus, node k's channel is
 * the name with "_R<k>" (fleet_link.h); the bare name is the plant's per-robot leg (tvo_sim --fleet). */
#define TVO_CHANNEL_FLEET_SAMPLE "TVO_FLEET_SAMPLE"
#define TVO_CHANNEL_FLEET_COMMAND "TVO_FLEET_COMMAND"

/** Channel numbers; they also tag frames on a serial link. */
typedef enum {
    TVO_NODE_CH_SESSION = 1,
    TVO_NODE_CH_SESSION_ACK = 2,
    TVO_NODE_CH_MEASUREMENT = 3,
    TVO_NODE_CH_TARGET = 4,
    TVO_NODE_CH_COMMAND = 5,
    TVO_NODE_CH_TELEMETRY = 6
} tvo_node_channel_t;

/** LCM channel name of a channel, or NULL. */
const char *tvo_node_channel_name(int channel);
/** Channel of an LCM channel name, or 0. */
int tvo_node_channel_of(const char *name);

/**
 * The edge's own answers, apart from the core's (tvo/status.h): what the node refuses or answers with
 * before, beside or instead of the core's step. The codec maps them, with the core's errors and
 * reasons, to command_t.status (step_codec.c: tvo_step_wire_status).
 */
typedef enum {
    TVO_NODE_OK = 0,
    TVO_NODE_WRONG_ROBOT_COUNT = 1,   /* a measurement's robot_count is not the session's */
    TVO_NODE_IMPLAUSIBLE_STAMP = 2,   /* the stamp (or stamp and sequence) does not fit the schedule */
    TVO_NODE_NOT_LATER_PERIOD = 3,    /* the sample serves no later period than the last accepted one */
    TVO_NODE_STALE = 4,               /* the sample is too old for the period it would serve */
    TVO_NODE_MISSING_DERIVATIVES = 5, /* a chain session reads derivatives the sample does not carry */
    TVO_NODE_REFUSAL_STREAK = 6,      /* CLOCK_PLANT: watchdog_periods refusals in a row stop the robots */
    TVO_NODE_SESSION_CONFLICT = 7,    /* a START reuses the running session's id with other content */
    TVO_NODE_NO_SESSION = 8,          /* no such session is running (send START) */
    TVO_NODE_UNKNOWN_ACTION = 9,      /* a session message that is neither START nor STOP */
    TVO_NODE_STATUS_COUNT
} tvo_node_status_t;

/** Short English description of an edge status, for logs. */
const char *tvo_node_status_str(tvo_node_status_t status);

/** Short English description of a wire status (command_t.STATUS_*), for a plant's or the node's logs. */
const char *tvo_protocol_status_str(int32_t status);

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
