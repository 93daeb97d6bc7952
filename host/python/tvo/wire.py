"""The protocol's channel names (lcm_types/README.md, "Channels"), as firmware/edge/channels.h writes
them once: read from it at build time into _channels_h.py.

    from tvo import wire
    lc.subscribe(wire.NODE, on_node)        # "TVO_NODE"
"""
from ._channels_h import (CHAIN_COMMAND, CHAIN_SAMPLE, COMMAND, NODE, SAMPLE, SESSION, SESSION_ACK, TARGET,
                          TELEMETRY)

__all__ = ["NODE", "SESSION", "SESSION_ACK", "SAMPLE", "TARGET", "COMMAND", "TELEMETRY", "CHAIN_SAMPLE",
           "CHAIN_COMMAND"]
