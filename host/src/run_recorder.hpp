// The run as CSV, one row per robot per control period (long format, easy to plot and filter).
#pragma once

#include <cstdint>
#include <cstdio>
#include <string>

#include <Eigen/Core>

#include "plant.hpp"

namespace tvo_host {

class RunRecorder {
public:
    /// Opens path and writes the header; std::runtime_error if it cannot.
    explicit RunRecorder(const std::string& path);
    ~RunRecorder();
    RunRecorder(const RunRecorder&) = delete;
    RunRecorder& operator=(const RunRecorder&) = delete;

    /// One robot at t_s: true pose, its target, the distance between them, the command in force.
    void row(double t_s, std::size_t robot, const UnicycleState& state, const Eigen::Vector2d& target_m,
             double error_m, const UnicycleInput& command, std::int32_t status, std::int32_t flags);

    /// Flushes and closes; false if anything failed to write.
    bool close();

private:
    std::FILE* file_{nullptr};
    bool ok_{true};
};

}  // namespace tvo_host
