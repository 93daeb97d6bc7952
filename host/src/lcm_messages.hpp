// The wire protocol as the host sees it: generated message types, channel names, firmware codes.
#pragma once

#include "tvo_lcm/command_t.hpp"
#include "tvo_lcm/measurement_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"
#include "tvo_lcm/target_t.hpp"
#include "tvo_lcm/telemetry_t.hpp"

// Status codes, parameter names and flags come from the firmware's own (plain C) header.
extern "C" {
#include "tvo/status.h"
}

namespace tvo_host::channel {
inline const char* const kSession = "TVO_SESSION";
inline const char* const kSessionAck = "TVO_SESSION_ACK";
inline const char* const kMeasurement = "TVO_MEASUREMENT";
inline const char* const kTarget = "TVO_TARGET";
inline const char* const kCommand = "TVO_COMMAND";
inline const char* const kTelemetry = "TVO_TELEMETRY";
}  // namespace tvo_host::channel
