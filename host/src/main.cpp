// tvo_sim: the plant side of the hardware-in-the-loop run (see sim_loop.hpp for the timing).
//
// Exit codes (host/README.md, "Exit codes"): 0 run completed; 1 runtime failure (LCM, firmware
// rejected or silent, files, out of memory); 2 bad command line or scenario file; 3 run completed
// with a collision; 128 + signal when interrupted (130 for Ctrl-C).
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <new>
#include <optional>
#include <vector>

#include "constraint_metrics.hpp"
#include "firmware_process.hpp"
#include "metrics.hpp"
#include "options.hpp"
#include "plant_clock.hpp"
#include "run_recorder.hpp"
#include "scenario.hpp"
#include "scenario_file.hpp"
#include "session.hpp"
#include "sim_loop.hpp"
#include "summary.hpp"
#include "transport.hpp"

namespace {

volatile std::sig_atomic_t g_signal = 0;  // the signal that asked us to stop, 0 if none

extern "C" void on_signal(int signo)
{
    g_signal = signo;
}

void install_signal_handlers()
{
    struct sigaction action {};
    action.sa_handler = on_signal;
    sigemptyset(&action.sa_mask);
    action.sa_flags = 0;  // no SA_RESTART: a blocking select returns EINTR and the loop notices
    sigaction(SIGINT, &action, nullptr);
    sigaction(SIGTERM, &action, nullptr);
}

constexpr std::chrono::milliseconds kStartTimeout{5000};
constexpr std::chrono::milliseconds kStopTimeout{1000};
// After STOP each node announces itself at once with its final counters (then it exits, unless kept running).
constexpr std::chrono::milliseconds kFinalAnnouncementTimeout{500};
constexpr std::chrono::milliseconds kChildExitTimeout{2000};
// A run that completed with a robot in contact (summary key collisions > 0).
constexpr int kExitCollision = 3;
constexpr int kExitUsage = 2;

/// A fresh session id (session_t.session_id: an int32 >= 0) for this run.
std::int32_t make_session_id()
{
    const auto ticks = static_cast<std::uint64_t>(std::chrono::steady_clock::now().time_since_epoch().count());
    const std::uint64_t mixed = (static_cast<std::uint64_t>(getpid()) * 0x9e3779b97f4a7c15ull) ^ ticks;
    return static_cast<std::int32_t>((mixed ^ (mixed >> 31)) & 0x7fffffffu);
}

/// Waits until every named node announced itself after `since` (its final counters, after STOP).
void await_final_announcements(tvo_host::LcmTransport& transport, const std::vector<std::int64_t>& boots,
                               std::chrono::steady_clock::time_point since)
{
    const auto deadline = std::chrono::steady_clock::now() + kFinalAnnouncementTimeout;
    const auto all_in = [&] {
        for (const std::int64_t boot : boots) {
            const auto heard = transport.nodes().heard_at(boot);
            const tvo_lcm::node_status_t* node = transport.nodes().of_boot(boot);
            if (!heard || *heard < since || node->state != tvo_lcm::node_status_t::STATE_IDLE) {
                return false;
            }
        }
        return true;
    };
    while (!all_in() && std::chrono::steady_clock::now() < deadline) {
        transport.wait(std::chrono::duration_cast<std::chrono::microseconds>(deadline - std::chrono::steady_clock::now()));
    }
}

/// STOP the session and let the child go; a child that ignores STOP is terminated.
void finish(tvo_host::LcmTransport& transport, tvo_host::SessionClient& session, tvo_host::FirmwareProcess& firmware,
            std::int64_t stop_utime)
{
    if (g_signal != 0) {
        firmware.send_signal(g_signal);  // a signal sent to us alone reaches the child too
    }
    const auto stopped_at = std::chrono::steady_clock::now();
    const bool acked = session.stop(stop_utime, kStopTimeout);
    if (acked && g_signal == 0) {
        await_final_announcements(transport, session.named(), stopped_at);
    }
    if (!firmware.spawned()) {
        return;
    }
    if (acked && session.ack().status != TVO_OK) {
        firmware.terminate();  // it runs no session of ours (START refused): STOP does not end it
    } else if (!firmware.wait_for_exit(kChildExitTimeout)) {
        std::cerr << "tvo_sim: warning: the firmware node did not exit after STOP; terminating it\n";
        firmware.terminate();
    }
}

/// The named nodes' counters (their newest announcements), summed: the summary's node_* keys.
void add_node_counters(const tvo_host::LcmTransport& transport, const std::vector<std::int64_t>& boots,
                       tvo_host::RunSummary* summary)
{
    tvo_host::NodeCounterSums sums;
    bool any = false;
    for (const std::int64_t boot : boots) {
        if (const tvo_lcm::node_status_t* node = transport.nodes().of_boot(boot)) {
            sums.add(node->counters);
            any = true;
        }
    }
    if (any) {
        summary->node_counters = sums;
    }
}

/// The summary keys that apply to the scenario (host/README.md, "Outputs").
void add_constraint_figures(const tvo_host::Scenario& scenario, const tvo_host::ConstraintMonitor& monitor,
                            const tvo_host::TrackingMetrics& metrics, tvo_host::RunSummary* summary)
{
    if (monitor.has_contacts()) {
        summary->collisions = monitor.collisions();
        summary->min_clearance_m = monitor.min_clearance_m();
    }
    if (monitor.has_pair()) {
        summary->min_distance_m = monitor.min_distance_m();
        summary->final_distance_m = monitor.final_distance_m();
        if (scenario.crossing_window) {
            summary->min_distance_crossing_m = monitor.min_distance_window_m();
        }
    }
    if (scenario.has_inequalities()) {
        summary->max_violation_frac = monitor.max_violation_frac();
        summary->initial_violation_frac = monitor.initial_violation_frac();
        summary->time_to_feasible_s = monitor.time_to_feasible_s();
        summary->regularized_steps = metrics.regularized();
        bool has_min = false;
        bool has_max = false;
        for (const tvo_host::DistanceBound& d : scenario.distances) {
            has_min = has_min || d.min_m > 0.0;
            has_max = has_max || d.max_m > 0.0;
        }
        if (has_min) {
            summary->max_violation_min_bound_frac = monitor.max_violation_min_bound_frac();
        }
        if (has_max) {
            summary->max_violation_max_bound_frac = monitor.max_violation_max_bound_frac();
        }
    }
    if (!scenario.offsets.empty()) {
        summary->equality_residual_m = monitor.equality_residual_m();
    }
}

int run(const tvo_host::SimOptions& options)
{
    using namespace tvo_host;
    const std::filesystem::path out_dir(options.out_dir);
    std::filesystem::create_directories(out_dir);
    const std::string csv_path = (out_dir / "run.csv").string();
    const std::string log_path = (out_dir / "run.lcmlog").string();

    // Realtime: the plant clock runs from here, before the first START (CLOCK_NODE takes the node's
    // clock offset from the START's stamp). Lockstep never reads it.
    const PlantClock clock(options.start_utime_us);
    Scenario scenario = make_scenario(options.scenario, options.robots, options.target);
    scenario.barrier.apply(options.barrier);
    // Subscribed before the node is spawned: its first announcement (TVO_NODE, its boot) is heard.
    LcmTransport transport(options.lcm_url, log_path, scenario.robot_count, options.key_file, options.sender_id);
    FirmwareProcess firmware;
    if (!options.firmware.empty()) {
        firmware.spawn(options.firmware, options.lcm_url, options.key_file);
    }
    const auto keep_waiting = [&firmware] { return g_signal == 0 && (!firmware.spawned() || firmware.running()); };
    const std::optional<NodeBoots> boots = await_nodes(transport, scenario.robot_count, kStartTimeout, keep_waiting);
    if (!boots) {
        if (g_signal != 0) {
            std::cerr << "tvo_sim: interrupted\n";
            return 128 + g_signal;
        }
        std::cerr << "tvo_sim: error: the firmware node " << firmware.exit_description() << " before it announced itself\n";
        return 1;
    }
    // Lockstep: START and epoch at --start-utime-us, every START alike (deterministic). Realtime: each
    // START stamped with the plant's current time; the epoch a fixed lead after the first.
    const std::int64_t start_utime = options.realtime ? clock.now_utime() : options.start_utime_us;
    const std::int64_t epoch_utime = options.realtime ? start_utime + kNodeClockEpochLeadUs : start_utime;
    const auto stamp = [&clock, &options] { return options.realtime ? clock.now_utime() : options.start_utime_us; };
    SessionClient session(
        transport, make_start_session(options, scenario, make_session_id(), start_utime, epoch_utime, *boots), stamp);
    const auto stop_utime = [&](std::int64_t steps) {
        return options.realtime ? clock.now_utime() : epoch_utime + steps * options.period_us;
    };
    if (!session.start(kStartTimeout, keep_waiting)) {
        if (g_signal != 0) {
            finish(transport, session, firmware, stop_utime(0));
            std::cerr << "tvo_sim: interrupted\n";
            return 128 + g_signal;
        }
        std::cerr << "tvo_sim: error: the firmware node " << firmware.exit_description()
                  << " before acknowledging the session\n";
        return 1;
    }
    if (session.refused()) {
        std::cerr << "tvo_sim: error: " << describe_rejection(session.ack(), options) << '\n';
        finish(transport, session, firmware, stop_utime(0));
        return 1;
    }

    const double duration_s = static_cast<double>(options.steps * options.period_us) * 1e-6;
    RunRecorder recorder(csv_path);
    TrackingMetrics metrics(duration_s, kRmsWindowS);
    ConstraintMonitor monitor(scenario);
    SimLoop loop(options, scenario, transport, session, clock, recorder, metrics, monitor, g_signal);
    LoopResult result;
    try {
        result = loop.run();
    } catch (const TransportError& e) {
        std::cerr << "tvo_sim: error: " << e.what();
        if (firmware.spawned() && !firmware.running()) {
            std::cerr << "; the firmware node " << firmware.exit_description();
        }
        std::cerr << '\n';
        finish(transport, session, firmware, stop_utime(options.steps));
        return 1;
    }
    finish(transport, session, firmware, stop_utime(result.steps));
    if (!recorder.close()) {
        std::cerr << "tvo_sim: error: writing " << csv_path << " failed\n";
        return 1;
    }
    if (result.interrupted) {
        std::cerr << "tvo_sim: interrupted after " << result.steps << " steps\n";
        return 128 + (g_signal != 0 ? g_signal : SIGINT);
    }

    RunSummary summary;
    summary.final_error_m = metrics.final_error_m();
    summary.rms_error_last5s_m = metrics.rms_error_window_m();
    summary.rms_whole_run = metrics.rms_whole_run();
    summary.max_abs_omega_radps = metrics.max_abs_omega_radps();
    summary.steps = result.steps;
    summary.steps_per_s = result.wall_s > 0.0 ? static_cast<double>(result.steps) / result.wall_s : 0.0;
    summary.faults = metrics.faults();
    summary.commands = metrics.commands();
    summary.drops = result.drops;
    summary.late_commands = result.late_commands;
    summary.lost_answers = result.lost_answers;
    summary.lost_telemetry = result.lost_telemetry;
    summary.link_lost_measurements = result.link_lost_measurements;
    summary.ignored_commands = result.ignored_commands;
    summary.other_session_commands = result.other_session_commands;
    summary.session_restarts = result.session_restarts;
    summary.safe_stop_commands = result.safe_stop_commands;
    summary.first_safe_stop_after_loss_s = result.first_safe_stop_after_loss_s;
    add_node_counters(transport, session.named(), &summary);
    add_constraint_figures(scenario, monitor, metrics, &summary);
    print_summary_table(std::cout, summary, options);
    write_summary_json(options.summary_json, summary);
    const std::string scenario_path = (out_dir / "scenario.json").string();
    write_scenario_json(scenario_path, scenario, duration_s);
    std::cout << "  outputs: " << csv_path << ", " << log_path << " (" << transport.logged_events()
              << " LCM events), " << options.summary_json << ", " << scenario_path << '\n';
    if (transport.keyed() && transport.unauthenticated() + transport.replayed() > 0) {
        std::cerr << "tvo_sim: keyed bus: dropped " << transport.unauthenticated()
                  << " frame(s) without a valid tag and " << transport.replayed() << " replayed frame(s)\n";
    }
    if (!transport.log_ok()) {
        std::cerr << "tvo_sim: error: writing " << log_path << " failed\n";
        return 1;
    }
    if (summary.collisions && *summary.collisions > 0) {
        std::cerr << "tvo_sim: the run ended with " << *summary.collisions << " collision(s) (exit code "
                  << kExitCollision << ")\n";
        return kExitCollision;
    }
    return 0;
}

/// The run's duration (the file's, the default or --duration-s) against the file's last waypoints;
/// the file itself was checked against its own duration when it was read. -1 if fine, else 2.
int check_duration(const tvo_host::SimOptions& options)
{
    using namespace tvo_host;
    try {
        const ScenarioFile file = load_scenario_file(scenario_path(options.scenario));
        const double duration_s = static_cast<double>(options.steps * options.period_us) * 1e-6;
        check_run_duration(file, duration_s, "--duration-s");
    } catch (const ScenarioFileError& e) {
        std::cerr << "tvo_sim: error: " << e.what() << '\n';
        return kExitUsage;
    }
    return -1;
}

int main_unguarded(int argc, char** argv)
{
    tvo_host::SimOptions options;
    const int parsed = tvo_host::parse_options(argc, argv, &options);
    const bool checked_run = parsed < 0 || (parsed == 0 && options.dry_run && !options.list_scenarios);
    if (!checked_run) {
        return parsed;
    }
    if (const int duration = check_duration(options); duration >= 0) {
        return duration;
    }
    if (parsed == 0) {
        return 0;  // --dry-run
    }
    install_signal_handlers();
    try {
        return run(options);
    } catch (const std::bad_alloc&) {
        throw;
    } catch (const std::exception& e) {
        std::cerr << "tvo_sim: error: " << e.what() << '\n';
        return 1;
    }
}

}  // namespace

int main(int argc, char** argv)
{
    // Out of memory anywhere (reading the options, a scenario file, the run) ends with a message and
    // exit code 1, not an abort (std::terminate: SIGABRT, 134).
    try {
        return main_unguarded(argc, argv);
    } catch (const std::bad_alloc&) {
        std::cerr << "tvo_sim: error: out of memory (std::bad_alloc)\n";
        return 1;
    }
}
