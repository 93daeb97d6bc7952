// The plant's messages to and from the wire; see plant_wire.hpp.
#include "plant_wire.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace tvo_host {

namespace {
constexpr double kTwoPi = 6.283185307179586476925286766559;
}  // namespace

void to_wire(const JointMeasurement& in, std::size_t robot, tvo_lcm::unicycle_sample_t* out)
{
    out->header.utime = in.utime;
    out->header.session_id = in.session_id;
    out->header.sequence = in.sequence;
    out->header.robot = static_cast<std::int8_t>(robot);
    out->has = static_cast<std::int8_t>((in.heading_valid ? tvo_lcm::unicycle_sample_t::HAS_HEADING : 0) |
                                        (in.speed_valid ? tvo_lcm::unicycle_sample_t::HAS_SPEED : 0));
    out->position_m[0] = in.position_m[robot][0];
    out->position_m[1] = in.position_m[robot][1];
    out->heading_rad = static_cast<float>(std::remainder(in.heading_rad[robot], kTwoPi));
    out->speed_mps = static_cast<float>(in.speed_mps[robot]);
}

const JointCommand* CommandAssembler::add(const tvo_lcm::unicycle_command_t& command)
{
    const tvo_lcm::command_header_t& h = command.header;
    if (h.robot < 0 || static_cast<std::size_t>(h.robot) >= robots_) {
        return nullptr;
    }
    if (arrived_.none() || h.session_id != joint_.session_id || h.measurement_sequence != joint_.measurement_sequence) {
        joint_ = JointCommand{};
        joint_.session_id = h.session_id;
        joint_.measurement_sequence = h.measurement_sequence;
        joint_.robot_count = static_cast<std::int32_t>(robots_);
        arrived_.reset();
    }
    const auto r = static_cast<std::size_t>(h.robot);
    arrived_.set(r);
    utime_[r] = h.utime;
    status_[r] = h.status;
    flags_[r] = h.flags;
    joint_.speed_mps[r] = static_cast<double>(command.speed_mps);
    joint_.turn_rate_radps[r] = static_cast<double>(command.turn_rate_radps);
    if (arrived_.count() != robots_) {
        return nullptr;
    }
    arrived_.reset();  // the next command starts a new set (safe stops of the next period share sequence -1)
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
