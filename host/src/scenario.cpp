// Demo scenario and analytic targets; see scenario.hpp.
#include "scenario.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Geometry>

namespace tvo_host {

namespace {
constexpr double kPi = 3.14159265358979323846;
}  // namespace

bool parse_target_kind(const std::string& text, TargetKind* kind)
{
    if (text == "ellipse") {
        *kind = TargetKind::Ellipse;
    } else if (text == "circle") {
        *kind = TargetKind::Circle;
    } else if (text == "streamed") {
        *kind = TargetKind::Streamed;
    } else {
        return false;
    }
    return true;
}

const char* target_kind_name(TargetKind kind)
{
    switch (kind) {
    case TargetKind::Ellipse: return "ellipse";
    case TargetKind::Circle: return "circle";
    case TargetKind::Streamed: return "streamed";
    }
    return "unknown";
}

std::array<Eigen::Vector2d, 4> EllipseTarget::derivatives(double t_s) const
{
    // d^j/dt^j (cos phi, sin phi) = omega^j (cos, sin)(phi + j pi/2): one formula for every order.
    const Eigen::Rotation2Dd rotation(rotation_rad);
    const double phi = omega_radps * t_s + phase_rad;
    std::array<Eigen::Vector2d, 4> deriv;
    double omega_pow = 1.0;
    for (std::size_t j = 0; j < deriv.size(); ++j) {
        const double shifted = phi + static_cast<double>(j) * kPi / 2.0;
        const Eigen::Vector2d local(semi_axis_m.x() * omega_pow * std::cos(shifted),
                                    semi_axis_m.y() * omega_pow * std::sin(shifted));
        deriv[j] = rotation * local;
        omega_pow *= omega_radps;
    }
    deriv[0] += center_m;
    return deriv;
}

Eigen::Vector2d EllipseTarget::position(double t_s) const
{
    const double phi = omega_radps * t_s + phase_rad;
    const Eigen::Vector2d local(semi_axis_m.x() * std::cos(phi), semi_axis_m.y() * std::sin(phi));
    return center_m + Eigen::Rotation2Dd(rotation_rad) * local;
}

Scenario make_demo_scenario(std::size_t robot_count, TargetKind kind)
{
    if (robot_count < 1 || robot_count > kMaxRobots) {
        throw std::invalid_argument("robot count must be 1..4");
    }
    Scenario scenario;
    scenario.kind = kind;
    scenario.robot_count = robot_count;
    const Eigen::Vector2d semi_axis_m = kind == TargetKind::Circle ? Eigen::Vector2d(2.0, 2.0)
                                                                   : Eigen::Vector2d(3.0, 1.5);
    for (std::size_t r = 0; r < robot_count; ++r) {
        const double turn_rad = 2.0 * kPi * static_cast<double>(r) / static_cast<double>(robot_count);
        EllipseTarget& target = scenario.targets[r];
        target.center_m = Eigen::Vector2d::Zero();
        target.semi_axis_m = semi_axis_m;
        target.omega_radps = 2.0 * kPi / 10.0;
        target.phase_rad = turn_rad;
        target.rotation_rad = 0.0;
        UnicycleState& start = scenario.starts[r];
        start.position_m = Eigen::Rotation2Dd(turn_rad) * Eigen::Vector2d(-1.0, -2.0);
        start.heading_rad = turn_rad;
        scenario.weights[r] = Eigen::Vector2d(1.0, 1.0);
    }
    return scenario;
}

}  // namespace tvo_host
