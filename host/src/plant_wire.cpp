// The plant's messages to and from the wire; see plant_wire.hpp.
#include "plant_wire.hpp"

#include <algorithm>
#include <cstddef>
#include <iterator>

namespace tvo_host {

void to_wire(const JointMeasurement& in, tvo_lcm::measurement_t* out)
{
    out->utime = in.utime;
    out->session_id = in.session_id;
    out->sequence = in.sequence;
    out->robot_count = in.robot_count;
    out->heading_valid = in.heading_valid;
    out->speed_valid = in.speed_valid;
    for (std::size_t r = 0; r < kMaxJointRobots; ++r) {
        out->position_m[r][0] = in.position_m[r][0];
        out->position_m[r][1] = in.position_m[r][1];
        out->heading_rad[r] = in.heading_rad[r];
        out->speed_mps[r] = in.speed_mps[r];
    }
}

void to_wire(const JointMeasurement& in, std::size_t robot, tvo_lcm::fleet_sample_t* out)
{
    out->utime = in.utime;
    out->session_id = in.session_id;
    out->sequence = in.sequence;
    out->robot = static_cast<std::int32_t>(robot);
    out->robot_count = in.robot_count;
    out->position_m[0] = in.position_m[robot][0];
    out->position_m[1] = in.position_m[robot][1];
    out->heading_rad = in.heading_rad[robot];
    out->speed_mps = in.speed_mps[robot];
    out->heading_valid = in.heading_valid;
    out->speed_valid = in.speed_valid;
}

JointCommand from_wire(const tvo_lcm::command_t& in)
{
    JointCommand out;
    out.utime = in.utime;
    out.session_id = in.session_id;
    out.measurement_sequence = in.measurement_sequence;
    out.robot_count = in.robot_count;
    out.status = in.status;
    out.flags = in.flags;
    std::copy(std::begin(in.speed_mps), std::end(in.speed_mps), out.speed_mps.begin());
    std::copy(std::begin(in.turn_rate_radps), std::end(in.turn_rate_radps), out.turn_rate_radps.begin());
    return out;
}

const JointCommand* CommandAssembler::add(const tvo_lcm::fleet_command_t& row)
{
    if (row.robot < 0 || static_cast<std::size_t>(row.robot) >= robots_ ||
        row.robot_count != static_cast<std::int32_t>(robots_)) {
        return nullptr;
    }
    if (arrived_ == 0u || row.session_id != joint_.session_id || row.measurement_sequence != joint_.measurement_sequence) {
        joint_ = JointCommand{};
        joint_.session_id = row.session_id;
        joint_.measurement_sequence = row.measurement_sequence;
        joint_.robot_count = row.robot_count;
        arrived_ = 0u;
    }
    const auto r = static_cast<std::size_t>(row.robot);
    arrived_ |= 1u << r;
    utime_[r] = row.utime;
    status_[r] = row.status;
    flags_[r] = row.flags;
    joint_.speed_mps[r] = row.speed_mps;
    joint_.turn_rate_radps[r] = row.turn_rate_radps;
    if (arrived_ != (1u << robots_) - 1u) {
        return nullptr;
    }
    joint_.utime = *std::max_element(utime_.begin(), utime_.begin() + static_cast<std::ptrdiff_t>(robots_));
    joint_.status = 0;
    joint_.flags = 0;
    for (std::size_t k = 0; k < robots_; ++k) {
        joint_.status = joint_.status != 0 ? joint_.status : status_[k];
        joint_.flags |= flags_[k];
    }
    return &joint_;
}

}  // namespace tvo_host
