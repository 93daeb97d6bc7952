/* The protocol's channel table; see channels.h. */
#include "channels.h"

#include <stddef.h>
#include <string.h>

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
