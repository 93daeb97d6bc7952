// Random perturbations of the loop: Gaussian measurement noise and a process disturbance.
#pragma once

#include <cstdint>
#include <random>

#include "plant.hpp"

namespace tvo_host {

struct MeasurementNoiseConfig {
    double position_sigma_m{0.0};   // per axis
    double heading_sigma_rad{0.0};
    double speed_sigma_mps{0.0};
};

/// What the sensor reports for one robot.
struct RobotSample {
    Eigen::Vector2d position_m{Eigen::Vector2d::Zero()};
    double heading_rad{0.0};  // wrapped to (-pi, pi]
    double speed_mps{0.0};
};

class MeasurementNoise {
public:
    MeasurementNoise(const MeasurementNoiseConfig& config, std::uint64_t seed);

    /// True pose and speed plus independent Gaussian noise (nothing drawn for a zero sigma).
    RobotSample measure(const UnicycleState& state, const UnicycleInput& input);

private:
    double draw(double sigma);

    MeasurementNoiseConfig config_;
    std::mt19937_64 rng_;
    std::normal_distribution<double> unit_{0.0, 1.0};
};

struct DisturbanceConfig {
    double speed_sigma_mps{0.0};
    double turn_rate_sigma_radps{0.0};
};

/// Actuator disturbance: each applied command is perturbed once and held, so arcs stay exact.
class ProcessDisturbance {
public:
    ProcessDisturbance(const DisturbanceConfig& config, std::uint64_t seed);

    UnicycleInput perturb(const UnicycleInput& commanded);

private:
    DisturbanceConfig config_;
    std::mt19937_64 rng_;
    std::normal_distribution<double> unit_{0.0, 1.0};
};

/// Wraps an angle to (-pi, pi].
double wrap_angle(double angle_rad);

}  // namespace tvo_host
