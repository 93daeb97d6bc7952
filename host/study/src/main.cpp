// tvo_study: the sampled-data fidelity study of issue 4 on the paper's integrator-chain testbed.
// Runs the firmware's chain controller in-process against an exact plant; prints a table per study
// and (--json) writes the full tables plus the headline figures.
#include <CLI/CLI.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "chain_sim.hpp"
// The ranges of numeric options, shared with tvo_sim (host/study builds without host/src on its include path).
#include "../../src/option_ranges.hpp"
#include "../../src/command_line.hpp"
#include "studies.hpp"

extern "C" {
#include "tvo/status.h"
}

namespace {

using tvo_options::add_ranged;
using tvo_options::Default;
using tvo_options::End;
using tvo_options::real_in;
using tvo_options::whole_in;

constexpr const char* kProgram = "tvo_study";

// The trace's configuration is 20 s of the testbed (SimConfig::duration_s); h >= 0.1 ms keeps its CSV
// within 200,000 rows (25 MB measured). Noise, filter and budget bounds: host/README.md, "Options".
constexpr double kMinTraceH = 1e-4;
constexpr double kMaxTraceH = 1.0;
constexpr double kMaxFilterTfS = 10.0;
constexpr double kMaxSigmaM = 1.0;
constexpr double kMaxUBudget = 1000.0;
constexpr unsigned kMaxThreads = 64;

// One key of --trace-config: its type and range as --help shows them, and its default.
struct TraceKey {
    const char *name;
    const char *type;
    CLI::Validator check;
    const char *note;
    const char *default_value;
};

const std::vector<TraceKey> &trace_keys()
{
    static const std::vector<TraceKey> keys{
        {"k", "INT", whole_in<int>(1, 3), "relative degree", "2"},
        {"h", "FLOAT", real_in({kMinTraceH, kMaxTraceH, "s"}), "whole, even microseconds", "0.01"},
        {"tau", "FLOAT", real_in({0.0, 1.0, ""}), "fraction of h", "0.5"},
        {"comp", "INT", whole_in<int>(0, 1), "delay compensation", "0"},
        {"zoh", "INT", whole_in<int>(0, 1), "ZOH-aware", "0"},
        {"filtered", "INT", whole_in<int>(0, 1), "derivatives filtered", "0"},
        {"tf", "FLOAT", real_in({0.0, kMaxFilterTfS, "s", End::Open}), "filter T_f", "0.05"},
        {"sigma", "FLOAT", real_in({0.0, kMaxSigmaM, "m"}), "position noise", "0"},
        {"seed", "UINT", whole_in<uint64_t>(0, std::numeric_limits<uint64_t>::max()), "noise seed", "1"}};
    return keys;
}

std::string trace_keys_help()
{
    std::string out;
    for (const TraceKey &key : trace_keys()) {
        out += std::string(out.empty() ? "" : ", ") + key.name + "=" + key.type + " " + key.check.get_description() +
               " (" + key.note + ")";
    }
    return out;
}

// "k=2,h=0.01,tau=0.5,comp=0,zoh=0,filtered=0,tf=0.05,sigma=0,seed=1" (any subset, any order) -> SimConfig.
bool parse_trace_config(const std::string &text, study::SimConfig &cfg, std::string &err)
{
    std::map<std::string, std::string> v;
    for (const TraceKey &key : trace_keys()) {
        v[key.name] = key.default_value;
    }
    std::stringstream ss(text);
    std::string item;
    while (!text.empty() && std::getline(ss, item, ',')) {
        const size_t eq = item.find('=');
        const std::string name = item.substr(0, eq);
        const auto key = std::find_if(trace_keys().begin(), trace_keys().end(),
                                      [&name](const TraceKey &k) { return name == k.name; });
        if (eq == std::string::npos || key == trace_keys().end()) {
            err = "item '" + item + "' is not KEY=VALUE with a key of: " + trace_keys_help();
            return false;
        }
        std::string value = item.substr(eq + 1);
        const std::string why = key->check(value);
        if (!why.empty()) {
            err = "item '" + item + "': " + why;
            return false;
        }
        v[name] = value;
    }
    if (!text.empty() && text.back() == ',') {
        err = "an empty item at the end";
        return false;
    }
    double h_s = 0.0, tau = 0.0, tf_s = 0.0, sigma_m = 0.0;
    int k = 0, comp = 0, zoh = 0, filtered = 0;
    uint64_t seed = 0;
    // Checked above (or defaults): these conversions succeed.
    tvo_options::read_real(v["h"], &h_s);
    tvo_options::read_real(v["tau"], &tau);
    tvo_options::read_real(v["tf"], &tf_s);
    tvo_options::read_real(v["sigma"], &sigma_m);
    tvo_options::read_whole(v["k"], &k);
    tvo_options::read_whole(v["comp"], &comp);
    tvo_options::read_whole(v["zoh"], &zoh);
    tvo_options::read_whole(v["filtered"], &filtered);
    tvo_options::read_whole(v["seed"], &seed);
    // Even ticks (1 tick = 1 us) so that tau = h/2 lands on a tick.
    const double h_us = h_s * static_cast<double>(cfg.tick_hz);
    const long long h_ticks = std::llround(h_us);
    if (std::fabs(h_us - static_cast<double>(h_ticks)) > 1e-3 || h_ticks % 2 != 0) {
        err = "item 'h=" + v["h"] + "': must be a whole, even number of microseconds";
        return false;
    }
    cfg.k = k;
    cfg.period_ticks = static_cast<uint32_t>(h_ticks);
    cfg.delay_ticks = static_cast<uint32_t>(std::llround(static_cast<double>(cfg.period_ticks) * tau));
    cfg.compensation = comp != 0;
    cfg.zoh_aware = zoh != 0;
    cfg.filtered = filtered != 0;
    cfg.filter_tf_s = tf_s;
    cfg.sigma_m = sigma_m;
    cfg.seed = seed;
    return true;
}

// --studies: a comma-separated subset of 1, 2, 3; empty runs none.
bool parse_studies(const std::string &text, std::set<int> &chosen)
{
    chosen.clear();
    std::stringstream ss(text);
    std::string item;
    while (!text.empty() && std::getline(ss, item, ',')) {
        if (item != "1" && item != "2" && item != "3") {
            return false;
        }
        chosen.insert(item[0] - '0');
    }
    return text.empty() || text.back() != ',';
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
    app.footer("Every number is checked against the range shown ('(' or ')': that end excluded) before anything "
               "runs; a bad value exits with code 2 and names the option. host/README.md (\"Options\") says why.");
    study::StudyOptions opt;
    std::string json_path, trace_path, trace_config = "k=2,h=0.01,tau=0.5,comp=0,zoh=0";
    std::string studies = "1,2,3";
    opt.threads = std::min(kMaxThreads, std::max(1u, std::thread::hardware_concurrency()));
    app.add_option("--json", json_path, "write the full tables and headline figures as JSON to this file");
    app.add_flag("--quick", opt.quick, "fewer h / sigma / T_f values and a coarser edge sweep (seconds)");
    add_ranged(app, "--threads", opt.threads, "worker threads (results do not depend on it)",
               whole_in<unsigned>(1, kMaxThreads), Default::NotShown);
    add_ranged(app, "--seed", opt.seed, "noise seed (std::mt19937_64)",
               whole_in<uint64_t>(0, std::numeric_limits<uint64_t>::max()));
    add_ranged(app, "--subsamples", opt.subsamples, "dense error points per held interval (study 1)",
               whole_in<int>(1, 1000));
    add_ranged(app, "--u-budget", opt.u_budget,
               "command-noise budget (RMS |u - y_d''|, m/s^2) for the constrained noise-aware T_f",
               real_in({0.0, kMaxUBudget, "m/s^2", End::Open}));
    app.add_option("--studies", studies, "which studies to run, e.g. 1,3 (2 needs 1); empty: none")
        ->check(CLI::Validator(
            [](std::string &text) {
                std::set<int> chosen;
                return parse_studies(text, chosen) ? std::string()
                                                   : "got '" + text + "', expected a comma-separated list of 1, 2, 3";
            },
            "subset of 1,2,3"))
        ->capture_default_str();
    app.add_option("--trace", trace_path, "also write the command sequence of one configuration (CSV, hex floats)");
    app.add_option("--trace-config", trace_config, "that configuration, KEY=VALUE items: " + trace_keys_help())
        ->check(CLI::Validator(
            [](std::string &text) {
                study::SimConfig cfg;
                std::string err;
                return parse_trace_config(text, cfg, err) ? std::string() : err;
            },
            "KEY=VALUE,..."))
        ->capture_default_str();
    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    std::set<int> chosen;
    parse_studies(studies, chosen);
    const bool s1 = chosen.count(1) > 0;
    const bool s2 = chosen.count(2) > 0;
    const bool s3 = chosen.count(3) > 0;
    if (s2 && !s1) {
        return tvo_options::option_error(kProgram, "--studies", "study 2 needs study 1 (--studies 1,2)");
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
