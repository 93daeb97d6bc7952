// The run as CSV, one row per robot per control period (long format, easy to plot and filter).
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

private:
    std::FILE* file_{nullptr};
    bool ok_{true};
};

}  // namespace tvo_host
