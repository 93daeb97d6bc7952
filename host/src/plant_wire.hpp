// The plant's messages in one place: a period's sample of every robot and the joint command it
// applies, sized by the simulator's limit (kMaxRobots, the wire's), and their per-robot messages on the
// wire (lcm_types/README.md, "Writing your own plant"): one unicycle_sample_t per robot and period out,
// in robot order; one unicycle_command_t per robot in, joined into the joint command.
#pragma once

#include <array>
#include <bitset>
#include <cstddef>
#include <cstdint>

#include "lcm_messages.hpp"
#include "plant.hpp"

namespace tvo_host {

static_assert(kMaxRobots == static_cast<std::size_t>(tvo_lcm::session_t::MAX_ROBOTS),
              "the simulator's limit is the wire's");

/// One period's sample of every robot, as the plant measured it.
struct JointMeasurement {
    std::int64_t utime{0};
    std::int32_t session_id{0};
    std::int32_t sequence{0};
    std::int32_t robot_count{0};
    std::array<std::array<double, 2>, kMaxRobots> position_m{};
    std::array<double, kMaxRobots> heading_rad{};  // unwrapped, as the plant integrates it
    std::array<double, kMaxRobots> speed_mps{};
    bool heading_valid{false};
    bool speed_valid{false};
};

/// A command for every robot, as the plant's rules see it: one period's unicycle_command_t of each robot.
struct JointCommand {
    std::int64_t utime{0};
    std::int32_t session_id{0};
    std::int32_t measurement_sequence{0};
    std::int32_t robot_count{0};
    std::int32_t status{0};
    std::int32_t flags{0};
    std::array<double, kMaxRobots> speed_mps{};
    std::array<double, kMaxRobots> turn_rate_radps{};
};

/// Robot `robot`'s sample of the period. The heading goes out wrapped to [-pi, pi], where the wire's
/// float resolves it to 2.4e-7 rad (unicycle_sample_t.lcm).
void to_wire(const JointMeasurement& in, std::size_t robot, tvo_lcm::unicycle_sample_t* out);

/// Joins one period's commands (unicycle_command_t, one per robot) into the joint command, complete when
/// every robot's command of one (session, sequence) arrived. Its status is the first refusing robot's (in
/// robot order), else 0; its flags every robot's; its utime the latest command's. A command of another
/// (session, sequence) starts over: a period's commands come back to back, and one whose commands did not
/// all come is never applied (as a lost command). A node's own safe stops (sequence -1) join the same way,
/// one set per period. A command naming no robot of the run cannot join any command and is dropped.
class CommandAssembler {
public:
    explicit CommandAssembler(std::size_t robots) : robots_(robots) {}

    /// The joint command `command` completes, else nullptr (valid until the next call).
    const JointCommand* add(const tvo_lcm::unicycle_command_t& command);

private:
    std::size_t robots_;
    std::bitset<kMaxRobots> arrived_;  // robot r's command of joint_'s (session, sequence) is in
    JointCommand joint_{};
    std::array<std::int64_t, kMaxRobots> utime_{};  // each command's own, joined on completion
    std::array<std::int32_t, kMaxRobots> status_{};
    std::array<std::int32_t, kMaxRobots> flags_{};
};

}  // namespace tvo_host
