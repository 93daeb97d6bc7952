// tvo_scenario_export: the session tvo_sim would START for a scenario, solved (a `through` target's
// polynomial coefficients, the barrier with the firmware's defaults filled in), as JSON on stdout,
// with the robots' start poses. Takes tvo_sim's own options (the same parser, the same scenario
// files and checks), so what it prints is what the firmware node would receive on the wire.
//
// The `tvo` Python module reads it (tvo.load_scenario) to build the same problem in Python and to
// export it as a C initialiser a firmware compiles (tvo.export_c): the waypoint solve stays in one
// place (host/src/target_path.cpp).
//
// Exit codes: 0 printed; 2 bad options or scenario file (tvo_sim's message); 1 another error.
#include <cstdint>
#include <exception>
#include <iostream>
#include <string>

#include <nlohmann/json.hpp>

#include "options.hpp"
#include "scenario.hpp"
#include "scenario_file.hpp"
#include "session.hpp"

namespace {

using nlohmann::json;

json path_json(const tvo_lcm::path_t& p)
{
    switch (p.kind) {
    case tvo_lcm::path_t::KIND_POLYNOMIAL: {
        json coeff = json::array();
        for (const auto& axis : p.coeff) {
            coeff.push_back(json(std::vector<double>(std::begin(axis), std::end(axis))));
        }
        return {{"kind", "polynomial"}, {"coeff", coeff}};
    }
    case tvo_lcm::path_t::KIND_CIRCLE:
        return {{"kind", "circle"},
                {"center_m", {p.center_m[0], p.center_m[1]}},
                {"radius_m", p.semi_axis_m[0]},
                {"omega_radps", p.omega_radps},
                {"phase_rad", p.phase_rad}};
    case tvo_lcm::path_t::KIND_ELLIPSE:
        return {{"kind", "ellipse"},
                {"center_m", {p.center_m[0], p.center_m[1]}},
                {"semi_axis_m", {p.semi_axis_m[0], p.semi_axis_m[1]}},
                {"omega_radps", p.omega_radps},
                {"phase_rad", p.phase_rad},
                {"rotation_rad", p.rotation_rad}};
    default:
        return {{"kind", "streamed"}};
    }
}

json session_json(const tvo_lcm::session_t& s, const tvo_host::Scenario& scenario, const tvo_host::SimOptions& o)
{
    json robots = json::array();
    for (std::int32_t r = 0; r < s.robot_count; ++r) {
        const tvo_host::UnicycleState& start = scenario.starts[static_cast<std::size_t>(r)];
        robots.push_back({{"target", path_json(s.robot[r].target)},
                          {"tracking_weight", {s.robot[r].tracking_weight[0], s.robot[r].tracking_weight[1]}},
                          {"initial_speed_mps", s.robot[r].initial_speed_mps},
                          {"start", {start.position_m.x(), start.position_m.y(), start.heading_rad}}});
    }
    const tvo_lcm::barrier_t& b = s.barrier;
    json distances = json::array();
    for (std::int32_t i = 0; i < s.distance_count; ++i) {
        const tvo_lcm::distance_bound_t& d = s.distance[i];
        distances.push_back({{"robot_a", d.robot_a}, {"robot_b", d.robot_b}, {"min_m", d.min_m},
                             {"min_rate_mps", d.min_rate_mps}, {"max_m", d.max_m}, {"max_rate_mps", d.max_rate_mps}});
    }
    json halfspaces = json::array();
    for (std::int32_t i = 0; i < s.halfspace_count; ++i) {
        const tvo_lcm::halfspace_t& h = s.halfspace[i];
        halfspaces.push_back({{"robot", h.robot},
                              {"normal", {h.normal[0], h.normal[1]}},
                              {"normal_rate", {h.normal_rate[0], h.normal_rate[1]}},
                              {"bound_m", h.bound_m},
                              {"bound_rate_mps", h.bound_rate_mps}});
    }
    json obstacles = json::array();
    for (std::int32_t i = 0; i < s.obstacle_count; ++i) {
        obstacles.push_back({{"center_m", {s.obstacle[i].center_m[0], s.obstacle[i].center_m[1]}},
                             {"radius_m", s.obstacle[i].radius_m}});
    }
    json offsets = json::array();
    for (std::int32_t i = 0; i < s.offset_count; ++i) {
        offsets.push_back({{"robot_a", s.offset[i].robot_a}, {"robot_b", s.offset[i].robot_b},
                           {"offset", path_json(s.offset[i].offset)}});
    }
    return {
        {"name", scenario.name},
        {"duration_s", static_cast<double>(o.steps * o.period_us) * 1e-6},
        {"controller",
         {{"period_us", s.period_us},
          {"delay_us", s.delay_us},
          {"delay_compensation", s.delay_compensation},
          {"zoh_aware", s.zoh_aware},
          {"watchdog_periods", s.watchdog_periods},
          {"velocity_source", s.velocity_source == tvo_lcm::session_t::VELOCITY_FROM_POSITION ? "position" : "pose"},
          {"filter_tf_s", s.filter_tf_s},
          {"gain_kp", s.gain_kp},
          {"gain_kd", s.gain_kd},
          {"omega_max_radps", s.omega_max_radps},
          {"accel_max_mps2", s.accel_max_mps2},
          {"speed_max_mps", s.speed_max_mps},
          {"min_speed_mps", s.min_speed_mps}}},
        {"problem",
         {{"robots", robots},
          {"barrier",
           {{"c0", b.c0},
            {"alpha_c_per_s", b.alpha_c_per_s},
            {"c_max", b.c_max},
            {"delta0", b.delta0},
            {"alpha_s_per_s", b.alpha_s_per_s},
            {"slack_margin", b.slack_margin},
            {"relaxation_degree", b.relaxation_degree}}},
          {"distance_bounds", distances},
          {"halfspaces", halfspaces},
          {"robot_radius_m", s.robot_radius_m},
          {"obstacles", obstacles},
          {"offsets", offsets}}},
    };
}

}  // namespace

int main(int argc, char** argv)
{
    try {
        tvo_host::SimOptions options;
        const int parsed = tvo_host::parse_options(argc, argv, &options);
        if (parsed >= 0) {
            return parsed;  // --help, --list-scenarios, a bad option (exit 2, message printed)
        }
        // tvo_sim's check of the run's duration against the file's last waypoints (exit 2).
        try {
            const tvo_host::ScenarioFile file = tvo_host::load_scenario_file(tvo_host::scenario_path(options.scenario));
            const double duration_s = static_cast<double>(options.steps * options.period_us) * 1e-6;
            tvo_host::check_run_duration(file, duration_s, "--duration-s");
        } catch (const tvo_host::ScenarioFileError& e) {
            std::cerr << "tvo_scenario_export: error: " << e.what() << '\n';
            return 2;
        }
        tvo_host::Scenario scenario = tvo_host::make_scenario(options.scenario, options.robots, options.target);
        scenario.barrier.apply(options.barrier);
        // No node here: the problem and the timing are what is exported, not the boots a START names.
        const tvo_lcm::session_t start = tvo_host::make_start_session(options, scenario, 1, 0, 0, tvo_host::NodeBoots{});
        std::cout << session_json(start, scenario, options).dump(1) << '\n';
        return 0;
    } catch (const std::exception& e) {
        std::cerr << "tvo_scenario_export: error: " << e.what() << '\n';
        return 1;
    }
}
