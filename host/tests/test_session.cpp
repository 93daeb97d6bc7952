// Checks of the session START built from the scenarios (every field of the nested types, the clock
// source, the protocol, each robot's node boot, the telemetry rate) and of the rejection message. Plain asserts (no framework): exit code 0 = pass.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "options.hpp"
#include "scenario.hpp"
#include "session.hpp"

extern "C" {
#include "tvo/barrier.h"
}

namespace {

int g_failures = 0;

void check(bool ok, const char* what)
{
    std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    g_failures += ok ? 0 : 1;
}

using tvo_host::Scenario;
using tvo_host::SimOptions;
using tvo_host::TargetKind;

tvo_lcm::session_t start_of(const Scenario& scenario, const SimOptions& options)
{
    tvo_host::NodeBoots boots{};
    for (std::size_t r = 0; r < tvo_host::kMaxRobots; ++r) {
        boots[r] = 500 + static_cast<std::int64_t>(r);
    }
    return tvo_host::make_start_session(options, scenario, 77, 1000123, 1300123, boots);
}

void test_demo_ellipse()
{
    SimOptions options;
    const Scenario demo = tvo_host::make_demo_scenario(2, TargetKind::Ellipse);
    const tvo_lcm::session_t msg = start_of(demo, options);
    check(msg.action == tvo_lcm::session_t::ACTION_START && msg.session_id == 77, "START with the session id");
    check(msg.protocol_version == tvo_lcm::node_status_t::PROTOCOL_VERSION, "the protocol version of this wire");
    check(msg.node_boot_id[0] == 500 && msg.node_boot_id[1] == 501 && msg.node_boot_id[2] == 0,
          "each robot's node boot, none past the robots");
    check(msg.telemetry_every == 0, "telemetry at the node's default rate unless asked");
    check(msg.utime == 1000123 && msg.epoch_utime == 1300123, "utime and epoch as given");
    check(msg.clock_source == tvo_lcm::session_t::CLOCK_PLANT, "lockstep: CLOCK_PLANT");
    check(msg.period_us == options.period_us && msg.delay_us == options.delay_us &&
              msg.watchdog_periods == options.watchdog_periods,
          "timing from the options");
    check(msg.robot_count == 2, "two robots");
    bool paths_ok = true;
    for (int r = 0; r < 2; ++r) {
        const tvo_lcm::path_t& path = msg.robot[r].target;
        const tvo_host::EllipseTarget& e = demo.targets[static_cast<std::size_t>(r)].ellipse_params();
        paths_ok = paths_ok && path.kind == tvo_lcm::path_t::KIND_ELLIPSE && path.semi_axis_m[0] == 3.0 &&
                   path.semi_axis_m[1] == 1.5 && path.omega_radps == e.omega_radps &&
                   path.phase_rad == e.phase_rad && path.rotation_rad == e.rotation_rad &&
                   msg.robot[r].initial_speed_mps == 0.0 &&
                   msg.robot[r].tracking_weight[0] == demo.weights[static_cast<std::size_t>(r)].x();
    }
    check(paths_ok, "each robot's ellipse, start speed and weights in robot[r]");
    check(msg.robot[2].target.kind == 0 && msg.robot[2].tracking_weight[0] == 0.0, "entries past the count are zero");

    options.realtime = true;
    check(start_of(demo, options).clock_source == tvo_lcm::session_t::CLOCK_NODE, "realtime: CLOCK_NODE");
}

void test_circle_and_streamed()
{
    const tvo_lcm::session_t circle = start_of(tvo_host::make_demo_scenario(1, TargetKind::Circle), SimOptions{});
    check(circle.robot[0].target.kind == tvo_lcm::path_t::KIND_CIRCLE && circle.robot[0].target.semi_axis_m[0] == 2.0,
          "circle: kind and radius in semi_axis_m[0]");
    const tvo_lcm::session_t streamed =
        start_of(tvo_host::make_scenario("formation-max", 1, TargetKind::Streamed), SimOptions{});
    check(streamed.robot_count == 2 && streamed.robot[0].target.kind == tvo_lcm::path_t::KIND_STREAMED &&
              streamed.robot[1].target.kind == tvo_lcm::path_t::KIND_STREAMED,
          "streamed: every robot's target KIND_STREAMED");
}

void test_constraints()
{
    const Scenario bilateral = tvo_host::make_scenario("formation-bilateral", 1, TargetKind::Ellipse);
    const tvo_lcm::session_t msg = start_of(bilateral, SimOptions{});
    const tvo_host::DistanceBound& d = bilateral.distances.at(0);
    check(msg.distance_count == 1 && msg.distance[0].robot_a == static_cast<std::int32_t>(d.robot_a) &&
              msg.distance[0].robot_b == static_cast<std::int32_t>(d.robot_b) && msg.distance[0].min_m == d.min_m &&
              msg.distance[0].max_m == d.max_m && msg.distance[0].max_rate_mps == d.max_rate_mps,
          "distance bound in distance[0]");
    const bool polynomial = bilateral.targets[0].kind() == tvo_host::PathKind::Polynomial;
    check(polynomial && msg.robot[0].target.kind == tvo_lcm::path_t::KIND_POLYNOMIAL &&
              msg.robot[1].target.coeff[1][3] == bilateral.targets[1].coefficients()[1][3],
          "polynomial target: coefficients per axis");
    tvo_barrier_config_t defaults{};
    tvo_barrier_config_default(&defaults);
    check(msg.barrier.relaxation_degree == bilateral.barrier.relaxation_degree.value_or(defaults.relaxation_degree) &&
              msg.barrier.c_max == bilateral.barrier.c_max.value_or(static_cast<double>(defaults.c_max)),
          "barrier: the scenario's settings over the firmware's defaults");

    const Scenario obstacles = tvo_host::make_scenario("obstacles", 1, TargetKind::Ellipse);
    const tvo_lcm::session_t obs = start_of(obstacles, SimOptions{});
    bool centers_ok = obs.obstacle_count == static_cast<std::int32_t>(obstacles.obstacles.size()) &&
                      obs.robot_radius_m == obstacles.robot_radius_m && !obstacles.obstacles.empty();
    for (std::size_t i = 0; centers_ok && i < obstacles.obstacles.size(); ++i) {
        centers_ok = obs.obstacle[i].center_m[0] == obstacles.obstacles[i].center_m.x() &&
                     obs.obstacle[i].center_m[1] == obstacles.obstacles[i].center_m.y() &&
                     obs.obstacle[i].radius_m == obstacles.obstacles[i].radius_m;
    }
    check(centers_ok, "obstacles: centres, radii and the robot radius");

    const Scenario equality = tvo_host::make_scenario("formation-equality", 1, TargetKind::Ellipse);
    const tvo_lcm::session_t eq = start_of(equality, SimOptions{});
    const tvo_host::TargetPath& offset = equality.offsets.at(0).offset;
    const bool offset_poly = offset.kind() == tvo_host::PathKind::Polynomial;
    check(eq.offset_count == 1 && eq.offset[0].robot_a == 0 && eq.offset[0].robot_b == 1 &&
              (offset_poly ? eq.offset[0].offset.kind == tvo_lcm::path_t::KIND_POLYNOMIAL &&
                                 eq.offset[0].offset.coeff[0][1] == offset.coefficients()[0][1]
                           : eq.offset[0].offset.omega_radps == offset.ellipse_params().omega_radps),
          "formation offset d(t) in offset[0]");
}

void test_rejection_message()
{
    SimOptions options;
    options.scenario = "obstacles";
    tvo_lcm::session_ack_t ack{};
    ack.status = TVO_ERR_PARAM;
    ack.bad_param = TVO_PARAM_OBJECTIVE;
    ack.bad_part = tvo_lcm::session_ack_t::PART_OBSTACLES;
    ack.bad_index = 3;
    ack.own_robot = -1;
    const std::string text = tvo_host::describe_rejection(ack, options);
    std::printf("     %s\n", text.c_str());
    check(text.find("part of the problem: obstacles, entry 3") != std::string::npos &&
              text.find("node of robot") == std::string::npos,
          "rejection names the entry; the node of every robot needs no name");
    ack.own_robot = 2;
    check(tvo_host::describe_rejection(ack, options).find("at the node of robot 2") != std::string::npos,
          "a fleet node's refusal names its robot");
    ack.bad_part = tvo_lcm::session_ack_t::PART_NONE;
    ack.bad_index = -1;
    ack.bad_param = TVO_PARAM_GAINS;
    ack.own_robot = -1;
    const std::string gains = tvo_host::describe_rejection(ack, options);
    check(gains.find("--gains") != std::string::npos && gains.find("entry") == std::string::npos,
          "rejection of a parameter names its option, no entry");
}

}  // namespace

// The first session and a restart repeat START on one schedule: 100 ms after the first copy, then
// twice the last interval up to 800 ms; a reset starts a new handshake at once. Times are given, not
// slept, so the check does not depend on the machine's speed.
void test_start_repeats_back_off()
{
    using std::chrono::milliseconds;
    tvo_host::StartRepeats repeats;
    const auto t0 = tvo_host::StartRepeats::Clock::time_point{} + std::chrono::hours(1);
    check(repeats.due(t0) && repeats.next(t0) == t0, "the first START is due at once");
    auto now = t0;
    const long expected_ms[] = {100, 200, 400, 800, 800, 800};
    bool intervals_ok = true;
    for (const long interval : expected_ms) {
        repeats.sent(now);
        intervals_ok = intervals_ok && repeats.next(now) - now == milliseconds(interval) &&
                       !repeats.due(now + milliseconds(interval - 1)) && repeats.due(now + milliseconds(interval));
        now += milliseconds(interval);
    }
    check(intervals_ok, "START repeats after 100, 200, 400, 800, 800, 800 ms");
    repeats.reset();
    check(repeats.due(now) && repeats.next(now) == now, "after a reset the next START is due at once");
    repeats.sent(now);
    check(repeats.next(now) - now == milliseconds(100), "and the schedule starts again from 100 ms");
}

int main()
{
    test_start_repeats_back_off();
    test_demo_ellipse();
    test_circle_and_streamed();
    test_constraints();
    test_rejection_message();
    std::printf("%s\n", g_failures == 0 ? "all passed" : "FAILED");
    return g_failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
