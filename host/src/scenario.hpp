// What the robots should do, as data: start poses, targets, tracking weights, and the constraints
// of the problem the firmware solves (distance bounds, half-spaces, disk obstacles, formation
// offsets, barrier settings). The session message is filled from it (session.cpp) and the metrics
// judge the run against it (constraint_metrics.cpp), so a scenario is written down exactly once.
//
// The scenarios are YAML files (host/scenarios/*.yaml, or a user's; scenario_file.hpp reads them):
//   demo, formation-max, formation-bilateral, obstacles, obstacles-infeasible-target,
//   infeasible-start, formation-equality (tools/scenario --list prints each file's description).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "plant.hpp"
#include "target_path.hpp"

namespace tvo_host {

/// How the firmware learns the demo's target: on-board analytic (ellipse, circle) or streamed by the host.
enum class TargetKind { Ellipse, Circle, Streamed };

/// Parses "ellipse" | "circle" | "streamed"; false if unknown.
bool parse_target_kind(const std::string& text, TargetKind* kind);
const char* target_kind_name(TargetKind kind);

/// Barrier settings a scenario (or the command line) changes; the rest are the firmware's
/// tvo_barrier_config_default (c0 = 1, alpha_c = 1/s, c_max = 1e4, delta0 = 0.05, alpha_s = 1/s,
/// epsilon_s = 0.1, m_r = 4).
struct BarrierOverrides {
    std::optional<double> c0;
    std::optional<double> alpha_c_per_s;
    std::optional<double> c_max;
    std::optional<double> delta0;
    std::optional<double> alpha_s_per_s;
    std::optional<double> slack_margin;
    std::optional<int> relaxation_degree;

    /// Fields set in `other` replace this one's.
    void apply(const BarrierOverrides& other);
};

/// d_min(t) <= |y_a - y_b| <= d_max(t), d(t) = d0 + rate t; a zero d0 means no such bound.
struct DistanceBound {
    std::size_t robot_a{0};
    std::size_t robot_b{1};
    double min_m{0.0};
    double min_rate_mps{0.0};
    double max_m{0.0};
    double max_rate_mps{0.0};

    double min_at(double t_s) const { return min_m + min_rate_mps * t_s; }
    double max_at(double t_s) const { return max_m + max_rate_mps * t_s; }
};

/// a(t)^T y_robot <= b(t), a(t) = normal + normal_rate t, b(t) = bound + bound_rate t.
struct HalfSpace {
    std::size_t robot{0};
    Eigen::Vector2d normal{Eigen::Vector2d::UnitX()};
    Eigen::Vector2d normal_rate{Eigen::Vector2d::Zero()};
    double bound_m{0.0};
    double bound_rate_mps{0.0};
};

struct Disk {
    Eigen::Vector2d center_m{Eigen::Vector2d::Zero()};
    double radius_m{0.0};
};

/// y_a - y_b = d(t).
struct OffsetEquality {
    std::size_t robot_a{0};
    std::size_t robot_b{1};
    TargetPath offset;
};

struct TimeWindow {
    double start_s{0.0};
    double end_s{0.0};
};

struct Scenario {
    std::string name{"demo"};
    double duration_s{20.0};          // T when --duration-s is not given
    bool streamed{false};             // targets streamed on TVO_TARGET instead of evaluated on board
    std::size_t robot_count{1};
    std::array<TargetPath, kMaxRobots> targets{};
    std::array<UnicycleState, kMaxRobots> starts{};
    std::array<Eigen::Vector2d, kMaxRobots> weights{};  // diagonal of each tracking term's W

    BarrierOverrides barrier;
    std::vector<DistanceBound> distances;
    std::vector<HalfSpace> halfspaces;
    double robot_radius_m{0.0};       // disk robots: obstacle clearance and robot-robot contact
    std::vector<Disk> obstacles;
    std::vector<OffsetEquality> offsets;

    std::optional<TimeWindow> crossing_window;  // min inter-robot distance is also reported inside it
    double settle_time_s{5.0};                  // the equality residual counts from here on

    bool has_inequalities() const { return !distances.empty() || !halfspaces.empty() || !obstacles.empty(); }

    /// Per robot, what its tracking error is measured against at t_s: its target, or with formation
    /// offsets the minimiser of sum_r 1/2 |y_r - y_d,r|_W^2 subject to the offsets (a KKT solve).
    std::array<Eigen::Vector2d, kMaxRobots> references(double t_s) const;

    /// The robot pair whose distance the summary reports: the first distance bound's, else the first
    /// offset's, else none.
    std::optional<std::array<std::size_t, 2>> reported_pair() const;
};

/// Defined in scenario_file.cpp (tvo_sim_lib), from the files:

/// True if name_or_path names a scenario file (scenario_path(): a path, or NAME in the scenario folder).
bool scenario_exists(const std::string& name_or_path);

/// The scenario of a name or file (ScenarioFileError if it cannot be read or is malformed). robots and kind
/// apply the file's variants (the demo's); kind == Streamed streams any scenario's targets.
Scenario make_scenario(const std::string& name_or_path, std::size_t robots, TargetKind kind);

/// The demo (host/scenarios/demo.yaml): an ellipse centre (0, 0), semi-axes (3, 1.5), period 10 s;
/// robot 0 starts at (-1, -2) heading 0 at rest. Further robots are the same picture turned by 2 pi r / N.
/// A circle scenario uses radius 2 with the same rate.
Scenario make_demo_scenario(std::size_t robot_count, TargetKind kind);

}  // namespace tvo_host
