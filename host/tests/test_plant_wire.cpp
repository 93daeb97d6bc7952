// Checks of the plant's messages on the wire (plant_wire.hpp, nodes.hpp): a period's sample as one
// unicycle_sample_t per robot, unicycle_command_t per robot joined into the joint command (up to the
// wire's 32 robots), the nodes' announcements into each robot's node boot (rule 1), and tvo_sim's
// duration limit from the wire's int32 sequence. Plain asserts (no framework): exit code 0 = pass.
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "nodes.hpp"
#include "options.hpp"
#include "plant_wire.hpp"
#include "session.hpp"

namespace {

int g_failures = 0;

void check(bool ok, const char* what)
{
    std::printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    g_failures += ok ? 0 : 1;
}

using tvo_host::CommandAssembler;
using tvo_host::JointCommand;
using tvo_host::JointMeasurement;
using tvo_host::kMaxRobots;
using tvo_host::NodeDirectory;

JointMeasurement sample_of(std::size_t robots)
{
    JointMeasurement m;
    m.utime = 1005000;
    m.session_id = 77;
    m.sequence = 3;
    m.robot_count = static_cast<std::int32_t>(robots);
    m.heading_valid = true;
    m.speed_valid = false;
    for (std::size_t r = 0; r < robots; ++r) {
        m.position_m[r] = {1.0 + static_cast<double>(r), -2.0 - static_cast<double>(r)};
        m.heading_rad[r] = 0.1 * static_cast<double>(r);
        m.speed_mps[r] = 0.5 + static_cast<double>(r);
    }
    return m;
}

void test_samples()
{
    const JointMeasurement m = sample_of(kMaxRobots);
    bool rows_ok = true;
    for (std::size_t r = 0; r < kMaxRobots; ++r) {
        tvo_lcm::unicycle_sample_t s{};
        tvo_host::to_wire(m, r, &s);
        rows_ok = rows_ok && s.header.utime == m.utime && s.header.session_id == 77 && s.header.sequence == 3 &&
                  s.header.robot == static_cast<std::int8_t>(r) && s.position_m[0] == m.position_m[r][0] &&
                  s.position_m[1] == m.position_m[r][1] && s.heading_rad == static_cast<float>(m.heading_rad[r]) &&
                  s.speed_mps == static_cast<float>(m.speed_mps[r]) &&
                  s.has == tvo_lcm::unicycle_sample_t::HAS_HEADING;
    }
    check(rows_ok, "per-robot samples: robot r's own pose, the period's stamp, 32 robots, HAS_HEADING only");

    // The plant's heading is unwrapped (continuous); the wire's is in [-pi, pi] (its float's best resolution).
    JointMeasurement turned = sample_of(1);
    turned.heading_rad[0] = -10.0;
    tvo_lcm::unicycle_sample_t s{};
    tvo_host::to_wire(turned, 0, &s);
    const double expected = -10.0 + 4.0 * M_PI;
    check(std::fabs(static_cast<double>(s.heading_rad) - expected) < 1e-6 && s.heading_rad <= static_cast<float>(M_PI) &&
              s.heading_rad >= static_cast<float>(-M_PI),
          "heading -10 rad goes out wrapped: -10 + 4 pi");
    turned.heading_valid = false;
    turned.speed_valid = true;
    tvo_host::to_wire(turned, 0, &s);
    check(s.has == tvo_lcm::unicycle_sample_t::HAS_SPEED, "has: HAS_SPEED only");
}

tvo_lcm::unicycle_command_t command_of(std::int8_t robot, std::int32_t sequence)
{
    tvo_lcm::unicycle_command_t c{};
    c.header.utime = 2000 + robot;
    c.header.session_id = 7;
    c.header.measurement_sequence = sequence;
    c.header.robot = robot;
    c.header.flags = static_cast<std::int16_t>(robot >= 0 && robot < 15 ? 1 << robot : 0);
    c.speed_mps = 0.125f * static_cast<float>(robot);
    c.turn_rate_radps = -0.25f * static_cast<float>(robot);
    return c;
}

void test_assembler()
{
    CommandAssembler commands(kMaxRobots);
    const auto n = static_cast<std::int8_t>(kMaxRobots);
    const JointCommand* joint = nullptr;
    bool early = false;
    for (int r = n - 1; r >= 0; --r) {  // any order
        joint = commands.add(command_of(static_cast<std::int8_t>(r), 5));
        early = early || (r > 0 && joint != nullptr);
    }
    check(!early && joint != nullptr, "32 robots: complete with the last robot's command, not before");
    bool values_ok = joint != nullptr && joint->robot_count == n && joint->measurement_sequence == 5 &&
                     joint->session_id == 7 && joint->status == 0 && joint->flags == 0x7fff && joint->utime == 2000 + n - 1;
    for (int r = 0; joint != nullptr && r < n; ++r) {
        values_ok = values_ok && joint->speed_mps[static_cast<std::size_t>(r)] == 0.125 * r &&
                    joint->turn_rate_radps[static_cast<std::size_t>(r)] == -0.25 * r;
    }
    check(values_ok, "each robot's command in its place; flags joined, the latest utime");

    // A period whose commands did not all come is replaced by the next one's.
    CommandAssembler three(3);
    three.add(command_of(0, 10));
    three.add(command_of(1, 10));
    check(three.add(command_of(0, 11)) == nullptr && three.add(command_of(2, 11)) == nullptr,
          "an incomplete period is dropped: the next period starts over");
    tvo_lcm::unicycle_command_t refused = command_of(1, 11);
    refused.header.status = 9;
    joint = three.add(refused);
    check(joint != nullptr && joint->measurement_sequence == 11 && joint->status == 9,
          "complete on the third command of sequence 11; status the refusing robot's");
    check(three.add(command_of(3, 12)) == nullptr && three.add(command_of(-1, 12)) == nullptr,
          "commands naming no robot of the run are dropped");
    three.add(command_of(0, 12));
    three.add(command_of(1, 12));
    tvo_lcm::unicycle_command_t other = command_of(2, 12);
    other.header.session_id = 8;
    check(three.add(other) == nullptr, "a command of another session does not complete this one");

    // The node's own safe stops all carry sequence -1: each period's set joins on its own.
    CommandAssembler two(2);
    check(two.add(command_of(0, -1)) == nullptr && two.add(command_of(1, -1)) != nullptr,
          "a period's safe stops of both robots join");
    check(two.add(command_of(0, -1)) == nullptr, "the next period's first safe stop does not complete at once");
}

tvo_lcm::node_status_t announcement(std::int8_t own_robot, std::int64_t boot, std::int64_t utime)
{
    tvo_lcm::node_status_t s{};
    s.utime = utime;
    s.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
    s.boot_id = boot;
    s.own_robot = own_robot;
    s.max_robots = 8;
    s.session_id = -1;
    return s;
}

void test_directory()
{
    using Clock = NodeDirectory::Clock;
    const Clock::time_point t0 = Clock::now();
    NodeDirectory every;
    check(!every.assignment(1), "no node heard: no assignment");
    every.heard(announcement(-1, 41, 10), t0);
    const auto boots = every.assignment(3);
    check(boots && (*boots)[0] == 41 && (*boots)[2] == 41 && (*boots)[3] == 0,
          "one node of every robot: its boot names robots 0 .. 2, none past them");
    every.heard(announcement(-1, 42, 5), t0 + std::chrono::milliseconds(10));
    check(every.assignment(1) && (*every.assignment(1))[0] == 42, "a new boot of the role takes it at once");
    every.heard(announcement(-1, 41, 20), t0 + std::chrono::milliseconds(20));
    check((*every.assignment(1))[0] == 42, "a late announcement of the old boot does not take it back");
    every.heard(announcement(-1, 41, 30), t0 + NodeDirectory::kCurrentWindow + std::chrono::milliseconds(20));
    check((*every.assignment(1))[0] == 41, "a lower boot, once the current one fell silent for the window, does");

    NodeDirectory fleet;
    fleet.heard(announcement(0, 7, 1), t0);
    fleet.heard(announcement(-1, 9, 1), t0);
    check(!fleet.assignment(2), "robot 0 has its own node, robot 1 none: no assignment (not mixed with every-robot)");
    fleet.heard(announcement(1, 8, 1), t0);
    const auto own = fleet.assignment(2);
    check(own && (*own)[0] == 7 && (*own)[1] == 8, "each robot its own node");
    check(fleet.of_boot(8) != nullptr && fleet.of_boot(8)->own_robot == 1 && fleet.heard_at(8) == t0,
          "a boot's announcement and when it was heard");

    NodeDirectory other;
    tvo_lcm::node_status_t v2 = announcement(-1, 5, 1);
    v2.protocol_version = 2;
    other.heard(v2, t0);
    check(!other.assignment(1) && other.foreign() == 1 && other.describe().find("protocol 2") != std::string::npos,
          "another protocol's node is not taken, and said so");
}

void test_telemetry_rate()
{
    check(tvo_host::telemetry_every_periods(0, 10000) == 10 && tvo_host::telemetry_every_periods(0, 30000) == 4 &&
              tvo_host::telemetry_every_periods(0, 200000) == 1 && tvo_host::telemetry_every_periods(3, 10000) == 3,
          "telemetry every n-th period: the fewest spanning 100 ms by default, else as asked");
}

/// tvo_sim's exit code for a command line, its error text in *err.
int parse(std::vector<std::string> args, std::string* err)
{
    args.insert(args.begin(), "tvo_sim");
    std::vector<char*> argv;
    for (std::string& a : args) {
        argv.push_back(a.data());
    }
    std::ostringstream captured;
    std::streambuf* const saved = std::cerr.rdbuf(captured.rdbuf());
    std::streambuf* const saved_out = std::cout.rdbuf(captured.rdbuf());
    tvo_host::SimOptions options;
    const int rc = tvo_host::parse_options(static_cast<int>(argv.size()), argv.data(), &options);
    std::cerr.rdbuf(saved);
    std::cout.rdbuf(saved_out);
    *err = captured.str();
    return rc;
}

void test_options()
{
    std::string err;
    const int many = parse({"--scenario", "demo", "--robots", std::to_string(kMaxRobots), "--dry-run", "--out-dir", "/tmp"},
                           &err);
    check(many == 0, "32 robots (the wire's limit): a run");
    const int sequence = parse({"--period-s", "1e-6", "--duration-s", "3000", "--dry-run", "--out-dir", "/tmp",
                                "--max-output-mib", "65536"},
                               &err);
    check(sequence == 2 && err.find("int32") != std::string::npos,
          "more periods than an int32 sequence numbers: refused, naming the wire's sequence");
}

}  // namespace

int main()
{
    test_samples();
    test_assembler();
    test_directory();
    test_telemetry_rate();
    test_options();
    if (g_failures != 0) {
        std::printf("%d check(s) failed\n", g_failures);
        return 1;
    }
    std::printf("all checks passed\n");
    return 0;
}
