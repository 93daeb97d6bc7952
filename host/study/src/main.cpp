// tvo_study: the sampled-data fidelity study of issue 4 on the paper's integrator-chain testbed.
// Runs the firmware's chain controller in-process against an exact plant; prints a table per study
// and (--json) writes the full tables plus the headline figures.
#include <CLI/CLI.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "chain_sim.hpp"
#include "studies.hpp"

extern "C" {
#include "tvo/status.h"
}

namespace {

// "k=2,h=0.01,tau=0.5,comp=0,zoh=0,filtered=0,tf=0.05,sigma=0,seed=1" -> SimConfig (tau as a fraction of h).
bool parse_trace_config(const std::string &text, study::SimConfig &cfg, std::string &err)
{
    std::map<std::string, double> v{{"k", 2},        {"h", 0.01},   {"tau", 0.5}, {"comp", 0}, {"zoh", 0},
                                    {"filtered", 0}, {"tf", 0.05}, {"sigma", 0}, {"seed", 1}};
    std::stringstream ss(text);
    std::string item;
    while (std::getline(ss, item, ',')) {
        const size_t eq = item.find('=');
        if (eq == std::string::npos || v.find(item.substr(0, eq)) == v.end()) {
            err = "bad --trace-config item '" + item + "'";
            return false;
        }
        try {
            v[item.substr(0, eq)] = std::stod(item.substr(eq + 1));
        } catch (const std::exception &) {
            err = "bad number in --trace-config item '" + item + "'";
            return false;
        }
    }
    if (!(v["k"] >= 1 && v["k"] <= 3) || !(v["h"] > 0 && v["h"] <= 1) || !(v["tau"] >= 0 && v["tau"] <= 1)) {
        err = "--trace-config needs k in 1..3, 0 < h <= 1, 0 <= tau <= 1 (fraction of h)";
        return false;
    }
    cfg.k = static_cast<int>(v["k"]);
    const double half = std::round(v["h"] * 1e6 / 2.0);
    cfg.period_ticks = static_cast<uint32_t>(std::max(1.0, half) * 2.0);
    cfg.delay_ticks = static_cast<uint32_t>(std::llround(static_cast<double>(cfg.period_ticks) * v["tau"]));
    cfg.compensation = v["comp"] != 0;
    cfg.zoh_aware = v["zoh"] != 0;
    cfg.filtered = v["filtered"] != 0;
    cfg.filter_tf_s = v["tf"];
    cfg.sigma_m = v["sigma"];
    cfg.seed = static_cast<uint64_t>(v["seed"]);
    return true;
}

int write_trace(const std::string &path, const std::string &config_text)
{
    study::SimConfig cfg;
    std::string err;
    if (!parse_trace_config(config_text, cfg, err)) {
        std::fprintf(stderr, "tvo_study: %s\n", err.c_str());
        return 2;
    }
    std::vector<study::TraceRow> rows;
    const study::SimResult res = study::run_chain(cfg, &rows);
    std::FILE *f = std::fopen(path.c_str(), "w");
    if (f == nullptr) {
        std::fprintf(stderr, "tvo_study: cannot write %s\n", path.c_str());
        return 1;
    }
    std::fprintf(f, "# tvo_study trace: %s; period_ticks=%u delay_ticks=%u tick_hz=%u; max_err_m=%.9e diverged=%d\n",
                 config_text.c_str(), cfg.period_ticks, cfg.delay_ticks, cfg.tick_hz, res.max_err_m,
                 res.diverged ? 1 : 0);
    std::fprintf(f, "step,apply_tick,stamp_tick,y0_meas,y1_meas,u0_hex,u1_hex,u0,u1,status,flags\n");
    for (const study::TraceRow &r : rows) {
        std::fprintf(f, "%llu,%u,%u,%a,%a,%a,%a,%.9g,%.9g,%d,0x%x\n", static_cast<unsigned long long>(r.step),
                     r.apply_tick, r.stamp_tick, r.measured[0], r.measured[1], static_cast<double>(r.u[0]),
                     static_cast<double>(r.u[1]), static_cast<double>(r.u[0]), static_cast<double>(r.u[1]), r.status,
                     r.flags);
    }
    std::fclose(f);
    std::printf("trace: %zu commands of [%s] written to %s\n", rows.size(), config_text.c_str(), path.c_str());
    return 0;
}

}  // namespace

int main(int argc, char **argv)
{
    CLI::App app{"tvo_study: sampled-data fidelity of the TV-O chain controller (issue 4): error vs h, "
                 "stability edges, noise"};
    study::StudyOptions opt;
    std::string json_path, trace_path, trace_config = "k=2,h=0.01,tau=0.5,comp=0,zoh=0";
    std::string studies = "1,2,3";
    opt.threads = std::max(1u, std::thread::hardware_concurrency());
    app.add_option("--json", json_path, "write the full tables and headline figures as JSON to this file");
    app.add_flag("--quick", opt.quick, "fewer h / sigma / T_f values and a coarser edge sweep (seconds)");
    app.add_option("--threads", opt.threads, "worker threads (results do not depend on it)")->check(CLI::Range(1u, 64u));
    app.add_option("--seed", opt.seed, "noise seed (std::mt19937_64)");
    app.add_option("--subsamples", opt.subsamples, "dense error points per held interval (study 1)")
        ->check(CLI::Range(1, 1000));
    app.add_option("--u-budget", opt.u_budget,
                   "command-noise budget (RMS |u - y_d''|, m/s^2) for the constrained noise-aware T_f")
        ->check(CLI::PositiveNumber);
    app.add_option("--studies", studies, "which studies to run, e.g. 1,3 (2 needs 1); empty: none");
    app.add_option("--trace", trace_path, "also write the command sequence of one configuration (CSV, hex floats)");
    app.add_option("--trace-config", trace_config,
                   "that configuration: k=,h=,tau= (fraction of h),comp=,zoh=,filtered=,tf=,sigma=,seed=");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    }
    const bool s1 = studies.find('1') != std::string::npos;
    const bool s2 = studies.find('2') != std::string::npos;
    const bool s3 = studies.find('3') != std::string::npos;
    if (s2 && !s1) {
        std::fprintf(stderr, "tvo_study: study 2 needs study 1 (--studies 1,2)\n");
        return 2;
    }
    const auto t0 = std::chrono::steady_clock::now();
    try {
        if (!trace_path.empty()) {
            const int rc = write_trace(trace_path, trace_config);
            if (rc != 0) {
                return rc;
            }
        }
        nlohmann::json out;
        out["testbed"] = {{"k", 2},
                          {"poles", -1.6},
                          {"omega_radps", study::paper_omega()},
                          {"y0", {2.0, 0.0}},
                          {"duration_s", 20.0},
                          {"window_s", 10.0},
                          {"tick_hz", 1000000},
                          {"core", TVO_USE_DOUBLE ? "double" : "float32"},
                          {"quick", opt.quick},
                          {"seed", opt.seed},
                          {"subsamples", opt.subsamples},
                          {"timing", "u_n applied at t_n, held over [t_n, t_n+h); computed from y sampled at t_n - tau; "
                                     "uncompensated: law evaluated at the sample instant with the sampled state"}};
        study::Study1Result r1;
        if (s1) {
            r1 = study::run_study1(opt);
            study::print_study1(r1);
            if (s2) {
                const double w2 = study::run_study2(opt, r1);
                study::print_study2(r1);
                std::printf("study 2 wall time: %.1f s\n", w2);
                out["study2_wall_s"] = w2;
            }
            nlohmann::json curves = nlohmann::json::array();
            for (const study::Curve &c : r1.curves) {
                curves.push_back(study::to_json(c));
            }
            out["study1"] = {{"continuous_baseline_m", r1.baseline_m},
                             {"small_h_max_s", r1.small_h_max_s},
                             {"curves", curves},
                             {"wall_s", r1.wall_s}};
            auto find = [&](const std::string &name) -> const study::Curve & {
                for (const study::Curve &c : r1.curves) {
                    if (c.name == name) {
                        return c;
                    }
                }
                throw std::runtime_error("no curve " + name);
            };
            auto num = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
            const study::Curve &c0 = find("tau0"), &ch = find("tau_half"), &cf = find("tau_full");
            const study::Curve &kh = find("comp_tau_half"), &kf = find("comp_tau_full"), &z = find("zoh_tau0");
            nlohmann::json per_tau = nlohmann::json::array();
            for (const study::Curve *c : {&c0, &ch, &cf}) {
                per_tau.push_back(study::to_json(*c));
            }
            out["per_tau"] = per_tau;
            out["compensated"] = {study::to_json(kh), study::to_json(kf)};
            out["zoh_aware"] = {study::to_json(z), study::to_json(find("zoh_comp_tau_full"))};
            out["order_tau0"] = num(c0.order);
            out["ratio_tau_half"] = num(ch.small_h_ratio);
            out["ratio_tau_full"] = num(cf.small_h_ratio);
            out["comp_ratio_tau_half"] = num(kh.small_h_ratio);
            out["comp_ratio_tau_full"] = num(kf.small_h_ratio);
            out["zoh_aware_order"] = num(z.order);
            if (s2) {
                out["edge_exact_s"] = {num(c0.edge_exact_s), num(ch.edge_exact_s), num(cf.edge_exact_s)};
                out["edge_sim_s"] = {num(c0.edge_sim_s), num(ch.edge_sim_s), num(cf.edge_sim_s)};
                out["comp_edge_exact_s"] = {num(c0.edge_exact_s), num(kh.edge_exact_s), num(kf.edge_exact_s)};
                out["comp_edge_sim_s"] = {num(c0.edge_sim_s), num(kh.edge_sim_s), num(kf.edge_sim_s)};
                out["edge_sim_threshold_1e3_s"] = {num(c0.edge_sim_1e3_s), num(ch.edge_sim_1e3_s), num(cf.edge_sim_1e3_s)};
                out["paper_edge_s"] = {0.69, 0.63, 0.33};
            }
            uint64_t not_ok = 0;
            for (const study::Curve &c : r1.curves) {
                not_ok += c.not_ok_steps;
            }
            if (not_ok != 0) {
                std::fprintf(stderr, "tvo_study: WARNING: %llu controller steps returned a status other than TVO_OK\n",
                             static_cast<unsigned long long>(not_ok));
            }
        }
        if (s3) {
            const study::Study3Result r3 = study::run_study3(opt);
            study::print_study3(r3);
            nlohmann::json cfgs = nlohmann::json::array();
            const study::NoiseConfig *k2 = nullptr, *k3 = nullptr;
            for (const study::NoiseConfig &c : r3.configs) {
                cfgs.push_back(study::to_json(c));
                if (c.filtered && std::fabs(c.tf_s - 0.05) < 1e-12) {
                    (c.k == 2 ? k2 : k3) = &c;
                }
            }
            nlohmann::json grid = nlohmann::json::array();
            for (size_t i = 0; i < r3.tf_grid_s.size(); ++i) {
                grid.push_back({{"tf_s", r3.tf_grid_s[i]},
                                {"rms_m", std::isfinite(r3.tf_grid_rms_m[i]) ? nlohmann::json(r3.tf_grid_rms_m[i])
                                                                             : nlohmann::json(nullptr)},
                                {"u_dev_rms_mps2", std::isfinite(r3.tf_grid_udev[i]) ? nlohmann::json(r3.tf_grid_udev[i])
                                                                                     : nlohmann::json(nullptr)}});
            }
            out["study3"] = {{"h_s", r3.h_s},
                             {"tau_s", 0.0},
                             {"noise", "Gaussian on the measured position, per axis; exact derivatives noise-free"},
                             {"configs", cfgs},
                             {"tf_search",
                              {{"k", 2},
                               {"sigma_m", r3.best_sigma_m},
                               {"range_s", {r3.tf_grid_s.front(), r3.tf_grid_s.back()}},
                               {"grid", grid},
                               {"best_tf_s", r3.best_tf_s},
                               {"best_rms_m", r3.best_rms_m},
                               {"best_u_dev_rms_mps2", r3.best_udev},
                               {"best_at_lower_bound", r3.best_at_lower_bound},
                               {"u_budget_mps2", r3.u_budget},
                               {"budget_tf_s", std::isfinite(r3.budget_tf_s) ? nlohmann::json(r3.budget_tf_s) : nlohmann::json(nullptr)},
                               {"budget_rms_m", std::isfinite(r3.budget_rms_m) ? nlohmann::json(r3.budget_rms_m) : nlohmann::json(nullptr)},
                               {"budget_u_dev_rms_mps2", std::isfinite(r3.budget_udev) ? nlohmann::json(r3.budget_udev) : nlohmann::json(nullptr)}}},
                             {"wall_s", r3.wall_s}};
            if (k2 != nullptr && k3 != nullptr) {
                out["floor_k2_tf005"] = k2->floor_m;
                out["floor_k3_tf005"] = k3->floor_m;
                out["floor_ratio_k3_k2_tf005"] = k3->floor_m / k2->floor_m;
                out["predicted_floor_ratio_k3_k2_tf005"] = k3->predicted_floor_m / k2->predicted_floor_m;
                std::printf("floor ratio k=3 / k=2 at T_f = 0.05 s: %.4f (paper: 1.8; continuous prediction %.4f)\n",
                            k3->floor_m / k2->floor_m, k3->predicted_floor_m / k2->predicted_floor_m);
            }
            out["best_tf_s"] = r3.best_tf_s;
            out["best_rms_m"] = r3.best_rms_m;
            out["best_tf_at_lower_bound"] = r3.best_at_lower_bound;
            out["budget_tf_s"] = std::isfinite(r3.budget_tf_s) ? nlohmann::json(r3.budget_tf_s) : nlohmann::json(nullptr);
            out["budget_rms_m"] = std::isfinite(r3.budget_rms_m) ? nlohmann::json(r3.budget_rms_m) : nlohmann::json(nullptr);
        }
        const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        out["wall_s"] = wall;
        out["threads"] = opt.threads;
        std::printf("\ntotal wall time: %.1f s (%u threads)\n", wall, opt.threads);
        if (!json_path.empty()) {
            std::ofstream f(json_path);
            if (!f) {
                std::fprintf(stderr, "tvo_study: cannot write %s\n", json_path.c_str());
                return 1;
            }
            f << out.dump(2) << "\n";
            std::printf("JSON: %s\n", json_path.c_str());
        }
    } catch (const std::exception &e) {
        std::fprintf(stderr, "tvo_study: ERROR: %s\n", e.what());
        return 1;
    }
    return 0;
}
