// The wire protocol as the host sees it: generated message types, and from the firmware's own
// (plain C) headers the channel names, status texts and flags.
#pragma once

#include "tvo_lcm/chain_command_t.hpp"
#include "tvo_lcm/chain_sample_t.hpp"
#include "tvo_lcm/command_header_t.hpp"
#include "tvo_lcm/node_status_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"
#include "tvo_lcm/target_t.hpp"
#include "tvo_lcm/telemetry_t.hpp"
#include "tvo_lcm/unicycle_command_t.hpp"
#include "tvo_lcm/unicycle_sample_t.hpp"

extern "C" {
#include "channels.h"
#include "tvo/status.h"
}
