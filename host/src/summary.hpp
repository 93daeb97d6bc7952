// The run's summary: a table on stdout and a JSON file for scripts and tests.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <ostream>
#include <string>

#include "lcm_messages.hpp"
#include "options.hpp"
#include "scenario.hpp"

namespace tvo_host {

/// node_counters_t of one or more nodes, summed (each counter saturates at 2^31 - 1 on its node).
struct NodeCounterSums {
    std::uint64_t accepted{0};
    std::uint64_t refused{0};                   // every status
    std::array<std::uint64_t, tvo_lcm::node_counters_t::STATUS_SLOTS> refused_by_status{};
    std::uint64_t malformed{0};
    std::uint64_t unauthenticated{0};
    std::uint64_t replayed{0};
    std::uint64_t wrong_boot{0};
    std::uint64_t idle{0};
    std::uint64_t other_session{0};
    std::uint64_t predicted{0};
    std::uint64_t safe_stops{0};
    std::uint64_t targets_refused{0};
    std::uint64_t speed_mismatch{0};
    std::uint64_t sessions{0};
    void add(const tvo_lcm::node_counters_t& c);
};

struct RunSummary {
    double final_error_m{0.0};
    double rms_error_last5s_m{0.0};  // over the whole run if it is kRmsWindowS or shorter
    bool rms_whole_run{false};
    double max_abs_omega_radps{0.0};
    std::int64_t steps{0};
    double steps_per_s{0.0};
    std::uint64_t faults{0};
    std::uint64_t commands{0};
    std::uint64_t drops{0};
    std::uint64_t late_commands{0};
    std::uint64_t lost_answers{0};
    std::uint64_t lost_telemetry{0};
    std::uint64_t link_lost_measurements{0};
    std::uint64_t ignored_commands{0};
    std::uint64_t other_session_commands{0};
    std::uint64_t session_restarts{0};
    std::uint64_t safe_stop_commands{0};
    std::optional<double> first_safe_stop_after_loss_s;  // realtime runs with --link-loss

    // The run's nodes' own counters since they started, from their newest announcements (TVO_NODE: at
    // the end, the one each node makes after STOP), summed over the nodes; absent if none was heard.
    std::optional<NodeCounterSums> node_counters;

    // Where the scenario has them (host/README.md defines each); absent keys do not apply.
    std::optional<std::uint64_t> collisions;
    std::optional<double> min_clearance_m;
    std::optional<double> min_distance_m;
    std::optional<double> min_distance_crossing_m;
    std::optional<double> final_distance_m;
    std::optional<double> max_violation_frac;
    std::optional<double> max_violation_min_bound_frac;
    std::optional<double> max_violation_max_bound_frac;
    std::optional<double> initial_violation_frac;
    std::optional<double> time_to_feasible_s;   // infinity: infeasible at the end (JSON null)
    std::optional<double> equality_residual_m;
    std::optional<std::uint64_t> regularized_steps;
};

void print_summary_table(std::ostream& out, const RunSummary& summary, const SimOptions& options);

/// Keys: final_error_m, rms_error_last5s_m, max_abs_omega_radps, steps, steps_per_s, faults, commands,
/// the transport and session counters, then the optional keys that are set (same names as the
/// fields; a non-finite value is written as null). host/README.md defines each.
/// std::runtime_error if the file cannot be written.
void write_summary_json(const std::string& path, const RunSummary& summary);

/// The scenario's geometry for the plot (tools/plot_run.py): name, robot radius, obstacles, distance
/// bounds, half-spaces, offsets, crossing window. std::runtime_error if the file cannot be written.
void write_scenario_json(const std::string& path, const Scenario& scenario, double duration_s);

}  // namespace tvo_host
