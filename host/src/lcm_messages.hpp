// The wire protocol as the host sees it: generated message types, and from the firmware's own
// (plain C) headers the channel names, status codes, parameter names and flags.
#pragma once

#include "tvo_lcm/command_t.hpp"
#include "tvo_lcm/measurement_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"
#include "tvo_lcm/target_t.hpp"
#include "tvo_lcm/telemetry_t.hpp"

extern "C" {
#include "channels.h"
#include "tvo/status.h"
}
