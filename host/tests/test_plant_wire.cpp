// Checks of the plant's two legs on the wire (plant_wire.hpp): a period's sample as measurement_t and
// as per-robot fleet_sample_t, command_t and fleet_command_t rows into the joint command (up to the
// simulator's 8 robots), and tvo_sim's refusal of a scenario the joint messages cannot carry without
// --fleet. Plain asserts (no framework): exit code 0 = pass.
#include <cstdio>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "plant_wire.hpp"

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
    const JointMeasurement m = sample_of(4);
    tvo_lcm::measurement_t joint{};
    tvo_host::to_wire(m, &joint);
    check(joint.utime == m.utime && joint.session_id == 77 && joint.sequence == 3 && joint.robot_count == 4 &&
              joint.heading_valid && !joint.speed_valid,
          "joint sample: stamp, session, sequence, count and flags");
    check(joint.position_m[3][0] == 4.0 && joint.position_m[3][1] == -5.0 && joint.heading_rad[3] == m.heading_rad[3] &&
              joint.speed_mps[2] == 2.5,
          "joint sample: every robot's pose and speed");
    const JointMeasurement m8 = sample_of(kMaxRobots);
    bool rows_ok = true;
    for (std::size_t r = 0; r < kMaxRobots; ++r) {
        tvo_lcm::fleet_sample_t s{};
        tvo_host::to_wire(m8, r, &s);
        rows_ok = rows_ok && s.utime == m8.utime && s.session_id == 77 && s.sequence == 3 &&
                  s.robot == static_cast<std::int32_t>(r) && s.robot_count == 8 &&
                  s.position_m[0] == m8.position_m[r][0] && s.position_m[1] == m8.position_m[r][1] &&
                  s.heading_rad == m8.heading_rad[r] && s.speed_mps == m8.speed_mps[r] && s.heading_valid &&
                  !s.speed_valid;
    }
    check(rows_ok, "per-robot samples: robot r's own pose, the period's stamp, 8 robots");
}

void test_joint_command()
{
    tvo_lcm::command_t c{};
    c.utime = 42;
    c.session_id = 7;
    c.measurement_sequence = 9;
    c.robot_count = 4;
    c.status = 12;
    c.flags = 0x21;
    c.speed_mps[3] = 1.5;
    c.turn_rate_radps[0] = -0.25;
    const JointCommand j = tvo_host::from_wire(c);
    check(j.utime == 42 && j.session_id == 7 && j.measurement_sequence == 9 && j.robot_count == 4 && j.status == 12 &&
              j.flags == 0x21 && j.speed_mps[3] == 1.5 && j.turn_rate_radps[0] == -0.25,
          "command_t as the joint command");
}

tvo_lcm::fleet_command_t row_of(std::int32_t robot, std::int32_t robots, std::int64_t sequence)
{
    tvo_lcm::fleet_command_t row{};
    row.utime = 2000 + robot;
    row.session_id = 7;
    row.measurement_sequence = sequence;
    row.robot = robot;
    row.robot_count = robots;
    row.speed_mps = 0.1 * robot;
    row.turn_rate_radps = -0.2 * robot;
    row.flags = robot >= 0 ? 1 << robot : 0;
    return row;
}

void test_assembler()
{
    CommandAssembler rows(kMaxRobots);
    const auto n = static_cast<std::int32_t>(kMaxRobots);
    const JointCommand* joint = nullptr;
    bool early = false;
    for (std::int32_t r = n - 1; r >= 0; --r) {  // any order
        joint = rows.add(row_of(r, n, 5));
        early = early || (r > 0 && joint != nullptr);
    }
    check(!early && joint != nullptr, "8 robots: complete with the last robot's row, not before");
    bool values_ok = joint != nullptr && joint->robot_count == n && joint->measurement_sequence == 5 &&
                     joint->session_id == 7 && joint->status == 0 && joint->flags == 0xff && joint->utime == 2000 + n - 1;
    for (std::int32_t r = 0; joint != nullptr && r < n; ++r) {
        values_ok = values_ok && joint->speed_mps[static_cast<std::size_t>(r)] == 0.1 * r &&
                    joint->turn_rate_radps[static_cast<std::size_t>(r)] == -0.2 * r;
    }
    check(values_ok, "each robot's row in its place; flags joined, the latest utime");

    // A period whose rows did not all come is replaced by the next one's.
    CommandAssembler three(3);
    three.add(row_of(0, 3, 10));
    three.add(row_of(1, 3, 10));
    check(three.add(row_of(0, 3, 11)) == nullptr && three.add(row_of(2, 3, 11)) == nullptr,
          "an incomplete period is dropped: the next period starts over");
    tvo_lcm::fleet_command_t refused = row_of(1, 3, 11);
    refused.status = 9;
    joint = three.add(refused);
    check(joint != nullptr && joint->measurement_sequence == 11 && joint->status == 9,
          "complete on the third row of sequence 11; status the refusing row's");
    check(three.add(row_of(3, 3, 12)) == nullptr && three.add(row_of(0, 4, 12)) == nullptr &&
              three.add(row_of(-1, 3, 12)) == nullptr,
          "rows naming no robot of the run are dropped");
    three.add(row_of(0, 3, 12));
    three.add(row_of(1, 3, 12));
    tvo_lcm::fleet_command_t other = row_of(2, 3, 12);
    other.session_id = 8;
    check(three.add(other) == nullptr, "a row of another session does not complete this one");
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

void test_leg_options()
{
    const std::string robots = std::to_string(tvo_host::kMaxJointRobots + 1);
    std::string err;
    const int joint = parse({"--scenario", "demo", "--robots", robots, "--dry-run", "--out-dir", "/tmp"}, &err);
    check(joint == 2 && err.find("--fleet") != std::string::npos, "more robots than measurement_t carries: refused, naming --fleet");
    const int fleet = parse({"--scenario", "demo", "--robots", robots, "--fleet", "--dry-run", "--out-dir", "/tmp"}, &err);
    const bool session_carries = tvo_host::kMaxJointRobots + 1 <= static_cast<std::size_t>(tvo_lcm::session_t::MAX_ROBOTS);
    check(session_carries ? fleet == 0 : (fleet == 2 && err.find("session_t") != std::string::npos),
          "with --fleet: run if session_t carries the robots, else refused naming session_t");
    const int four = parse({"--scenario", "demo", "--robots", "4", "--dry-run", "--out-dir", "/tmp"}, &err);
    check(four == 0, "4 robots on the joint leg: fine");
    const int spawn = parse({"--scenario", "demo", "--fleet", "--firmware", "/bin/true", "--dry-run"}, &err);
    check(spawn == 2 && err.find("--fleet") != std::string::npos, "--fleet with --firmware: refused");
}

}  // namespace

int main()
{
    test_samples();
    test_joint_command();
    test_assembler();
    test_leg_options();
    if (g_failures != 0) {
        std::printf("%d check(s) failed\n", g_failures);
        return 1;
    }
    std::printf("all checks passed\n");
    return 0;
}
