/* The protocol's channel table; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

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
