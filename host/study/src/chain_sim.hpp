// Closed loop of the firmware's chain controller (tvo_core, float32 by default) with an exact
// double-precision integrator-chain plant y^(k) = u, y in R^2, on the paper's testbed
// (f0 = 1/2 |y - y_d|^2, y_d = (cos wt, sin wt), all poles at -1.6, y(0) = (2, 0) at rest).
//
// Timing (ticks, as in the firmware): the command u_n is applied at t_n = n h and held over
// [t_n, t_{n+1}); it is computed from the plant sampled at t_n - tau (before t = 0 the plant rests at
// y(0), so the first sample is y(0) for any tau). The plant moves by its exact polynomial flow.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace study {

struct SimConfig {
    int k = 2;                       // relative degree, 1..3
    uint32_t tick_hz = 1000000u;     // 1 tick = 1 us
    uint32_t period_ticks = 10000u;  // h
    uint32_t delay_ticks = 0u;       // tau, 0..h
    bool compensation = false;       // firmware delay compensation
    bool zoh_aware = false;          // firmware ZOH-aware (mid-interval) evaluation
    bool filtered = false;           // derivatives from the firmware's dirty-derivative filters
    double filter_tf_s = 0.05;
    double sigma_m = 0.0;            // Gaussian noise on the measured position (std, per axis)
    uint64_t seed = 1u;              // std::mt19937_64 seed of the noise
    double pole = 1.6;               // all closed-loop poles at -pole
    double omega_radps = 0.0;        // 0: 2 pi / 10
    double duration_s = 20.0;        // T
    double window_s = 10.0;          // metrics over [T - window, T] (the last target period)
    int subsamples = 20;             // dense error points per held interval inside the window
    double diverge_factor = 10.0;    // |e| > factor |e(0)| (or non-finite) anywhere: diverged
};

struct SimResult {
    double max_err_m = 0.0;    // worst |y - y_d| over the window (dense)
    double rms_err_m = 0.0;    // RMS of |y - y_d| over the same points
    double u_dev_rms = 0.0;    // RMS over the window's commands of |u_n - y_d^(k)(t_n)| (effort beyond feedforward)
    bool diverged = false;
    double diverged_at_s = 0.0;
    double peak_ratio = 0.0;   // max |e| / |e(0)| seen (interval starts, dense points); inf if non-finite
    uint64_t steps = 0;        // controller steps taken
    uint64_t not_ok = 0;       // steps that did not apply a new command (should stay 0)
    int first_bad_status = 0;  // its call error, or 100 + the reason it held or stopped
};

// One controller step, for --trace (the command as the firmware produced it).
struct TraceRow {
    uint64_t step;
    uint32_t apply_tick;
    uint32_t stamp_tick;
    double measured[2];
    double rate[2];     // y' at the sample (sent when derivatives are measured)
    double accel[2];    // y'' at the sample (k = 3)
    float u[2];
    int status;
    uint32_t flags;
};

// a_0..a_{k-1} of (s + pole)^k = s^k + a_{k-1} s^{k-1} + ... + a_0.
std::vector<double> chain_gains(int k, double pole);

// Runs one configuration. Throws std::runtime_error if the controller rejects the configuration.
SimResult run_chain(const SimConfig &cfg, std::vector<TraceRow> *trace = nullptr);

// Continuous-time baseline: the continuous closed loop y^(k) = y_d^(k) - sum a_i (y^(i) - y_d^(i)),
// integrated with classical RK4 at step dt_s; worst |e| over the same window (at every RK step).
double continuous_baseline(int k, double pole, double omega_radps, double duration_s, double window_s, double dt_s);

// Steady-state |e| of the continuous loop on the circle (radius 1) with derivatives from D = s/(T_f s+1)
// (cascaded: D^i for y^(i)), or exact (tf_s = 0): |sum a_i ((jw)^i - D_i)| / |(jw)^k + sum a_i D_i|.
double predicted_bias_floor(int k, double pole, double omega_radps, double tf_s);

double paper_omega();

}  // namespace study
