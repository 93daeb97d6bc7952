// N unicycles x' = v cos(theta), y' = v sin(theta), theta' = omega, integrated exactly in double.
//
// The plant is the ground truth of the loop: it never shares code with the firmware (which runs in
// float and predicts with its own arcs), so a bug in one cannot hide in the other.
#pragma once

#include <array>
#include <cstddef>

#include <Eigen/Core>

namespace tvo_host {

/// Most robots the simulator runs: the wire's limit (session_t.MAX_ROBOTS, checked in plant_wire.hpp; this
/// library has no LCM). A node takes up to its build's (node_status_t.max_robots).
constexpr std::size_t kMaxRobots = 32;

struct UnicycleState {
    Eigen::Vector2d position_m{Eigen::Vector2d::Zero()};
    double heading_rad{0.0};  // unwrapped: continuous over the run
};

/// Input held (zero-order hold) between two command application instants.
struct UnicycleInput {
    double speed_mps{0.0};
    double turn_rate_radps{0.0};
};

/// Exact pose after dt_s >= 0 under a held input: a circular arc, or a line when the turn vanishes.
UnicycleState exact_arc(const UnicycleState& start, const UnicycleInput& input, double dt_s);

class UnicyclePlant {
public:
    /// robot_count in 1..kMaxRobots (std::invalid_argument otherwise); every robot at rest.
    UnicyclePlant(std::size_t robot_count, const std::array<UnicycleState, kMaxRobots>& initial);

    std::size_t robot_count() const { return robot_count_; }
    const UnicycleState& state(std::size_t robot) const { return state_.at(robot); }
    const UnicycleInput& input(std::size_t robot) const { return input_.at(robot); }

    /// The input robot `robot` holds from now on.
    void hold(std::size_t robot, const UnicycleInput& input);

    /// Moves every robot exactly along its held arc for dt_s >= 0 seconds.
    void advance(double dt_s);

private:
    std::size_t robot_count_;
    std::array<UnicycleState, kMaxRobots> state_;
    std::array<UnicycleInput, kMaxRobots> input_{};
};

}  // namespace tvo_host
