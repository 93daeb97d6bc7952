// Exact held-input motion of the unicycles; see plant.hpp.
#include "plant.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tvo_host {

namespace {
// Below this turn angle the closed forms cancel; the series' next term is ~1e-22 relative there.
constexpr double kSeriesTurnRad = 1e-4;
}  // namespace

UnicycleState exact_arc(const UnicycleState& start, const UnicycleInput& input, double dt_s)
{
    if (!(dt_s >= 0.0)) {
        throw std::invalid_argument("exact_arc: dt_s must be >= 0");
    }
    const double turn_rad = input.turn_rate_radps * dt_s;
    // Displacement in the start frame: v dt (sin(d)/d, (1 - cos d)/d) with d the turn angle.
    double sinc = 0.0;
    double cosc = 0.0;
    if (std::abs(turn_rad) < kSeriesTurnRad) {
        const double d2 = turn_rad * turn_rad;
        sinc = 1.0 - d2 / 6.0;
        cosc = turn_rad * (0.5 - d2 / 24.0);
    } else {
        sinc = std::sin(turn_rad) / turn_rad;
        cosc = (1.0 - std::cos(turn_rad)) / turn_rad;
    }
    const double distance_m = input.speed_mps * dt_s;
    const double c = std::cos(start.heading_rad);
    const double s = std::sin(start.heading_rad);
    const Eigen::Vector2d local(distance_m * sinc, distance_m * cosc);
    UnicycleState out;
    out.position_m = start.position_m + Eigen::Vector2d(c * local.x() - s * local.y(), s * local.x() + c * local.y());
    out.heading_rad = start.heading_rad + turn_rad;
    return out;
}

UnicyclePlant::UnicyclePlant(std::size_t robot_count, const std::array<UnicycleState, kMaxRobots>& initial)
    : robot_count_(robot_count), state_(initial)
{
    if (robot_count < 1 || robot_count > kMaxRobots) {
        throw std::invalid_argument("UnicyclePlant: robot count must be 1.." + std::to_string(kMaxRobots));
    }
}

void UnicyclePlant::hold(std::size_t robot, const UnicycleInput& input)
{
    input_.at(robot) = input;
}

void UnicyclePlant::advance(double dt_s)
{
    if (dt_s == 0.0) {
        return;
    }
    for (std::size_t r = 0; r < robot_count_; ++r) {
        state_[r] = exact_arc(state_[r], input_[r], dt_s);
    }
}

}  // namespace tvo_host
