/*
 * The protocol's channels: LCM names, and the numbers that tag frames on a serial link. No
 * dependencies, so transports (the LCM node, the PIL program, the bridge) share one table.
 */
#ifndef TVO_CHANNELS_H
#define TVO_CHANNELS_H

/* LCM channels of the protocol (the host uses the same names). */
#define TVO_CHANNEL_SESSION "TVO_SESSION"
#define TVO_CHANNEL_SESSION_ACK "TVO_SESSION_ACK"
#define TVO_CHANNEL_MEASUREMENT "TVO_MEASUREMENT"
#define TVO_CHANNEL_TARGET "TVO_TARGET"
#define TVO_CHANNEL_COMMAND "TVO_COMMAND"
#define TVO_CHANNEL_TELEMETRY "TVO_TELEMETRY"

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

#endif /* TVO_CHANNELS_H */
