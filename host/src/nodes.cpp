// The nodes on the bus; see nodes.hpp.
#include "nodes.hpp"

#include <sstream>

namespace tvo_host {

std::optional<std::size_t> NodeDirectory::role_index(std::int8_t own_robot)
{
    if (own_robot < -1 || own_robot >= static_cast<std::int8_t>(kMaxRobots)) {
        return std::nullopt;
    }
    return static_cast<std::size_t>(own_robot + 1);
}

void NodeDirectory::heard(const tvo_lcm::node_status_t& status, Clock::time_point now)
{
    if (status.protocol_version != tvo_lcm::node_status_t::PROTOCOL_VERSION) {
        ++foreign_;
        foreign_protocol_ = status.protocol_version;
        return;
    }
    const std::optional<std::size_t> index = role_index(status.own_robot);
    if (!index || status.boot_id <= 0) {
        return;
    }
    Role& role = roles_[*index];
    const bool same_boot = role.known && role.status.boot_id == status.boot_id;
    const bool lower_boot_recently = role.known && status.boot_id < role.status.boot_id && now - role.heard < kCurrentWindow;
    if (lower_boot_recently) {
        return;
    }
    if (same_boot && status.utime < role.status.utime) {
        return;  // an older announcement of this boot, late
    }
    role.known = true;
    role.status = status;
    role.heard = now;
}

std::optional<NodeBoots> NodeDirectory::assignment(std::size_t robots) const
{
    NodeBoots boots{};
    bool every_robot_its_own = robots > 0;
    bool any_own = false;
    for (std::size_t r = 0; r < robots && r < kMaxRobots; ++r) {
        const Role& own = roles_[r + 1];
        every_robot_its_own = every_robot_its_own && own.known;
        any_own = any_own || own.known;
        boots[r] = own.known ? own.status.boot_id : 0;
    }
    if (every_robot_its_own) {
        return boots;
    }
    const Role& all = roles_[0];
    if (any_own || !all.known) {
        return std::nullopt;
    }
    for (std::size_t r = 0; r < robots && r < kMaxRobots; ++r) {
        boots[r] = all.status.boot_id;
    }
    return boots;
}

const tvo_lcm::node_status_t* NodeDirectory::current(std::int8_t own_robot) const
{
    const std::optional<std::size_t> index = role_index(own_robot);
    return index && roles_[*index].known ? &roles_[*index].status : nullptr;
}

const tvo_lcm::node_status_t* NodeDirectory::of_boot(std::int64_t boot_id) const
{
    for (const Role& role : roles_) {
        if (role.known && role.status.boot_id == boot_id) {
            return &role.status;
        }
    }
    return nullptr;
}

std::optional<NodeDirectory::Clock::time_point> NodeDirectory::heard_at(std::int64_t boot_id) const
{
    for (const Role& role : roles_) {
        if (role.known && role.status.boot_id == boot_id) {
            return role.heard;
        }
    }
    return std::nullopt;
}

std::string NodeDirectory::describe() const
{
    std::ostringstream out;
    const char* separator = "";
    for (std::size_t i = 0; i < kRoles; ++i) {
        if (!roles_[i].known) {
            continue;
        }
        out << separator << (i == 0 ? std::string("the node of every robot") : "the node of robot " + std::to_string(i - 1))
            << " (boot " << roles_[i].status.boot_id << ", up to " << static_cast<int>(roles_[i].status.max_robots)
            << " robots)";
        separator = ", ";
    }
    if (foreign_ > 0) {
        out << separator << foreign_ << " announcement(s) of protocol " << foreign_protocol_ << " (this plant speaks "
            << tvo_lcm::node_status_t::PROTOCOL_VERSION << ")";
        separator = ", ";
    }
    const std::string text = out.str();
    return text.empty() ? "no node" : text;
}

}  // namespace tvo_host
