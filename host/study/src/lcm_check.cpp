// tvo_study_lcm_check: one configuration of the study run twice — in-process (the chain controller
// linked into this program) and over LCM (the same float32 core inside tvo_firmware_node, session
// PLANT_CHAIN) — and the two command sequences compared bit for bit.
//
// The LCM run replays the in-process run's measurements (same stamps; positions as doubles and
// derivatives as floats on the wire, chain_sample_t, which the float32 core reads as the in-process run
// does) and waits for each answer (chain_command_t). Session CLOCK_PLANT: step n is sampled at
// epoch + n h - tau and numbered n, so it serves the node's period n (lcm_types/README.md, "Timing"). As
// long as every command matches bit for bit, the plant of a closed LCM loop would see exactly these
// measurements, so the replay is the closed loop; the first differing command would end that
// equivalence and is reported. The START names the node's boot, heard on TVO_NODE (the plant's rule 1).
//
// Exit code 0 when every command (and status) is identical, 1 otherwise or on errors, 2 on bad usage.
#include <unistd.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>

#include "chain_sim.hpp"
#include "tvo_lcm/chain_command_t.hpp"
#include "tvo_lcm/chain_sample_t.hpp"
#include "tvo_lcm/node_status_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"

extern "C" {
#include "channels.h"
}

extern char **environ;

namespace {

constexpr int64_t kEpochUs = 1000000;  // chain_sim's epoch tick (1 tick = 1 us)
// Every wait for the node: its START ack, each answer, the STOP ack and its exit.
constexpr auto kAnswerTimeout = std::chrono::seconds(2);
constexpr auto kStartTimeout = std::chrono::seconds(5);
constexpr int kStartRepeatMs = 100;  // START repeated until acked (the node may not be listening yet)

struct Listener {
    int32_t session_id = 0;
    int64_t boot_id = 0;  // the node's, from its announcements (the newest boot of a node of every robot)
    int8_t awaited_action = tvo_lcm::session_t::ACTION_START;
    bool acked = false;
    int32_t ack_status = -1;
    int64_t answered = -1;
    tvo_lcm::chain_command_t last{};
    void on_node(const lcm::ReceiveBuffer *, const std::string &, const tvo_lcm::node_status_t *node)
    {
        if (node->protocol_version == tvo_lcm::node_status_t::PROTOCOL_VERSION && node->own_robot == -1 &&
            node->boot_id > boot_id) {
            boot_id = node->boot_id;
        }
    }
    void on_ack(const lcm::ReceiveBuffer *, const std::string &, const tvo_lcm::session_ack_t *ack)
    {
        if (ack->session_id == session_id && ack->action == awaited_action && ack->boot_id == boot_id) {
            acked = true;
            ack_status = ack->status;
        }
    }
    void on_command(const lcm::ReceiveBuffer *, const std::string &, const tvo_lcm::chain_command_t *cmd)
    {
        // Only our session's answers to what we sent (a sequence beyond ours is nobody's answer).
        if (cmd->header.session_id == session_id && cmd->header.measurement_sequence > answered) {
            answered = cmd->header.measurement_sequence;
            last = *cmd;
        }
    }
};

/// Waits for the child to exit up to timeout; kills it after that. Its wait status, or -1.
int reap(pid_t child, std::chrono::steady_clock::duration timeout)
{
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    int status = 0;
    while (waitpid(child, &status, WNOHANG) == 0) {
        if (std::chrono::steady_clock::now() >= deadline) {
            kill(child, SIGKILL);
            waitpid(child, &status, 0);
            return -1;
        }
        usleep(10000);
    }
    return status;
}

bool same_bits(float a, float b)
{
    return std::memcmp(&a, &b, sizeof(a)) == 0;
}

}  // namespace

int main(int argc, char **argv)
{
    CLI::App app{"tvo_study_lcm_check: one study configuration in-process and over LCM, compared bit for bit"};
    study::SimConfig cfg;
    double h_s = 0.01;
    double tau_frac = 0.5;
    std::string firmware;
    std::string url;
    std::string json_path;
    std::string boot_file;
    double duration_s = 20.0;
    app.add_option("--k", cfg.k, "relative degree")->check(CLI::Range(1, 3));
    app.add_option("--h", h_s, "sampling period, s")->check(CLI::Range(1e-4, 1.0));
    app.add_option("--tau", tau_frac, "computation delay as a fraction of h")->check(CLI::Range(0.0, 1.0));
    app.add_flag("--comp", cfg.compensation, "delay compensation on");
    app.add_flag("--zoh", cfg.zoh_aware, "ZOH-aware evaluation");
    app.add_option("--duration-s", duration_s, "simulated time")->check(CLI::PositiveNumber);
    app.add_option("--firmware", firmware, "tvo_firmware_node to spawn")->required();
    app.add_option("--lcm-url", url, "LCM URL (default: LCM's)");
    app.add_option("--json", json_path, "write the outcome as JSON here");
    app.add_option("--boot-file", boot_file, "the spawned node's boot counter file (its --boot-file)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return app.exit(e);
    }
    cfg.period_ticks = static_cast<uint32_t>(std::llround(h_s * 1e6));
    cfg.delay_ticks = static_cast<uint32_t>(std::llround(tau_frac * h_s * 1e6));
    cfg.duration_s = duration_s;
    cfg.window_s = duration_s / 2.0;

    std::vector<study::TraceRow> trace;
    (void)study::run_chain(cfg, &trace);

    lcm::LCM lcm(url);
    if (!lcm.good()) {
        std::fprintf(stderr, "tvo_study_lcm_check: error: cannot create LCM on '%s'\n", url.c_str());
        return 1;
    }
    // The node ends with us if we die before our STOP reaches it.
    std::vector<std::string> child_args = {firmware, "--exit-with-parent"};
    if (!url.empty()) {
        child_args.push_back("--lcm-url");
        child_args.push_back(url);
    }
    if (!boot_file.empty()) {
        child_args.push_back("--boot-file");
        child_args.push_back(boot_file);
    }
    std::vector<char *> child_argv;
    for (std::string &a : child_args) {
        child_argv.push_back(a.data());
    }
    child_argv.push_back(nullptr);
    pid_t child = 0;
    if (posix_spawn(&child, firmware.c_str(), nullptr, nullptr, child_argv.data(), environ) != 0) {
        std::fprintf(stderr, "tvo_study_lcm_check: error: cannot start %s\n", firmware.c_str());
        return 1;
    }

    // Subscribed before the node can announce itself: it was spawned just now, and LCM's socket is open.
    Listener listener;
    listener.session_id = static_cast<int32_t>((getpid() * 1000 + 7) & 0x7fffffff);
    lcm.subscribe(TVO_CHANNEL_NODE, &Listener::on_node, &listener);
    lcm.subscribe(TVO_CHANNEL_SESSION_ACK, &Listener::on_ack, &listener);
    lcm.subscribe(TVO_CHANNEL_CHAIN_COMMAND, &Listener::on_command, &listener);

    tvo_lcm::session_t start{};
    start.utime = kEpochUs;
    start.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
    start.session_id = listener.session_id;
    start.action = tvo_lcm::session_t::ACTION_START;
    start.clock_source = tvo_lcm::session_t::CLOCK_PLANT;
    start.epoch_utime = kEpochUs;
    start.period_us = cfg.period_ticks;
    start.delay_us = cfg.delay_ticks;
    start.delay_compensation = cfg.compensation;
    start.zoh_aware = cfg.zoh_aware;
    start.plant_kind = tvo_lcm::session_t::PLANT_CHAIN;
    start.velocity_source = tvo_lcm::session_t::VELOCITY_FROM_POSE;  // derivatives measured, not filtered
    start.filter_tf_s = cfg.filter_tf_s;
    start.chain_relative_degree = cfg.k;
    const std::vector<double> gains = study::chain_gains(cfg.k, cfg.pole);
    for (size_t i = 0; i < gains.size(); ++i) {
        start.chain_gains[i] = gains[i];
    }
    start.chain_input_max = 1e30;  // as the in-process run: the unsaturated loop
    start.watchdog_periods = 10;
    start.robot_count = 1;
    tvo_lcm::robot_t &robot = start.robot[0];
    robot.tracking_weight[0] = 1.0;
    robot.tracking_weight[1] = 1.0;
    robot.target.kind = tvo_lcm::path_t::KIND_CIRCLE;  // the unit circle at the study's rate
    robot.target.semi_axis_m[0] = 1.0;
    robot.target.semi_axis_m[1] = 1.0;
    robot.target.omega_radps = study::paper_omega();

    int rc = 0;
    const auto deadline = std::chrono::steady_clock::now() + kStartTimeout;
    while (listener.boot_id == 0 && std::chrono::steady_clock::now() < deadline) {
        lcm.handleTimeout(kStartRepeatMs);  // the node announces itself at once, then every 250 ms
    }
    start.node_boot_id[0] = listener.boot_id;
    while (listener.boot_id != 0 && !listener.acked && std::chrono::steady_clock::now() < deadline) {
        lcm.publish(TVO_CHANNEL_SESSION, &start);
        lcm.handleTimeout(kStartRepeatMs);
    }
    uint64_t identical = 0;
    int64_t first_mismatch = -1;
    if (!listener.acked || listener.ack_status != 0) {
        std::fprintf(stderr, "tvo_study_lcm_check: error: the node %s the chain session (status %d)\n",
                     listener.boot_id == 0 ? "did not announce itself for" : "did not accept", listener.ack_status);
        rc = 1;
    } else {
        tvo_lcm::chain_sample_t m{};
        for (const study::TraceRow &row : trace) {
            m.header.utime = row.stamp_tick;
            m.header.session_id = listener.session_id;
            m.header.sequence = static_cast<int32_t>(row.step);
            m.header.robot = 0;
            m.has = tvo_lcm::chain_sample_t::HAS_DERIVATIVES;
            for (int i = 0; i < 2; ++i) {
                m.position_m[i] = row.measured[i];
                m.output_rate_mps[i] = static_cast<float>(row.rate[i]);
                m.output_accel_mps2[i] = static_cast<float>(row.accel[i]);
            }
            lcm.publish(TVO_CHANNEL_CHAIN_SAMPLE, &m);
            const auto wait_until = std::chrono::steady_clock::now() + kAnswerTimeout;
            while (listener.answered < m.header.sequence && std::chrono::steady_clock::now() < wait_until) {
                lcm.handleTimeout(50);
            }
            if (listener.answered < m.header.sequence) {
                std::fprintf(stderr, "tvo_study_lcm_check: error: no answer to sample %d\n", m.header.sequence);
                rc = 1;
                break;
            }
            const bool same = same_bits(listener.last.input[0], row.u[0]) && same_bits(listener.last.input[1], row.u[1]) &&
                              listener.last.header.status == row.status;
            if (same) {
                ++identical;
            } else if (first_mismatch < 0) {
                first_mismatch = m.header.sequence;
                std::fprintf(stderr, "first difference at step %d: LCM %.9g %.9g, in-process %.9g %.9g\n",
                             m.header.sequence, static_cast<double>(listener.last.input[0]),
                             static_cast<double>(listener.last.input[1]), static_cast<double>(row.u[0]),
                             static_cast<double>(row.u[1]));
            }
        }
    }
    // STOP (the node exits after it); repeated until acked, since a lost STOP would leave it running.
    tvo_lcm::session_t stop = start;
    stop.action = tvo_lcm::session_t::ACTION_STOP;
    listener.acked = false;
    listener.awaited_action = tvo_lcm::session_t::ACTION_STOP;
    const auto stop_deadline = std::chrono::steady_clock::now() + kAnswerTimeout;
    while (!listener.acked && std::chrono::steady_clock::now() < stop_deadline) {
        lcm.publish(TVO_CHANNEL_SESSION, &stop);
        lcm.handleTimeout(kStartRepeatMs);
    }
    if (reap(child, kAnswerTimeout) < 0) {
        std::fprintf(stderr, "tvo_study_lcm_check: warning: the node did not exit after STOP; killed it\n");
    }

    const bool all_same = rc == 0 && identical == trace.size();
    std::printf("tvo_study_lcm_check: k=%d h=%g tau=%g*h comp=%d zoh=%d: %llu of %zu commands identical bit for bit%s\n",
                cfg.k, h_s, tau_frac, cfg.compensation ? 1 : 0, cfg.zoh_aware ? 1 : 0,
                static_cast<unsigned long long>(identical), trace.size(), all_same ? "" : " (DIFFERENT)");
    if (!json_path.empty()) {
        nlohmann::json out = {{"commands", trace.size()}, {"identical", identical}, {"first_mismatch", first_mismatch},
                              {"k", cfg.k}, {"h_s", h_s}, {"tau_fraction", tau_frac},
                              {"compensation", cfg.compensation}, {"zoh_aware", cfg.zoh_aware}};
        std::ofstream(json_path) << out.dump(2) << '\n';
    }
    return all_same ? 0 : 1;
}
