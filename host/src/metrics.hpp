// Run metrics: tracking error (final, RMS over the last seconds), largest turn rate, faults.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tvo_host {

/// The RMS error's window: the last 5 s of a run, the whole run if it is not longer.
constexpr double kRmsWindowS = 5.0;

class TrackingMetrics {
public:
    /// Errors sampled at t >= duration_s - window_s enter the RMS (all of them if the run is shorter).
    TrackingMetrics(double duration_s, double window_s);

    /// Tracking error at t_s: the largest distance of a robot from its target (metres).
    void add_error_sample(double t_s, double error_m);

    /// One command received from the firmware: its turn rates, whether it reports a fault and whether
    /// its solve regularised an indefinite Hessian (TVO_FLAG_REGULARIZED).
    void add_command(const double* turn_rate_radps, std::size_t robot_count, bool fault, bool regularized = false);

    double final_error_m() const { return final_error_m_; }
    double rms_error_window_m() const;
    /// True if the window covers the whole run (a run of at most window_s).
    bool rms_whole_run() const { return whole_run_; }
    double max_abs_omega_radps() const { return max_abs_omega_radps_; }
    std::uint64_t faults() const { return faults_; }
    std::uint64_t commands() const { return commands_; }
    std::uint64_t regularized() const { return regularized_; }

private:
    double window_start_s_;
    bool whole_run_;
    double final_error_m_{0.0};
    double window_sum_sq_{0.0};
    std::uint64_t window_count_{0};
    double max_abs_omega_radps_{0.0};
    std::uint64_t faults_{0};
    std::uint64_t commands_{0};
    std::uint64_t regularized_{0};
};

}  // namespace tvo_host
