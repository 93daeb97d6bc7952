// The run's summary: a table on stdout and a JSON file for scripts and tests.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "options.hpp"

namespace tvo_host {

struct RunSummary {
    double final_error_m{0.0};
    double rms_error_last5s_m{0.0};
    double max_abs_omega_radps{0.0};
    std::int64_t steps{0};
    double steps_per_s{0.0};
    std::uint64_t faults{0};
    std::uint64_t commands{0};
    std::uint64_t drops{0};
    std::uint64_t late_commands{0};
};

void print_summary_table(std::ostream& out, const RunSummary& summary, const SimOptions& options);

/// Keys exactly: final_error_m, rms_error_last5s_m, max_abs_omega_radps, steps, steps_per_s, faults.
/// std::runtime_error if the file cannot be written.
void write_summary_json(const std::string& path, const RunSummary& summary);

}  // namespace tvo_host
