// The scenarios as data; see scenario.hpp. Every number below is part of a scenario's definition
// (README.md, "Scenarios", shows and explains them).
#include "scenario.hpp"

#include <cmath>
#include <functional>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace tvo_host {

namespace {
constexpr double kPi = 3.14159265358979323846;

Eigen::Vector2d heading_vector(double heading_rad, double speed_mps)
{
    return speed_mps * Eigen::Vector2d(std::cos(heading_rad), std::sin(heading_rad));
}

UnicycleState pose(double x_m, double y_m, double heading_rad)
{
    UnicycleState s;
    s.position_m = Eigen::Vector2d(x_m, y_m);
    s.heading_rad = heading_rad;
    return s;
}

/// Times (1 ms grid over [0, T]) at which two targets are closer than distance_m: the first and last.
std::optional<TimeWindow> window_closer_than(const TargetPath& a, const TargetPath& b, double distance_m,
                                             double duration_s)
{
    std::optional<TimeWindow> window;
    const auto samples = static_cast<long>(std::llround(duration_s * 1000.0));
    for (long i = 0; i <= samples; ++i) {
        const double t = static_cast<double>(i) * 1e-3;
        if ((a.position(t) - b.position(t)).norm() < distance_m) {
            if (!window) {
                window = TimeWindow{t, t};
            }
            window->end_s = t;
        }
    }
    return window;
}

// ---- formation-max / formation-bilateral -------------------------------------------------------
// Targets as the paper builds them (sum A_j t^j, its "Section 2.4" construction): each is the
// degree-6 polynomial through seven conditions. They start at (-5, -3) and (-2, -3) moving along
// headings +0.5 and -0.5 rad (1.2 and 0.8 m/s, at zero acceleration), meet near (0.5, -3.4) at
// t = 5 s (0.1 m apart, target 1 above, crossing with velocities (1, -0.4) and (0.8, 0.5)) and end
// 4.46 m apart at T = 10 s. Their closest approach is 0.02 m at t = 5.1 s; speeds stay within
// 0.28 .. 1.2 m/s and accelerations below 1.1 m/s^2, well inside the robots' limits.
Scenario formation(const std::string& name, double min_m)
{
    Scenario s;
    s.name = name;
    s.duration_s = 10.0;
    s.robot_count = 2;
    s.targets[0] = TargetPath::through({{0.0, 0, {-5.0, -3.0}},
                                        {0.0, 1, heading_vector(0.5, 1.2)},
                                        {0.0, 2, {0.0, 0.0}},
                                        {5.0, 0, {0.5, -3.35}},
                                        {5.0, 1, {1.0, -0.4}},
                                        {10.0, 0, {4.0, -5.2}},
                                        {10.0, 1, {0.6, -0.2}}});
    s.targets[1] = TargetPath::through({{0.0, 0, {-2.0, -3.0}},
                                        {0.0, 1, heading_vector(-0.5, 0.8)},
                                        {0.0, 2, {0.0, 0.0}},
                                        {5.0, 0, {0.5, -3.45}},
                                        {5.0, 1, {0.8, 0.5}},
                                        {10.0, 0, {3.3, -0.8}},
                                        {10.0, 1, {0.5, 0.2}}});
    s.starts[0] = pose(-4.9, -4.2, 0.5);
    s.starts[1] = pose(-2.1, -4.3, -0.5);
    // The paper's objective |y1 - y1d|^2 + |y2 - y2d|^2 has no 1/2: W = 2 I in our 1/2 y^T W y form.
    s.weights[0] = Eigen::Vector2d(2.0, 2.0);
    s.weights[1] = Eigen::Vector2d(2.0, 2.0);
    DistanceBound bound;
    bound.robot_a = 0;
    bound.robot_b = 1;
    bound.min_m = min_m;
    bound.max_m = 3.0;
    s.distances.push_back(bound);
    // c(t) = e^{0.5 t} instead of the default e^{t}: the barrier keeps the pair about 1 / (c lambda)
    // inside an active bound, and with alpha_c = 1 (c = 220 when the pair swaps sides at t = 5.4 s
    // under saturated turning) the bilateral run overshot the 1 m bound by 1.2 %; with 0.5 it keeps
    // 3.5 % inside, and c(10) = 148 still brings the final distance within 5 mm of the 3 m bound
    // (measured; README.md). Both formation runs use it, so they differ only in the lower bound.
    s.barrier.alpha_c_per_s = 0.5;
    // "While the targets cross": the targets are closer than 1 m (the bilateral lower bound).
    s.crossing_window = window_closer_than(s.targets[0], s.targets[1], 1.0, s.duration_s);
    return s;
}

// ---- obstacles / obstacles-infeasible-target -----------------------------------------------------
// Four disjoint disks. The robot (radius 0.2) starts at (-6, -4.2) heading -10 rad (the paper's
// pose), the target at (-5, -5) moving along heading 0.5 rad at 0.6 m/s. Each target is the
// degree-6 polynomial through seven conditions and comes to rest (zero velocity and acceleration)
// at T = 20 s in open space.
const std::vector<Disk>& obstacle_field()
{
    static const std::vector<Disk> disks = {
        {{-3.2, -2.5}, 0.7},
        {{-0.6, -1.6}, 1.0},
        {{1.2, -4.6}, 0.8},
        {{3.0, 0.8}, 0.8},
    };
    return disks;
}

Scenario obstacles(const std::string& name, bool infeasible_target)
{
    Scenario s;
    s.name = name;
    s.duration_s = 20.0;
    s.robot_count = 1;
    s.robot_radius_m = 0.2;
    s.obstacles = obstacle_field();
    s.starts[0] = pose(-6.0, -4.2, -10.0);
    s.weights[0] = Eigen::Vector2d(1.0, 1.0);
    // c(t) = e^{0.4 t} instead of e^{t}: while the robot rides the crossed obstacle's edge (t = 9 ..
    // 12 s) the barrier holds it about 1 / (c lambda) off, 0.2 mm at alpha_c = 1 (c = 1e4 by then),
    // where 1 mm of measurement noise already made it touch (measured); at 0.4 it stays 1.3 cm off,
    // and c(20) = 3e3 leaves 6e-4 m of barrier bias on the free target at the end. Both cases share it.
    s.barrier.alpha_c_per_s = 0.4;
    const Eigen::Vector2d start_m(-5.0, -5.0);
    const Eigen::Vector2d start_velocity = heading_vector(0.5, 0.6);
    if (!infeasible_target) {
        // Threads the gap between the second and third disks: the robot's disk placed on the target
        // keeps at least 0.387 m from every obstacle (0.3 m + r required), and ends 1.86 m clear.
        s.targets[0] = TargetPath::through({{0.0, 0, start_m},
                                            {0.0, 1, start_velocity},
                                            {0.0, 2, {0.0, 0.0}},
                                            {9.0, 0, {-0.8, -3.3}},
                                            {20.0, 0, {4.2, -1.8}},
                                            {20.0, 1, {0.0, 0.0}},
                                            {20.0, 2, {0.0, 0.0}}});
    } else {
        // Runs straight through the second disk (inside it for t = 8.5 .. 12.3 s, 6 cm from its centre
        // at t = 10.4 s) and comes to rest at (1.2, 0.6), 0.81 m clear of every obstacle.
        s.targets[0] = TargetPath::through({{0.0, 0, start_m},
                                            {0.0, 1, start_velocity},
                                            {0.0, 2, {0.0, 0.0}},
                                            {8.0, 0, {-1.5, -2.5}},
                                            {20.0, 0, {1.2, 0.6}},
                                            {20.0, 1, {0.0, 0.0}},
                                            {20.0, 2, {0.0, 0.0}}});
    }
    return s;
}

// ---- infeasible-start -----------------------------------------------------------------------------
// Two robots start 4.5 m apart (heading +y, at rest) with |y1 - y2| <= 3: the start violates the
// bound, so s0 = f(y(0)) + epsilon_s > 0 and the relaxed constraint |y1 - y2|^2 - 9 <= s(t) tightens
// at rate alpha_s. The targets are feasible: 2.8 m apart, moving along +y at 0.3 m/s.
Scenario infeasible_start()
{
    Scenario s;
    s.name = "infeasible-start";
    s.duration_s = 10.0;
    s.robot_count = 2;
    PolyCoeffs left{};
    left[0][0] = -1.4;
    left[1][1] = 0.3;
    PolyCoeffs right{};
    right[0][0] = 1.4;
    right[1][1] = 0.3;
    s.targets[0] = TargetPath::polynomial(left);
    s.targets[1] = TargetPath::polynomial(right);
    s.starts[0] = pose(-2.25, 0.0, kPi / 2.0);
    s.starts[1] = pose(2.25, 0.0, kPi / 2.0);
    s.weights[0] = Eigen::Vector2d(1.0, 1.0);
    s.weights[1] = Eigen::Vector2d(1.0, 1.0);
    DistanceBound bound;
    bound.max_m = 3.0;
    s.distances.push_back(bound);
    return s;
}

// ---- formation-equality ---------------------------------------------------------------------------
// f0 = 1/2 |y1 - m_d(t)|^2 + 1/2 |y2 - m_d(t)|^2 (both robots track the midpoint target, so f0 is
// strongly convex) subject to y1 - y2 = d(t). m_d is the demo's ellipse slowed to a 20 s period;
// d(t) is a 1 m offset turning once every 10 s (a circle of radius 1 centred at 0). The constrained
// minimiser is y1 = m_d + d/2, y2 = m_d - d/2: the pair spins around the moving midpoint.
Scenario formation_equality()
{
    Scenario s;
    s.name = "formation-equality";
    s.duration_s = 20.0;
    s.robot_count = 2;
    EllipseTarget midpoint;
    midpoint.center_m = Eigen::Vector2d::Zero();
    midpoint.semi_axis_m = Eigen::Vector2d(3.0, 1.5);
    midpoint.omega_radps = 2.0 * kPi / 20.0;
    s.targets[0] = TargetPath::ellipse(midpoint);
    s.targets[1] = TargetPath::ellipse(midpoint);
    s.starts[0] = pose(1.0, -2.0, 0.0);
    s.starts[1] = pose(0.0, -2.5, 0.0);
    s.weights[0] = Eigen::Vector2d(1.0, 1.0);
    s.weights[1] = Eigen::Vector2d(1.0, 1.0);
    OffsetEquality offset;
    offset.robot_a = 0;
    offset.robot_b = 1;
    offset.offset = TargetPath::circle(Eigen::Vector2d::Zero(), 1.0, 2.0 * kPi / 10.0, 0.0);
    s.offsets.push_back(offset);
    s.settle_time_s = 5.0;
    return s;
}

struct CatalogEntry {
    ScenarioInfo info;
    std::function<Scenario(std::size_t, TargetKind)> make;
};

const std::vector<CatalogEntry>& catalog()
{
    static const std::vector<CatalogEntry> entries = {
        {{"demo", "one unicycle (--robots up to 4) tracks an ellipse, the paper's Fig. 2 setting"},
         [](std::size_t robots, TargetKind kind) { return make_demo_scenario(robots, kind); }},
        {{"formation-max", "two robots, targets approach, cross and separate; |y1 - y2| <= 3 m"},
         [](std::size_t, TargetKind) { return formation("formation-max", 0.0); }},
        {{"formation-bilateral", "the same with 1 m <= |y1 - y2| <= 3 m: the pair rides the lower bound"},
         [](std::size_t, TargetKind) { return formation("formation-bilateral", 1.0); }},
        {{"obstacles", "a disk robot (r = 0.2 m) among four disk obstacles, target in free space"},
         [](std::size_t, TargetKind) { return obstacles("obstacles", false); }},
        {{"obstacles-infeasible-target", "the same, the target runs through an obstacle: detour, re-acquire"},
         [](std::size_t, TargetKind) { return obstacles("obstacles-infeasible-target", true); }},
        {{"infeasible-start", "two robots start 4.5 m apart with |y1 - y2| <= 3 m: the slack brings them in"},
         [](std::size_t, TargetKind) { return infeasible_start(); }},
        {{"formation-equality", "both robots track a midpoint target with the offset y1 - y2 = d(t), |d| = 1 m"},
         [](std::size_t, TargetKind) { return formation_equality(); }},
    };
    return entries;
}
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

const std::vector<ScenarioInfo>& scenario_catalog()
{
    static const std::vector<ScenarioInfo> infos = [] {
        std::vector<ScenarioInfo> out;
        for (const CatalogEntry& e : catalog()) {
            out.push_back(e.info);
        }
        return out;
    }();
    return infos;
}

bool scenario_exists(const std::string& name)
{
    for (const CatalogEntry& e : catalog()) {
        if (name == e.info.name) {
            return true;
        }
    }
    return false;
}

Scenario make_scenario(const std::string& name, std::size_t robots, TargetKind kind)
{
    for (const CatalogEntry& e : catalog()) {
        if (name == e.info.name) {
            Scenario s = e.make(robots, kind);
            s.streamed = (kind == TargetKind::Streamed);
            return s;
        }
    }
    throw std::invalid_argument("unknown scenario '" + name + "'");
}

Scenario make_demo_scenario(std::size_t robot_count, TargetKind kind)
{
    if (robot_count < 1 || robot_count > kMaxRobots) {
        throw std::invalid_argument("robot count must be 1..4");
    }
    Scenario scenario;
    scenario.name = "demo";
    scenario.duration_s = 20.0;
    scenario.streamed = (kind == TargetKind::Streamed);
    scenario.robot_count = robot_count;
    const Eigen::Vector2d semi_axis_m = kind == TargetKind::Circle ? Eigen::Vector2d(2.0, 2.0)
                                                                   : Eigen::Vector2d(3.0, 1.5);
    for (std::size_t r = 0; r < robot_count; ++r) {
        const double turn_rad = 2.0 * kPi * static_cast<double>(r) / static_cast<double>(robot_count);
        EllipseTarget target;
        target.center_m = Eigen::Vector2d::Zero();
        target.semi_axis_m = semi_axis_m;
        target.omega_radps = 2.0 * kPi / 10.0;
        target.phase_rad = turn_rad;
        target.rotation_rad = 0.0;
        scenario.targets[r] = kind == TargetKind::Circle
                                  ? TargetPath::circle(target.center_m, semi_axis_m.x(), target.omega_radps, turn_rad)
                                  : TargetPath::ellipse(target);
        UnicycleState& start = scenario.starts[r];
        start.position_m = Eigen::Rotation2Dd(turn_rad) * Eigen::Vector2d(-1.0, -2.0);
        start.heading_rad = turn_rad;
        scenario.weights[r] = Eigen::Vector2d(1.0, 1.0);
    }
    return scenario;
}

}  // namespace tvo_host
