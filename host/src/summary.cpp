// Summary table and JSON; see summary.hpp.
#include "summary.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "metrics.hpp"

namespace tvo_host {

namespace {
void line(std::ostream& out, const char* label, const std::string& value)
{
    out << "  " << std::left << std::setw(30) << label << value << '\n';
}

std::string sci(double value, const char* unit)
{
    std::ostringstream s;
    if (std::isfinite(value)) {
        s << std::scientific << std::setprecision(3) << value << ' ' << unit;
    } else {
        s << "never (still violated at the end)";
    }
    return s.str();
}

void optional_line(std::ostream& out, const char* label, const std::optional<double>& value, const char* unit)
{
    if (value) {
        line(out, label, sci(*value, unit));
    }
}

std::string window_text()
{
    std::ostringstream s;
    s << kRmsWindowS;
    return s.str();
}

nlohmann::json number_or_null(double value)
{
    return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr);
}

void write_json_file(const std::string& path, const nlohmann::json& json)
{
    std::ofstream file(path);
    file << json.dump(2) << '\n';
    if (!file) {
        throw std::runtime_error("cannot write " + path);
    }
}
}  // namespace

void NodeCounterSums::add(const tvo_lcm::node_counters_t& c)
{
    const auto count = [](std::int32_t n) { return static_cast<std::uint64_t>(std::max<std::int32_t>(n, 0)); };
    accepted += count(c.accepted);
    for (std::size_t s = 0; s < refused_by_status.size(); ++s) {
        refused_by_status[s] += count(c.refused[s]);
        refused += count(c.refused[s]);
    }
    malformed += count(c.malformed);
    unauthenticated += count(c.unauthenticated);
    replayed += count(c.replayed);
    wrong_boot += count(c.wrong_boot);
    idle += count(c.idle);
    other_session += count(c.other_session);
    predicted += count(c.predicted);
    safe_stops += count(c.safe_stops);
    targets_refused += count(c.targets_refused);
    speed_mismatch += count(c.speed_mismatch);
    sessions += count(c.sessions);
}

void print_summary_table(std::ostream& out, const RunSummary& s, const SimOptions& o)
{
    std::ostringstream mode;
    mode << o.scenario << ", " << (o.realtime ? "realtime" : "lockstep") << ", h = " << o.period_us << " us, tau = " << o.delay_us
         << " us, compensation " << (o.delay_compensation ? "on" : "off") << (o.zoh_aware ? ", ZOH-aware" : "")
         << ", "
         << (o.position_only ? "position only" : "pose measured") << ", sigma = " << o.sigma << ", "
         << (o.target == TargetKind::Streamed ? "streamed targets" : "on-board targets");
    out << "tvo_sim summary (" << mode.str() << ")\n";
    line(out, "final tracking error", sci(s.final_error_m, "m"));
    const std::string rms_label =
        s.rms_whole_run ? std::string("RMS tracking error, whole run") : "RMS tracking error, last " + window_text() + " s";
    line(out, rms_label.c_str(), sci(s.rms_error_last5s_m, "m"));
    line(out, "max |omega|", sci(s.max_abs_omega_radps, "rad/s"));
    line(out, "steps", std::to_string(s.steps));
    std::ostringstream rate;
    rate << std::fixed << std::setprecision(0) << s.steps_per_s << " /s (wall clock)";
    line(out, "steps per second", rate.str());
    line(out, "faults", std::to_string(s.faults) + " of " + std::to_string(s.commands) + " commands");
    line(out, "measurements dropped", std::to_string(s.drops));
    line(out, "late commands", std::to_string(s.late_commands));
    if (o.on_missing_answer == MissingAnswer::Hold) {
        line(out, "lost answers", std::to_string(s.lost_answers) + " (+ " + std::to_string(s.lost_telemetry) +
                                      " telemetry only)");
    }
    if (o.has_link_loss()) {
        line(out, "lost to the link outage", std::to_string(s.link_lost_measurements) + " measurements");
    }
    line(out, "safe stops applied", std::to_string(s.safe_stop_commands));
    optional_line(out, "first safe stop after loss", s.first_safe_stop_after_loss_s, "s");
    line(out, "commands ignored", std::to_string(s.ignored_commands) + " (+ " +
                                      std::to_string(s.other_session_commands) + " for other sessions)");
    line(out, "session restarts", std::to_string(s.session_restarts));
    if (s.node_counters) {
        const NodeCounterSums& c = *s.node_counters;
        line(out, "node: accepted / refused", std::to_string(c.accepted) + " / " + std::to_string(c.refused) +
                                                  " periods, " + std::to_string(c.safe_stops) + " safe stops");
        if (c.malformed + c.unauthenticated + c.replayed + c.wrong_boot + c.idle + c.other_session > 0) {
            line(out, "node: dropped", std::to_string(c.malformed) + " malformed, " + std::to_string(c.unauthenticated) +
                                           " unauthenticated, " + std::to_string(c.replayed) + " replayed, " +
                                           std::to_string(c.wrong_boot) + " for another boot, " +
                                           std::to_string(c.idle) + " while idle, " + std::to_string(c.other_session) +
                                           " of another session");
        }
    }
    if (s.collisions) {
        line(out, "collisions", std::to_string(*s.collisions));
    }
    optional_line(out, "min clearance", s.min_clearance_m, "m");
    optional_line(out, "min inter-robot distance", s.min_distance_m, "m");
    optional_line(out, "  while the targets cross", s.min_distance_crossing_m, "m");
    optional_line(out, "final inter-robot distance", s.final_distance_m, "m");
    optional_line(out, "max violation (relative)", s.max_violation_frac, "");
    optional_line(out, "  of a minimum distance", s.max_violation_min_bound_frac, "");
    optional_line(out, "  of a maximum distance", s.max_violation_max_bound_frac, "");
    optional_line(out, "violation at the start", s.initial_violation_frac, "");
    optional_line(out, "time to feasibility", s.time_to_feasible_s, "s");
    optional_line(out, "equality residual (t >= 5 s)", s.equality_residual_m, "m");
    if (s.regularized_steps) {
        line(out, "regularised solves", std::to_string(*s.regularized_steps) + " of " + std::to_string(s.commands) +
                                            " commands");
    }
}

void write_summary_json(const std::string& path, const RunSummary& s)
{
    nlohmann::json json = {
        {"final_error_m", s.final_error_m},
        {"rms_error_last5s_m", s.rms_error_last5s_m},
        {"rms_error_whole_run", s.rms_whole_run},
        {"max_abs_omega_radps", s.max_abs_omega_radps},
        {"steps", s.steps},
        {"steps_per_s", s.steps_per_s},
        {"faults", s.faults},
        {"commands", s.commands},
        {"drops", s.drops},
        {"late_commands", s.late_commands},
        {"lost_answers", s.lost_answers},
        {"lost_telemetry", s.lost_telemetry},
        {"link_lost_measurements", s.link_lost_measurements},
        {"ignored_commands", s.ignored_commands},
        {"other_session_commands", s.other_session_commands},
        {"session_restarts", s.session_restarts},
        {"safe_stop_commands", s.safe_stop_commands},
    };
    const auto put = [&json](const char* key, const std::optional<double>& value) {
        if (value) {
            json[key] = number_or_null(*value);
        }
    };
    const auto put_count = [&json](const char* key, const std::optional<std::uint64_t>& value) {
        if (value) {
            json[key] = *value;
        }
    };
    put("first_safe_stop_after_loss_s", s.first_safe_stop_after_loss_s);
    if (s.node_counters) {
        const NodeCounterSums& c = *s.node_counters;
        json["node_accepted"] = c.accepted;
        json["node_refused"] = c.refused;
        json["node_safe_stops"] = c.safe_stops;
        nlohmann::json by_status = nlohmann::json::object();
        for (std::size_t status = 0; status < c.refused_by_status.size(); ++status) {
            if (c.refused_by_status[status] > 0) {
                by_status[std::to_string(status)] = c.refused_by_status[status];
            }
        }
        json["node_counters"] = {{"accepted", c.accepted},
                                 {"refused", by_status},
                                 {"malformed", c.malformed},
                                 {"unauthenticated", c.unauthenticated},
                                 {"replayed", c.replayed},
                                 {"wrong_boot", c.wrong_boot},
                                 {"idle", c.idle},
                                 {"other_session", c.other_session},
                                 {"predicted", c.predicted},
                                 {"safe_stops", c.safe_stops},
                                 {"targets_refused", c.targets_refused},
                                 {"speed_mismatch", c.speed_mismatch},
                                 {"sessions", c.sessions}};
    }
    put_count("collisions", s.collisions);
    put("min_clearance_m", s.min_clearance_m);
    put("min_distance_m", s.min_distance_m);
    put("min_distance_crossing_m", s.min_distance_crossing_m);
    put("final_distance_m", s.final_distance_m);
    put("max_violation_frac", s.max_violation_frac);
    put("max_violation_min_bound_frac", s.max_violation_min_bound_frac);
    put("max_violation_max_bound_frac", s.max_violation_max_bound_frac);
    put("initial_violation_frac", s.initial_violation_frac);
    put("time_to_feasible_s", s.time_to_feasible_s);
    put("equality_residual_m", s.equality_residual_m);
    put_count("regularized_steps", s.regularized_steps);
    write_json_file(path, json);
}

void write_scenario_json(const std::string& path, const Scenario& sc, double duration_s)
{
    nlohmann::json obstacles = nlohmann::json::array();
    for (const Disk& o : sc.obstacles) {
        obstacles.push_back({{"center_m", {o.center_m.x(), o.center_m.y()}}, {"radius_m", o.radius_m}});
    }
    nlohmann::json distances = nlohmann::json::array();
    for (const DistanceBound& d : sc.distances) {
        distances.push_back({{"robot_a", d.robot_a},
                             {"robot_b", d.robot_b},
                             {"min_m", d.min_m},
                             {"min_rate_mps", d.min_rate_mps},
                             {"max_m", d.max_m},
                             {"max_rate_mps", d.max_rate_mps}});
    }
    nlohmann::json halfspaces = nlohmann::json::array();
    for (const HalfSpace& h : sc.halfspaces) {
        halfspaces.push_back({{"robot", h.robot},
                              {"normal", {h.normal.x(), h.normal.y()}},
                              {"normal_rate", {h.normal_rate.x(), h.normal_rate.y()}},
                              {"bound_m", h.bound_m},
                              {"bound_rate_mps", h.bound_rate_mps}});
    }
    nlohmann::json offsets = nlohmann::json::array();
    for (const OffsetEquality& e : sc.offsets) {
        offsets.push_back({{"robot_a", e.robot_a}, {"robot_b", e.robot_b}});
    }
    nlohmann::json json = {
        {"name", sc.name},
        {"duration_s", duration_s},
        {"robot_count", sc.robot_count},
        {"robot_radius_m", sc.robot_radius_m},
        {"obstacles", obstacles},
        {"distance_bounds", distances},
        {"halfspaces", halfspaces},
        {"offsets", offsets},
        {"settle_time_s", sc.settle_time_s},
    };
    if (sc.crossing_window) {
        json["crossing_window_s"] = {sc.crossing_window->start_s, sc.crossing_window->end_s};
    }
    write_json_file(path, json);
}

}  // namespace tvo_host
