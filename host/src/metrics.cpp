// Run metrics; see metrics.hpp.
#include "metrics.hpp"

#include <algorithm>
#include <cmath>

namespace tvo_host {

namespace {
// Sample times are sums of whole microseconds: a nanosecond of slack keeps the window's edge in.
constexpr double kTimeSlackS = 1e-9;
}  // namespace

TrackingMetrics::TrackingMetrics(double duration_s, double window_s)
    : window_start_s_(std::max(0.0, duration_s - window_s) - kTimeSlackS), whole_run_(duration_s <= window_s)
{
}

void TrackingMetrics::add_error_sample(double t_s, double error_m)
{
    final_error_m_ = error_m;
    if (t_s >= window_start_s_) {
        window_sum_sq_ += error_m * error_m;
        ++window_count_;
    }
}

void TrackingMetrics::add_command(const double* turn_rate_radps, std::size_t robot_count, bool fault, bool regularized)
{
    ++commands_;
    regularized_ += regularized ? 1u : 0u;
    faults_ += fault ? 1u : 0u;
    for (std::size_t r = 0; r < robot_count; ++r) {
        max_abs_omega_radps_ = std::max(max_abs_omega_radps_, std::abs(turn_rate_radps[r]));
    }
}

double TrackingMetrics::rms_error_window_m() const
{
    return window_count_ > 0 ? std::sqrt(window_sum_sq_ / static_cast<double>(window_count_)) : 0.0;
}

}  // namespace tvo_host
