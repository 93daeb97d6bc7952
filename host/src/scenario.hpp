// What the robots should do: their start poses and moving targets, with analytic derivatives.
//
// The default is the demo (like the paper's Fig. 2): an ellipse, not a circle, because a held
// arc follows a circle exactly and would hide the discretization error.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include <Eigen/Core>

#include "plant.hpp"

namespace tvo_host {

/// How the firmware learns the target: on-board analytic (ellipse, circle) or streamed by the host.
enum class TargetKind { Ellipse, Circle, Streamed };

/// Parses "ellipse" | "circle" | "streamed"; false if unknown.
bool parse_target_kind(const std::string& text, TargetKind* kind);
const char* target_kind_name(TargetKind kind);

/// y_d(t) = c + R(rotation) (a cos(phi), b sin(phi)), phi = omega t + phase. a = b: a circle.
struct EllipseTarget {
    Eigen::Vector2d center_m{Eigen::Vector2d::Zero()};
    Eigen::Vector2d semi_axis_m{Eigen::Vector2d::Ones()};
    double omega_radps{0.0};
    double phase_rad{0.0};
    double rotation_rad{0.0};

    /// deriv[j] = j-th time derivative of y_d at t_s, j = 0..3 (position .. jerk).
    std::array<Eigen::Vector2d, 4> derivatives(double t_s) const;
    Eigen::Vector2d position(double t_s) const;
};

struct Scenario {
    TargetKind kind{TargetKind::Ellipse};
    std::size_t robot_count{1};
    std::array<EllipseTarget, kMaxRobots> targets{};
    std::array<UnicycleState, kMaxRobots> starts{};
    std::array<Eigen::Vector2d, kMaxRobots> weights{};  // diagonal of each tracking term's W
};

/// The demo: ellipse centre (0, 0), semi-axes (3, 1.5), omega 2 pi / 10 rad/s; robot 0 starts at
/// (-1, -2) heading 0 at rest. Further robots are the same picture turned by 2 pi r / N.
/// A circle scenario uses radius 2 with the same rate.
Scenario make_demo_scenario(std::size_t robot_count, TargetKind kind);

}  // namespace tvo_host
