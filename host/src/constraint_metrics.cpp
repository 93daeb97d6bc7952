// Constraint metrics of a run; see constraint_metrics.hpp.
#include "constraint_metrics.hpp"

#include <algorithm>
#include <cmath>

namespace tvo_host {

namespace {
// Sample times are sums of whole microseconds: a nanosecond of slack keeps a window's edges in.
constexpr double kTimeSlackS = 1e-9;
}  // namespace

ConstraintMonitor::ConstraintMonitor(const Scenario& scenario) : scenario_(scenario)
{
    contact_events_.reserve(kMaxContactEvents);  // no allocation while the run observes
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        for (std::size_t i = 0; i < scenario.obstacles.size(); ++i) {
            contacts_.push_back(Contact{r, i, false});
        }
    }
    if (scenario.robot_radius_m > 0.0) {
        for (std::size_t a = 0; a < scenario.robot_count; ++a) {
            for (std::size_t b = a + 1; b < scenario.robot_count; ++b) {
                contacts_.push_back(Contact{a, b, true});
            }
        }
    }
    if (const auto pair = scenario.reported_pair()) {
        pair_ = *pair;
        pair_valid_ = true;
    }
}

double ConstraintMonitor::Violations::worst() const
{
    return std::max(std::max(min_bound, max_bound), std::max(halfspace, obstacle));
}

ConstraintMonitor::Violations ConstraintMonitor::violations(double t_s, const Positions& p) const
{
    Violations v;
    for (const DistanceBound& b : scenario_.distances) {
        const double d = (p[b.robot_a] - p[b.robot_b]).norm();
        if (b.min_m > 0.0) {
            const double bound = b.min_at(t_s);
            v.min_bound = std::max(v.min_bound, (bound - d) / bound);
        }
        if (b.max_m > 0.0) {
            const double bound = b.max_at(t_s);
            v.max_bound = std::max(v.max_bound, (d - bound) / bound);
        }
    }
    for (const HalfSpace& h : scenario_.halfspaces) {
        // No natural scale: the signed distance past the plane, per metre.
        const Eigen::Vector2d a = h.normal + h.normal_rate * t_s;
        const double b = h.bound_m + h.bound_rate_mps * t_s;
        v.halfspace = std::max(v.halfspace, (a.dot(p[h.robot]) - b) / a.norm());
    }
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        for (const Disk& o : scenario_.obstacles) {
            const double reach = scenario_.robot_radius_m + o.radius_m;
            v.obstacle = std::max(v.obstacle, (reach - (p[r] - o.center_m).norm()) / reach);
        }
    }
    return v;
}

void ConstraintMonitor::observe(double t_s, const Positions& p)
{
    for (Contact& c : contacts_) {
        double clearance = 0.0;
        if (c.robot_robot) {
            clearance = (p[c.robot] - p[c.other]).norm() - 2.0 * scenario_.robot_radius_m;
        } else {
            const Disk& o = scenario_.obstacles[c.other];
            clearance = (p[c.robot] - o.center_m).norm() - scenario_.robot_radius_m - o.radius_m;
        }
        min_clearance_m_ = std::min(min_clearance_m_, clearance);
        const bool touching = clearance < 0.0;
        if (touching && !c.in_contact) {
            ++collisions_;  // an entry into contact, not every sample spent in it
            if (contact_events_.size() < kMaxContactEvents) {
                contact_events_.push_back(ContactEvent{t_s, c.robot, c.other, c.robot_robot, p[c.robot]});
            }
        }
        c.in_contact = touching;
    }

    if (pair_valid_) {
        const double d = (p[pair_[0]] - p[pair_[1]]).norm();
        min_distance_m_ = std::min(min_distance_m_, d);
        final_distance_m_ = d;
        const auto& w = scenario_.crossing_window;
        if (w && t_s >= w->start_s - kTimeSlackS && t_s <= w->end_s + kTimeSlackS) {
            min_distance_window_m_ = std::min(min_distance_window_m_, d);
        }
    }

    if (t_s >= scenario_.settle_time_s - kTimeSlackS) {
        for (const OffsetEquality& e : scenario_.offsets) {
            const double residual = (p[e.robot_a] - p[e.robot_b] - e.offset.position(t_s)).norm();
            equality_residual_m_ = std::max(equality_residual_m_, residual);
        }
    }

    if (scenario_.has_inequalities()) {
        const Violations now = violations(t_s, p);
        const double violation = std::max(0.0, now.worst());
        if (!observed_) {
            initial_violation_frac_ = violation;
        }
        max_violation_all_ = std::max(max_violation_all_, violation);
        const bool feasible = violation <= 0.0;
        if (feasible && !entered_feasible_) {
            entered_feasible_ = true;
            first_feasible_s_ = t_s;
        }
        if (entered_feasible_) {
            max_violation_entered_ = std::max(max_violation_entered_, violation);
            worst_entered_.min_bound = std::max(worst_entered_.min_bound, now.min_bound);
            worst_entered_.max_bound = std::max(worst_entered_.max_bound, now.max_bound);
            worst_entered_.halfspace = std::max(worst_entered_.halfspace, now.halfspace);
            worst_entered_.obstacle = std::max(worst_entered_.obstacle, now.obstacle);
        }
        if (!feasible) {
            ever_infeasible_ = true;
        } else if (!feasible_now_ || !observed_) {
            feasible_since_s_ = t_s;  // start of the current feasible stretch
        }
        feasible_now_ = feasible;
    }
    observed_ = true;
}

double ConstraintMonitor::max_violation_frac() const
{
    // A run that never became feasible is judged over all of it.
    return entered_feasible_ ? max_violation_entered_ : max_violation_all_;
}

double ConstraintMonitor::violation_counted_from_s() const
{
    return entered_feasible_ ? first_feasible_s_ : std::numeric_limits<double>::infinity();
}

double ConstraintMonitor::time_to_feasible_s() const
{
    if (!feasible_now_) {
        return std::numeric_limits<double>::infinity();
    }
    return ever_infeasible_ ? feasible_since_s_ : 0.0;
}

}  // namespace tvo_host
