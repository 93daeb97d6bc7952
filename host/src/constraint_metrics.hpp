// Judges a run against its scenario's constraints, from the plant's true positions: collisions and
// clearance, inter-robot distance, bound violations, time to feasibility, equality residual.
//
// observe() is called densely (sim_loop.cpp: every 1 ms of plant time and at every sample and
// command instant), so a contact between two checks would need the robot to cross a disk edge and
// come back within 1 ms.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include <Eigen/Core>

#include "scenario.hpp"

namespace tvo_host {

using Positions = std::array<Eigen::Vector2d, kMaxRobots>;

class ConstraintMonitor {
public:
    explicit ConstraintMonitor(const Scenario& scenario);

    /// The robots' true positions at plant time t_s (non-decreasing t_s).
    void observe(double t_s, const Positions& positions);

    /// Entries into contact (robot disk vs obstacle disk; robot vs robot when robots have a radius).
    std::uint64_t collisions() const { return collisions_; }
    /// Where and when a robot entered contact (the plot marks each); the first kMaxContactEvents only.
    struct ContactEvent {
        double t_s;
        std::size_t robot;
        std::size_t other;        // obstacle index, or robot index when robot_robot
        bool robot_robot;
        Eigen::Vector2d position_m;  // the robot's centre at the entry
    };
    static constexpr std::size_t kMaxContactEvents = 32;
    const std::vector<ContactEvent>& contact_events() const { return contact_events_; }
    /// Smallest gap between the disks over the run (negative: overlap).
    double min_clearance_m() const { return min_clearance_m_; }
    /// Distance of the reported pair (Scenario::reported_pair): smallest, inside the crossing window, last.
    double min_distance_m() const { return min_distance_m_; }
    double min_distance_window_m() const { return min_distance_window_m_; }
    double final_distance_m() const { return final_distance_m_; }
    /// Worst relative violation of any inequality bound (0 if none was violated); with an infeasible
    /// start, counted from the first instant all bounds hold (see host/README.md).
    double max_violation_frac() const;
    /// The same per kind of bound: distance minimum, distance maximum (formation scenarios).
    double max_violation_min_bound_frac() const { return worst_entered_.min_bound; }
    double max_violation_max_bound_frac() const { return worst_entered_.max_bound; }
    /// The instant from which max_violation_frac counts: the first at which every bound held (0 for a
    /// feasible start); infinity if no bound ever held all at once (then it counts over the whole run).
    double violation_counted_from_s() const;
    /// Largest relative violation at the start (0 for a feasible start).
    double initial_violation_frac() const { return initial_violation_frac_; }
    /// The first time after which every inequality holds to the end; infinity if one is violated at the end.
    double time_to_feasible_s() const;
    /// max over t >= settle_time_s of |y_a - y_b - d(t)| over the offsets.
    double equality_residual_m() const { return equality_residual_m_; }

    bool has_contacts() const { return !contacts_.empty(); }
    bool has_pair() const { return pair_valid_; }

private:
    struct Contact {
        std::size_t robot;
        std::size_t other;        // obstacle index, or robot index when robot_robot
        bool robot_robot;
        bool in_contact{false};
    };

    /// Relative violations at one instant, per kind of bound (<= 0: the bounds of that kind hold).
    struct Violations {
        double min_bound{-std::numeric_limits<double>::infinity()};
        double max_bound{-std::numeric_limits<double>::infinity()};
        double halfspace{-std::numeric_limits<double>::infinity()};
        double obstacle{-std::numeric_limits<double>::infinity()};
        double worst() const;
    };
    Violations violations(double t_s, const Positions& p) const;

    const Scenario& scenario_;
    std::vector<Contact> contacts_;
    std::array<std::size_t, 2> pair_{0, 1};
    bool pair_valid_{false};

    std::uint64_t collisions_{0};
    std::vector<ContactEvent> contact_events_;
    double min_clearance_m_{std::numeric_limits<double>::infinity()};
    double min_distance_m_{std::numeric_limits<double>::infinity()};
    double min_distance_window_m_{std::numeric_limits<double>::infinity()};
    double final_distance_m_{0.0};
    double equality_residual_m_{0.0};

    bool observed_{false};
    bool feasible_now_{true};
    bool ever_infeasible_{false};
    bool entered_feasible_{false};      // all bounds have held at least once
    double feasible_since_s_{0.0};
    double first_feasible_s_{0.0};      // when entered_feasible_ became true
    double initial_violation_frac_{0.0};
    double max_violation_all_{0.0};     // over the whole run
    double max_violation_entered_{0.0}; // from the first feasible instant on
    Violations worst_entered_{0.0, 0.0, 0.0, 0.0};
};

}  // namespace tvo_host
