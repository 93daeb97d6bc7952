// What a scenario is and what the metrics derive from it; see scenario.hpp. The scenarios themselves
// are files (host/scenarios/*.yaml, read by scenario_file.cpp).
#include "scenario.hpp"

#include <cmath>
#include <stdexcept>

#include <Eigen/Dense>

namespace tvo_host {

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

void BarrierOverrides::apply(const BarrierOverrides& other)
{
    c0 = other.c0 ? other.c0 : c0;
    alpha_c_per_s = other.alpha_c_per_s ? other.alpha_c_per_s : alpha_c_per_s;
    c_max = other.c_max ? other.c_max : c_max;
    delta0 = other.delta0 ? other.delta0 : delta0;
    alpha_s_per_s = other.alpha_s_per_s ? other.alpha_s_per_s : alpha_s_per_s;
    slack_margin = other.slack_margin ? other.slack_margin : slack_margin;
    relaxation_degree = other.relaxation_degree ? other.relaxation_degree : relaxation_degree;
}

std::array<Eigen::Vector2d, kMaxRobots> Scenario::references(double t_s) const
{
    std::array<Eigen::Vector2d, kMaxRobots> ref;
    for (std::size_t r = 0; r < kMaxRobots; ++r) {
        ref[r] = r < robot_count ? targets[r].position(t_s) : Eigen::Vector2d::Zero();
    }
    if (offsets.empty()) {
        return ref;
    }
    // KKT system of the equality-constrained quadratic: [W A^T; A 0] [y; nu] = [W y_d; d(t)].
    const auto n = static_cast<Eigen::Index>(2 * robot_count);
    const auto q = static_cast<Eigen::Index>(2 * offsets.size());
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + q, n + q);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + q);
    for (std::size_t r = 0; r < robot_count; ++r) {
        for (Eigen::Index axis = 0; axis < 2; ++axis) {
            const Eigen::Index i = static_cast<Eigen::Index>(2 * r) + axis;
            kkt(i, i) = weights[r][axis];
            rhs(i) = weights[r][axis] * ref[r][axis];
        }
    }
    for (std::size_t k = 0; k < offsets.size(); ++k) {
        const Eigen::Vector2d d = offsets[k].offset.position(t_s);
        for (Eigen::Index axis = 0; axis < 2; ++axis) {
            const Eigen::Index row = n + static_cast<Eigen::Index>(2 * k) + axis;
            const Eigen::Index a = static_cast<Eigen::Index>(2 * offsets[k].robot_a) + axis;
            const Eigen::Index b = static_cast<Eigen::Index>(2 * offsets[k].robot_b) + axis;
            kkt(row, a) = 1.0;
            kkt(row, b) = -1.0;
            kkt(a, row) = 1.0;
            kkt(b, row) = -1.0;
            rhs(row) = d[axis];
        }
    }
    const Eigen::VectorXd z = kkt.fullPivLu().solve(rhs);
    for (std::size_t r = 0; r < robot_count; ++r) {
        ref[r] = z.segment<2>(static_cast<Eigen::Index>(2 * r));
    }
    return ref;
}

std::optional<std::array<std::size_t, 2>> Scenario::reported_pair() const
{
    if (!distances.empty()) {
        return std::array<std::size_t, 2>{distances.front().robot_a, distances.front().robot_b};
    }
    if (!offsets.empty()) {
        return std::array<std::size_t, 2>{offsets.front().robot_a, offsets.front().robot_b};
    }
    return std::nullopt;
}

}  // namespace tvo_host
