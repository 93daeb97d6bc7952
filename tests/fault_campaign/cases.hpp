// The campaign's cases: each runs the plant against the node, injects its faults at known instants
// and prints one line per check.
#pragma once

#include <string>
#include <vector>

#include "lockstep.hpp"

namespace campaign {

struct Case {
    std::string name;
    std::string summary;
    void (*run)(Context& ctx);
    bool needs_spawn;   // restarts or watches the node process: needs --node PATH
};

const std::vector<Case>& all_cases();

/// The default session of a run: a fresh id, the robot starting at (-1, -2) heading 0.
LockstepConfig base_config(Context& ctx);

// Lockstep cases (cases.cpp).
void case_stray_future_stamp(Context& ctx);
void case_stray_past_stamp(Context& ctx);
void case_garbage(Context& ctx);
void case_huge_sequence(Context& ctx);
void case_duplicates(Context& ctx);
void case_reordering(Context& ctx);
void case_loss(Context& ctx);
void case_refusal_watchdog(Context& ctx);
void case_speed_mismatch(Context& ctx);
void case_rejected_start_during_run(Context& ctx);
void case_same_id_start(Context& ctx);
void case_implausible_epoch(Context& ctx);
void case_node_restart(Context& ctx);
void case_plant_restart(Context& ctx);
void case_clock_plant_limits(Context& ctx);
// The keyed bus under attack (case_auth.cpp).
void case_auth_attacks(Context& ctx);
void case_auth_node_restart(Context& ctx);
// The wall-clock case (case_node_clock.cpp).
void case_link_loss_node_clock(Context& ctx);

}  // namespace campaign
