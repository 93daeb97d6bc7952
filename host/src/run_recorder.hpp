// The run as CSV, one row per robot per control period (long format, easy to plot and filter), and
// the bound on everything a run writes, known before it starts.
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include <Eigen/Core>

#include "plant.hpp"

namespace tvo_host {

/// What the firmware reported about a step (telemetry_t), as far as the CSV shows it.
struct StepTelemetry {
    double barrier_c{0.0};        // c(t), 0 without inequality constraints
    double barrier_slack{0.0};    // s(t), units of the constraint functions
    double regularization{0.0};   // shift of an indefinite Hessian, 0 if none
};

class RunRecorder {
public:
    /// Opens path and writes the header; std::runtime_error if it cannot.
    explicit RunRecorder(const std::string& path);
    ~RunRecorder();
    RunRecorder(const RunRecorder&) = delete;
    RunRecorder& operator=(const RunRecorder&) = delete;

    /// One robot at t_s: true pose, its reference (target, or the constrained minimiser), the distance
    /// between them, the command in force and the firmware's telemetry of it.
    void row(double t_s, std::size_t robot, const UnicycleState& state, const Eigen::Vector2d& target_m,
             double error_m, const UnicycleInput& command, std::int32_t status, std::int32_t flags,
             const StepTelemetry& telemetry);

    /// Flushes and closes; false if anything failed to write.
    bool close();

    /// Largest size of the CSV of a run whose last row is at t_max_s with robots robots (rows at
    /// t = 0 and after each of the steps periods), from the row's format.
    static std::uint64_t max_bytes(std::int64_t steps, std::size_t robots, double t_max_s);

private:
    std::FILE* file_{nullptr};
    bool ok_{true};
};

/// The run's log holds at most this many session messages (START copies, STOP) and as many acks of each
/// node (a node acks every copy): a handshake repeats START a few times, a restart (rule 5) once more; the
/// rest go out unlogged, so bound_outputs holds.
constexpr std::uint64_t kLoggedSessionMessages = 32;
/// The log holds a node's announcement when its boot, state or session differs from the last one logged
/// of that node, else at most one per this much plant time (a running node's announcement period).
constexpr std::int64_t kLoggedAnnouncementIntervalUs = 1000000;

/// Upper bounds on the files of one run (host/README.md, "Outputs").
struct OutputBound {
    std::uint64_t csv_bytes{0};
    std::uint64_t lcm_log_bytes{0};
    std::uint64_t json_bytes{0};  // summary.json and scenario.json
    std::uint64_t total_bytes() const { return csv_bytes + lcm_log_bytes + json_bytes; }
};

/// What a run of steps periods of period_us writes at most: the CSV, the LCM log (per period each
/// robot's sample, streamed target when streamed, command and telemetry, in realtime one more command per
/// robot for the node's watchdog; the nodes' announcements and the session messages as the log takes
/// them, kLoggedSessionMessages and kLoggedAnnouncementIntervalUs) and the JSON files. Messages of other
/// sessions on the same LCM URL are logged too and not counted.
OutputBound bound_outputs(std::int64_t steps, std::int64_t period_us, std::size_t robots, bool streamed,
                          bool realtime);

}  // namespace tvo_host
