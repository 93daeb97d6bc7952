// Scenarios as YAML files (README.md, "Your own scenario", documents the format). The built-in runs
// are the files in host/scenarios/ (one source of truth: no C++ copy); a user's file is read the
// same way. Parsing fills the Scenario the simulator runs (scenario.hpp), so the run does not care
// where it came from, plus the run settings (timing, sensing, controller, faults) that the command
// line may override. Any error is a ScenarioFileError "FILE:LINE:COLUMN: FIELD: why".
#pragma once

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "scenario.hpp"

namespace tvo_host {

/// tvo_sim settings a file may give for its scenario; unset: tvo_sim's default. The command-line
/// option of the same name (--period-s for period_s, ...) overrides each.
struct RunSettings {
    std::optional<double> period_s;
    std::optional<double> delay_s;
    std::optional<bool> compensation;
    std::optional<bool> zoh_aware;
    std::optional<double> sigma;
    std::optional<bool> position_only;
    std::optional<double> filter_tf_s;
    std::optional<std::uint64_t> seed;
    std::optional<std::pair<double, double>> gains;  // KP, KD
    std::optional<double> omega_max_radps;
    std::optional<double> accel_max_mps2;
    std::optional<double> speed_max_mps;
    std::optional<double> min_speed_mps;
    std::optional<std::int32_t> watchdog_periods;
    std::optional<double> drop_prob;
    std::optional<double> extra_delay_s;
    std::optional<std::pair<double, double>> disturbance;  // speed sigma (m/s), turn-rate sigma (rad/s)
    std::optional<std::pair<double, double>> link_loss;    // start (s), duration (s)
};

/// What --robots N and --target circle do to a scenario (the demo's); a file without them refuses both.
struct ScenarioVariants {
    bool robots_turned{false};              // N copies of the one robot, copy r turned by 2 pi r / N
    std::optional<double> circle_radius_m;  // each ellipse target becomes a circle of this radius
};

/// A file larger than this is refused before it is read (a scenario of 4 robots with 8 waypoints each,
/// 8 obstacles and every section is a few kB; a 43 MB file took yaml-cpp 3.3 GB and 42 s to parse).
constexpr std::uintmax_t kMaxScenarioFileBytes = 1048576;  // 1 MiB

/// The last waypoint of a `through` time function: its polynomial is not held after it (the firmware
/// evaluates the same polynomial on board), so a run must end by t_s.
struct WaypointEnd {
    std::string field;  // robots[0].target.through[2].t_s
    std::string where;  // FILE:LINE:COLUMN of that t_s
    double t_s{0.0};
};

struct ScenarioFile {
    std::string path;
    std::string description;
    Scenario scenario;  // as written (one copy of each robot, targets as given)
    ScenarioVariants variants;
    RunSettings run;
    std::vector<WaypointEnd> waypoint_ends;  // one per `through` (targets and offsets)
};

class ScenarioFileError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Reads and checks a scenario file; its scenario is named after the file (obstacles.yaml: obstacles).
/// Throws ScenarioFileError naming the file, line, column and field of the first problem.
ScenarioFile load_scenario_file(const std::string& path);

/// Throws ScenarioFileError naming the waypoint's FILE:LINE:COLUMN if a run of duration_s (the file's,
/// the default or --duration-s) ends after the last waypoint of one of the file's `through` functions.
void check_run_duration(const ScenarioFile& file, double duration_s, const std::string& duration_source);

/// The folder of the built-in scenarios: $TVO_SCENARIO_DIR if set, else host/scenarios of this tree.
std::string scenario_folder();

/// A path (it holds a '/' or ends in .yaml / .yml) as it is; a name: <scenario_folder()>/NAME.yaml.
std::string scenario_path(const std::string& name_or_path);

/// The .yaml files of scenario_folder(), sorted by name.
std::vector<std::string> scenario_folder_files();

/// The .yaml files one folder down (host/scenarios/fleet/*.yaml: scenarios that are not built-ins,
/// run by their path), sorted by path.
std::vector<std::string> scenario_subfolder_files();

/// The scenario to run: robots > 1 needs variants.robots_turned, kind Circle variants.circle_radius_m
/// (ScenarioFileError otherwise); kind Streamed streams the targets of any scenario.
Scenario instantiate_scenario(const ScenarioFile& file, std::size_t robots, TargetKind kind);

}  // namespace tvo_host
