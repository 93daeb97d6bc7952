// The three studies of issue 4 on the chain testbed: error vs h (with delays, compensation and the
// ZOH-aware mode), stability edges (lifted closed loop and simulation), RMS error vs noise.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace study {

struct StudyOptions {
    bool quick = false;        // fewer h / sigma / T_f values, coarser sweeps (the CTest)
    unsigned threads = 2;
    uint64_t seed = 1;         // noise seed (the same for every noise configuration)
    int subsamples = 20;       // dense error points per interval (study 1 and 2)
    double u_budget = 1.0;     // command-noise budget (m/s^2, RMS of |u - y_d''|) for the constrained T_f
};

// One timing variant of the k = 2 loop and everything measured about it.
struct Curve {
    std::string name;
    std::string label;
    double tau_frac = 0.0;
    bool compensation = false;
    bool zoh_aware = false;
    // study 1
    std::vector<double> h_s;
    std::vector<double> err_m;        // NaN where diverged
    std::vector<uint8_t> diverged;
    std::vector<uint8_t> unstable;    // h at or beyond the exact edge (rho >= 1), diverged visibly or not
    double fit_lo_s = 0.0, fit_hi_s = 0.0;
    double order = 0.0;               // least-squares slope of log err vs log h over [fit_lo, fit_hi]
    int fit_points = 0;
    std::vector<double> ratio_to_tau0;  // per h (NaN where either diverged)
    double small_h_ratio = 0.0;       // geometric mean of ratio_to_tau0 over h <= small_h_max
    // study 2
    double edge_exact_s = 0.0;
    double edge_sim_s = 0.0;          // smallest h of the sweep whose 20 s run diverges
    double edge_sim_long_s = 0.0;     // the same with 200 s runs
    double edge_sim_1e3_s = 0.0;      // 20 s runs, threshold |e| > 1e3 |e(0)| (what matches the paper)
    bool sim_monotone = true;         // every h above edge_sim_s in the sweep diverged too
    uint64_t not_ok_steps = 0;        // controller steps that did not apply a new command (stable runs)
};

struct NoiseConfig {
    std::string name;
    int k = 2;
    bool filtered = false;
    double tf_s = 0.0;
    std::vector<double> sigma_m;
    std::vector<double> rms_m;        // NaN where diverged
    double floor_m = 0.0;             // sigma = 0
    double predicted_floor_m = 0.0;   // continuous-time prediction of the bias (filter lag) part
};

struct Study1Result {
    std::vector<Curve> curves;
    double baseline_m = 0.0;
    double small_h_max_s = 0.0;
    double wall_s = 0.0;
};

struct Study3Result {
    double h_s = 1e-3;
    std::vector<NoiseConfig> configs;
    // noise-aware T_f (k = 2, sigma = best_sigma)
    double best_sigma_m = 1e-2;
    std::vector<double> tf_grid_s, tf_grid_rms_m, tf_grid_udev;
    double best_tf_s = 0.0, best_rms_m = 0.0, best_udev = 0.0;
    bool best_at_lower_bound = false;
    // the same with the command's RMS deviation from the feedforward held to u_budget
    double u_budget = 0.0;
    double budget_tf_s = 0.0, budget_rms_m = 0.0, budget_udev = 0.0;
    double wall_s = 0.0;
};

// Runs fn(0) .. fn(n - 1) on `threads` threads; on a terminal, a progress line names `what` (n of N).
void parallel_for(const std::string &what, size_t n, unsigned threads, const std::function<void(size_t)> &fn);

Study1Result run_study1(const StudyOptions &opt);
double run_study2(const StudyOptions &opt, Study1Result &s1);  // fills the edges; returns wall time
Study3Result run_study3(const StudyOptions &opt);

void print_study1(const Study1Result &r);
void print_study2(const Study1Result &r);
void print_study3(const Study3Result &r);

nlohmann::json to_json(const Curve &c);
nlohmann::json to_json(const NoiseConfig &c);

}  // namespace study
