// The plant's messages in one place: a period's sample of every robot and the joint command it
// applies, sized by the simulator's limit (kMaxRobots), and their two legs on the wire: joint
// (measurement_t / command_t, at most measurement_t::MAX_ROBOTS robots) or per robot (tvo_sim --fleet:
// one fleet_sample_t and one fleet_command_t per robot and period; lcm_types/README.md, "A fleet").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "lcm_messages.hpp"
#include "plant.hpp"
#include "tvo_lcm/fleet_command_t.hpp"
#include "tvo_lcm/fleet_sample_t.hpp"

namespace tvo_host {

static_assert(kMaxRobots == static_cast<std::size_t>(tvo_lcm::fleet_sample_t::MAX_ROBOTS) &&
                  kMaxRobots == static_cast<std::size_t>(tvo_lcm::fleet_command_t::MAX_ROBOTS),
              "the simulator's limit is the per-robot messages' limit");

/// Most robots the joint messages carry; a larger scenario needs the per-robot leg (--fleet).
constexpr std::size_t kMaxJointRobots = static_cast<std::size_t>(tvo_lcm::measurement_t::MAX_ROBOTS);
static_assert(sizeof(tvo_lcm::command_t::speed_mps) / sizeof(double) == kMaxJointRobots &&
                  sizeof(tvo_lcm::target_t::position_m) / sizeof(tvo_lcm::target_t::position_m[0]) == kMaxJointRobots,
              "command_t and target_t carry measurement_t's robots");

/// One period's sample of every robot, as the plant measured it (measurement_t's fields).
struct JointMeasurement {
    std::int64_t utime{0};
    std::int64_t session_id{0};
    std::int64_t sequence{0};
    std::int32_t robot_count{0};
    std::array<std::array<double, 2>, kMaxRobots> position_m{};
    std::array<double, kMaxRobots> heading_rad{};
    std::array<double, kMaxRobots> speed_mps{};
    bool heading_valid{false};
    bool speed_valid{false};
};

/// A command for every robot, as the plant's rules see it (command_t's fields).
struct JointCommand {
    std::int64_t utime{0};
    std::int64_t session_id{0};
    std::int64_t measurement_sequence{0};
    std::int32_t robot_count{0};
    std::int32_t status{0};
    std::int32_t flags{0};
    std::array<double, kMaxRobots> speed_mps{};
    std::array<double, kMaxRobots> turn_rate_radps{};
};

/// The joint leg's sample (robot_count <= kMaxJointRobots: tvo_sim's options refuse more without --fleet).
void to_wire(const JointMeasurement& in, tvo_lcm::measurement_t* out);
/// The per-robot leg: robot `robot`'s sample of the period.
void to_wire(const JointMeasurement& in, std::size_t robot, tvo_lcm::fleet_sample_t* out);
/// The joint leg's command as the plant handles it.
JointCommand from_wire(const tvo_lcm::command_t& in);

/// The per-robot leg's commands: joins one period's rows (fleet_command_t, one per robot) into the
/// joint command, complete when every robot's row of one (session, sequence) arrived. Its status is the
/// first refusing row's (in robot order), else 0; its flags every row's; its utime the latest row's.
/// A row of another (session, sequence) starts over: a period's rows come back to back, and one whose
/// rows did not all come is never applied (as a lost joint command). A row naming no robot of the run
/// (robot or robot_count off) cannot join any command and is dropped.
class CommandAssembler {
public:
    explicit CommandAssembler(std::size_t robots) : robots_(robots) {}

    /// The joint command `row` completes, else nullptr (valid until the next call).
    const JointCommand* add(const tvo_lcm::fleet_command_t& row);

private:
    std::size_t robots_;
    std::uint32_t arrived_{0};  // bit r: robot r's row of joint_'s (session, sequence) is in
    JointCommand joint_{};
    std::array<std::int64_t, kMaxRobots> utime_{};  // each row's own, joined on completion
    std::array<std::int32_t, kMaxRobots> status_{};
    std::array<std::int32_t, kMaxRobots> flags_{};
};

}  // namespace tvo_host
