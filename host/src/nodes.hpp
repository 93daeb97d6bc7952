// The nodes on the bus as their announcements say (TVO_NODE, node_status_t): which node drives each
// robot, its boot, state and counters (the plant's rule 1, lcm_types/README.md "Writing your own plant").
#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "lcm_messages.hpp"
#include "plant.hpp"

namespace tvo_host {

/// Each robot's node boot (session_t.node_boot_id), robots past the session's count 0.
using NodeBoots = std::array<std::int64_t, kMaxRobots>;

class NodeDirectory {
public:
    using Clock = std::chrono::steady_clock;
    /// An announcement of another boot of a role heard this recently keeps the higher boot current: boots
    /// only grow, so a late copy of a dead boot's announcement (or a second node claiming the same robot)
    /// never takes a role back. Three of a running node's announcement periods.
    static constexpr std::chrono::milliseconds kCurrentWindow{3 * tvo_lcm::node_status_t::RUNNING_PERIOD_US / 1000};

    /// Takes an announcement heard at `now`; one of another protocol is only counted (foreign()).
    void heard(const tvo_lcm::node_status_t& status, Clock::time_point now);

    /// Rule 1: the boots driving robots 0 .. robots - 1: every robot its own node (own_robot == r), else
    /// the node that drives every robot (own_robot == -1, none of the robots has its own); nullopt until
    /// one of the two is complete.
    std::optional<NodeBoots> assignment(std::size_t robots) const;

    /// The newest announcement of the node currently in this role (own_robot, -1 for every robot).
    const tvo_lcm::node_status_t* current(std::int8_t own_robot) const;
    /// The newest announcement of this boot, if it is the current boot of its role.
    const tvo_lcm::node_status_t* of_boot(std::int64_t boot_id) const;

    /// When this boot's newest announcement was heard, if it is the current boot of its role.
    std::optional<Clock::time_point> heard_at(std::int64_t boot_id) const;

    /// Announcements of another protocol version, and the last of them.
    std::uint64_t foreign() const { return foreign_; }
    std::int32_t foreign_protocol() const { return foreign_protocol_; }

    /// What was heard, for an error message: "node of robot 0 (boot 12), node of every robot (boot 7)".
    std::string describe() const;

private:
    struct Role {
        bool known{false};
        tvo_lcm::node_status_t status{};  // the current boot's newest
        Clock::time_point heard{};
    };
    static constexpr std::size_t kRoles = kMaxRobots + 1;  // own_robot -1 .. kMaxRobots - 1
    static std::optional<std::size_t> role_index(std::int8_t own_robot);

    std::array<Role, kRoles> roles_{};
    std::uint64_t foreign_{0};
    std::int32_t foreign_protocol_{0};
};

}  // namespace tvo_host
