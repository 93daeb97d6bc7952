// tvo_sim's command line; see options.hpp. Why each range is what it is: host/README.md, "Options".
#include "options.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <limits>
#include <optional>
#include <system_error>
#include <utility>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "auth_key_file.h"   // the key file's checks, the node's own
#include "command_line.hpp"
#include "lcm_messages.hpp"  // TVO_WIRE_TIME_MAX_US
#include "option_ranges.hpp"
#include "sim_ranges.hpp"
#include "run_recorder.hpp"
#include "scenario_file.hpp"
#include "sim_loop.hpp"      // kNodeClockEpochLeadUs

extern "C" {
#include "session_codec.h"     // TVO_SESSION_TELEMETRY_EVERY_MAX
#include "tvo/config.h"        // TVO_BARRIER_MAX_DEGREE
#include "tvo/sample_clock.h"  // TVO_MAX_TICK_SPAN
}

namespace tvo_host {

namespace {

using tvo_options::add_ranged;
using tvo_options::Default;
using tvo_options::End;
using tvo_options::Interval;
using tvo_options::number;
using tvo_options::real_in;
using tvo_options::whole_in;
using namespace sim_ranges;

// A period must be whole microseconds (the wire's clock); allow float round-off of the decimal input.
constexpr double kWholeUsTolerance = 1e-3;

// The ranges shared with scenario files are in sim_ranges.hpp; these are the command line's own.
constexpr double kMinAnswerTimeoutS = 1e-3;
constexpr double kMaxAnswerTimeoutS = 600.0;
// Commands held back by --extra-delay-s wait in the plant's queue, one per period (sim_loop.cpp
// reserves 1024): at most this many periods of delay.
constexpr std::int64_t kMaxDelayedPeriods = 1000;
constexpr std::uint64_t kMaxOutputMib = 65536;
// Realtime stamps go on past the last period (the START handshake, stalls, the STOP): an hour of slack.
constexpr std::int64_t kRealtimeWireSlackUs = 3600LL * 1000000LL;
// Samples are numbered by period on the wire: sample_header_t.sequence is an int32 >= 0.
constexpr std::int64_t kMaxSequence = 2147483647;

constexpr const char* kProgram = "tvo_sim";

int fail(const std::string& option, const std::string& why)
{
    return tvo_options::option_error(kProgram, option, why);
}

std::string mib(std::uint64_t bytes)
{
    return number(std::ceil(static_cast<double>(bytes) / static_cast<double>(1 << 20) * 10.0) / 10.0) + " MiB";
}

/// The nearest existing folder at or above path (where its files would land).
std::filesystem::path existing_folder(const std::filesystem::path& path)
{
    std::error_code error;
    std::filesystem::path folder = std::filesystem::absolute(path, error);
    while (!folder.empty() && !std::filesystem::is_directory(folder, error) && folder != folder.parent_path()) {
        folder = folder.parent_path();
    }
    return folder;
}

/// Cross-option checks, derived microsecond timing and the bound on the files; returns -1 or 2.
int validate(SimOptions* o, const ScenarioFile& file, bool delay_given, bool duration_given, bool robots_given,
             bool target_given, bool link_loss_given)
{
    if (robots_given && !file.variants.robots_turned) {
        return fail("--robots", "scenario " + o->scenario + " has its own robots (its file has no variants.robots)");
    }
    if (target_given && o->target != TargetKind::Streamed && !file.variants.circle_radius_m) {
        return fail("--target", "scenario " + o->scenario + " has its own targets (only 'streamed' applies)");
    }
    const Scenario scenario = instantiate_scenario(file, o->robots, o->target);
    if (!duration_given) {
        o->duration_s = scenario.duration_s;
    }
    const double period_us = o->period_s * kUsPerS;
    o->period_us = static_cast<std::int64_t>(std::llround(period_us));
    if (std::abs(period_us - static_cast<double>(o->period_us)) > kWholeUsTolerance) {
        return fail("--period-s", "must be a whole number of microseconds, got " + number(o->period_s));
    }
    if (!delay_given) {
        o->delay_s = o->period_s / 2.0;
    }
    if (o->delay_s > o->period_s) {
        return fail("--delay-s", "must be within 0 .. --period-s (" + number(o->period_s) + "), got " +
                                     number(o->delay_s));
    }
    o->delay_us = std::min<std::int64_t>(o->period_us, std::llround(o->delay_s * kUsPerS));
    // duration <= kMaxDurationS and period >= kMinPeriodS: at most 8.64e10 steps, no overflow.
    o->steps = static_cast<std::int64_t>(std::llround(o->duration_s / o->period_s));
    if (o->steps < 1) {
        return fail("--duration-s", "must cover at least one period (--period-s " + number(o->period_s) + "), got " +
                                        number(o->duration_s));
    }
    if (o->steps > kMaxSequence) {
        return fail("--duration-s", "a run of " + number(o->duration_s) + " s at --period-s " + number(o->period_s) +
                                        " has " + std::to_string(o->steps) + " periods; the wire numbers them up to " +
                                        std::to_string(kMaxSequence) + " (sample_header_t.sequence, int32)");
    }
    // The node refuses a watchdog whose span (periods x h, in its microsecond ticks) passes TVO_MAX_TICK_SPAN
    // (TVO_PARAM_WATCHDOG); checked here from that public limit so the refusal comes before anything runs.
    // period_us >= 1 (kPeriod) and watchdog_periods >= 1 (kMinWatchdogPeriods).
    const std::uint64_t most_watchdog_periods = TVO_MAX_TICK_SPAN / static_cast<std::uint64_t>(o->period_us);
    if (static_cast<std::uint64_t>(o->watchdog_periods) > most_watchdog_periods) {
        return fail("--watchdog-periods", "got " + std::to_string(o->watchdog_periods) + ", at most " +
                                              std::to_string(most_watchdog_periods) +
                                              " periods of --period-s " + number(o->period_s) +
                                              " fit the node's watchdog span (2^30 - 1 us)");
    }
    o->extra_delay_us = static_cast<std::int64_t>(std::llround(o->extra_delay_s * kUsPerS));
    if (o->extra_delay_us > kMaxDelayedPeriods * o->period_us) {
        return fail("--extra-delay-s", "got " + number(o->extra_delay_s) + ", at most " +
                                           std::to_string(kMaxDelayedPeriods) + " periods of --period-s " +
                                           number(o->period_s) + " (commands queue in the plant, one per period)");
    }
    if (link_loss_given) {
        if (o->link_loss_start_s + o->link_loss_duration_s > kMaxDurationS) {
            return fail("--link-loss", "S + D must be at most " + number(kMaxDurationS) + " s, got " +
                                           number(o->link_loss_start_s) + "," + number(o->link_loss_duration_s));
        }
        o->link_loss_start_us = std::llround(o->link_loss_start_s * kUsPerS);
        o->link_loss_end_us = std::llround((o->link_loss_start_s + o->link_loss_duration_s) * kUsPerS);
    }
    // Every stamp of the run on the wire stays within TVO_WIRE_TIME_MAX_US (the node refuses the rest).
    const std::int64_t run_us =
        o->steps * o->period_us + (o->realtime ? kNodeClockEpochLeadUs + kRealtimeWireSlackUs : 0);
    const std::int64_t last_start_utime_us = TVO_WIRE_TIME_MAX_US - run_us;
    if (o->start_utime_us > last_start_utime_us) {
        return fail("--start-utime-us",
                    "got " + std::to_string(o->start_utime_us) + ", at most " + std::to_string(last_start_utime_us) +
                        " for this run: its wire times reach start + " + std::to_string(run_us) +
                        " us (--duration-s" + (o->realtime ? ", the realtime slack" : "") +
                        ") and must stay within 2^60 us (TVO_WIRE_TIME_MAX_US)");
    }
    const OutputBound bound =
        bound_outputs(o->steps, o->period_us, scenario.robot_count, scenario.streamed, o->realtime);
    const std::uint64_t limit_bytes = o->max_output_mib << 20;
    if (bound.total_bytes() > limit_bytes) {
        return fail("--duration-s", "a run of " + number(o->duration_s) + " s at --period-s " + number(o->period_s) +
                                        " (" + std::to_string(o->steps) + " periods, " +
                                        std::to_string(scenario.robot_count) + " robot(s)) could write up to " +
                                        mib(bound.total_bytes()) + " (run.csv " + mib(bound.csv_bytes) +
                                        ", run.lcmlog " + mib(bound.lcm_log_bytes) + "), more than --max-output-mib " +
                                        std::to_string(o->max_output_mib) +
                                        ": shorten --duration-s, lengthen --period-s or raise --max-output-mib");
    }
    if (o->out_dir.empty()) {
        return fail("--out-dir", "must not be empty");
    }
    std::error_code space_error;
    const std::filesystem::path folder = existing_folder(o->out_dir);
    const std::filesystem::space_info space = std::filesystem::space(folder, space_error);
    if (!space_error && bound.total_bytes() > space.available) {
        return fail("--out-dir", "the run could write up to " + mib(bound.total_bytes()) + " but " + folder.string() +
                                     " has " + mib(space.available) + " free");
    }
    if (!o->firmware.empty() && access(o->firmware.c_str(), X_OK) != 0) {
        return fail("--firmware", "cannot execute '" + o->firmware + "'");
    }
    if (o->summary_json.empty()) {
        o->summary_json = o->out_dir + "/summary.json";
    }
    if (o->dry_run) {
        std::cout << "tvo_sim: dry run: scenario " << o->scenario << ", " << scenario.robot_count << " robot(s), "
                  << (o->realtime ? "realtime" : "lockstep")
                  << ", h = " << o->period_us << " us, " << o->steps
                  << " periods (" << number(static_cast<double>(o->steps * o->period_us) / kUsPerS)
                  << " s); wire times from " << o->start_utime_us << " us to at most " << o->start_utime_us + run_us
                  << " us; files in " << o->out_dir << " at most " << bound.total_bytes() << " bytes (run.csv "
                  << bound.csv_bytes << ", run.lcmlog " << bound.lcm_log_bytes << ", JSON " << bound.json_bytes
                  << "); nothing was run\n";
        return 0;
    }
    return tvo_options::kRun;
}

}  // namespace

int parse_options(int argc, char** argv, SimOptions* o)
{
    CLI::App app{"Closes the TV-O unicycle controller (tvo_firmware_node) in the loop with an exact plant "
                 "simulation over LCM, hardware-in-the-loop style. Writes a CSV, an LCM log and a JSON "
                 "summary to --out-dir and prints a summary table.",
                 "tvo_sim"};
    app.get_formatter()->column_width(36);
    app.footer("Every number is checked against the range shown ('(' or ')': that end excluded) and the rules "
               "between options before anything runs; a bad value exits with code 2 and names the option. "
               "host/README.md (\"Options\") says why each range is what it is.");
    std::pair<double, double> gains{o->gain_kp, o->gain_kd};
    std::pair<double, double> disturbance{o->disturbance_speed_mps, o->disturbance_turn_radps};
    std::pair<double, double> link_loss{0.0, 0.0};
    std::string target = "ellipse";
    std::string on_missing_answer = "fail";

    add_ranged(app, "--period-s", o->period_s, "sampling period h, seconds (whole microseconds)", real_in(kPeriod));
    CLI::Option* delay = add_ranged(app, "--delay-s", o->delay_s,
                                    "computation delay tau, 0 .. h: the pose is sampled at t_{n+1} - tau and "
                                    "the command applied at t_{n+1} [default: h/2]",
                                    real_in(kDelay), Default::NotShown);
    app.add_flag("--no-compensation", "do not predict the pose over tau in the controller");
    app.add_flag("--zoh-aware", "evaluate the law at the middle of each held interval (tracking error second "
                 "order in h instead of first)");
    add_ranged(app, "--sigma", o->sigma,
               "measurement noise sigma: position (m, per axis), heading (rad) and speed (m/s)",
               real_in(kSigma));
    add_ranged(app, "--seed", o->seed, "seed of the noise, drop and disturbance streams (any 64-bit unsigned)",
               whole_in<std::uint64_t>(0, std::numeric_limits<std::uint64_t>::max()));
    add_ranged(app, "--duration-s", o->duration_s, "simulated time T, seconds [default: the scenario's]",
               real_in(kDuration), Default::NotShown);
    app.add_flag("--position-only",
                 "measure positions only (the first sample also carries the initial heading); the controller "
                 "derives y' with its dirty-derivative filter");
    add_ranged(app, "--filter-tf-s", o->filter_tf_s, "dirty-derivative time constant T_f, seconds",
               real_in(kFilterTf));
    app.add_option("--gains", gains, "KP,KD of s^2 + KD s + KP (the firmware refuses a pair that is not Hurwitz)")
        ->delimiter(',')
        ->check(real_in(kGainKp, "KP").application_index(0))
        ->check(real_in(kGainKd, "KD").application_index(1))
        ->capture_default_str();
    add_ranged(app, "--omega-max-radps", o->omega_max_radps, "turn-rate limit", real_in(kOmegaMax));
    add_ranged(app, "--accel-max-mps2", o->accel_max_mps2, "acceleration limit", real_in(kAccelMax));
    add_ranged(app, "--speed-max-mps", o->speed_max_mps, "speed limit", real_in(kSpeedMax));
    add_ranged(app, "--min-speed-mps", o->min_speed_mps, "1/v regularisation floor (the firmware also wants it "
               "below --speed-max-mps)", real_in(kMinSpeed));
    add_ranged(app, "--watchdog-periods", o->watchdog_periods, "safe stop after this many periods without a "
               "valid measurement (at most (2^30 - 1) us / h: the node's watchdog span); the plant stops its "
               "robots and starts a new session after as long without a command",
               whole_in<std::int32_t>(kMinWatchdogPeriods, kMaxWatchdogPeriods));
    add_ranged(app, "--telemetry-every", o->telemetry_every, "the node's telemetry follows the commands of every "
               "this-many-th period (session_t.telemetry_every); 0: the node's default, the fewest periods "
               "that span 100 ms. run.csv's telemetry columns hold each robot's newest",
               whole_in<std::int32_t>(0, TVO_SESSION_TELEMETRY_EVERY_MAX));
    app.add_option("--scenario", o->scenario, "what to run: a scenario file FILE.yaml, or a built-in scenario's name "
                   "(--list-scenarios lists them)")
        ->capture_default_str();
    app.add_flag("--list-scenarios", o->list_scenarios, "list the scenarios with one line each and exit");
    add_ranged(app, "--robots", o->robots, "demo (a file with variants.robots): number of unicycles, the picture "
               "turned per robot", whole_in<std::size_t>(1, kMaxRobots));
    app.add_option("--target", target, "demo: ellipse | circle (on-board targets); any scenario: streamed (the "
                   "targets sent on TVO_TARGET every period)")
        ->check(CLI::IsMember({"ellipse", "circle", "streamed"}))
        ->capture_default_str();
    // The barrier's finer rules (c_max >= c0, m_r >= k + 1) are the firmware's: it names the part it refuses.
    // Unset, each takes the scenario's value, else the firmware's: no default of its own to show.
    const struct {
        const char* name;
        std::optional<double>* value;
        const char* help;
        Interval range;
    } barrier_reals[] = {
        {"--barrier-c0", &o->barrier.c0, "barrier: c(0) [default: the scenario's, else the firmware's]", kBarrierC0},
        {"--barrier-alpha-c", &o->barrier.alpha_c_per_s, "barrier: growth rate of c(t), 1/s", kBarrierAlphaC},
        {"--barrier-c-max", &o->barrier.c_max, "barrier: cap of c(t)", kBarrierCMax},
        {"--barrier-delta0", &o->barrier.delta0, "barrier: delta(t) = delta0 / c(t)", kBarrierDelta0},
        {"--barrier-alpha-s", &o->barrier.alpha_s_per_s, "barrier: decay rate of the slack s(t), 1/s", kBarrierAlphaS},
        {"--barrier-slack-margin", &o->barrier.slack_margin, "barrier: epsilon_s of the slack rule", kBarrierSlackMargin},
    };
    for (const auto& option : barrier_reals) {
        add_ranged(app, option.name, *option.value, option.help, real_in(option.range), Default::NotShown);
    }
    add_ranged(app, "--barrier-degree", o->barrier.relaxation_degree,
               "barrier: relaxation degree m_r (the firmware wants at least k + 1 = 3)",
               whole_in<int>(kMinBarrierDegree, kMaxBarrierDegree), Default::NotShown);
    app.add_flag("--realtime", "run on the monotonic clock at 1/h with the node keeping the schedule on its own "
                 "clock (session CLOCK_NODE; commands applied at their utime, or on arrival if late) instead of "
                 "lockstep");
    add_ranged(app, "--answer-timeout-s", o->answer_timeout_s, "lockstep: longest wait for the firmware's answer",
               real_in({kMinAnswerTimeoutS, kMaxAnswerTimeoutS, "s"}));
    app.add_option("--on-missing-answer", on_missing_answer, "lockstep: when no answer comes within "
                   "--answer-timeout-s, fail (exit code 1) or hold (count it as lost, the plant holds its "
                   "command, the run goes on)")
        ->check(CLI::IsMember({"fail", "hold"}))
        ->capture_default_str();
    add_ranged(app, "--drop-prob", o->drop_prob, "probability that a measurement is lost (never published; the "
               "plant holds the last command)", real_in(kDropProb));
    add_ranged(app, "--extra-delay-s", o->extra_delay_s, "extra latency: each command takes effect this long "
               "after its utime (unknown to the controller)", real_in(kExtraDelay));
    CLI::Option* loss = app.add_option("--link-loss", link_loss, "S,D: no measurement is sent for sample times in "
                                       "[S, S + D) seconds of plant time (a link outage; the node's answers still "
                                       "arrive); S + D at most a day")
                            ->delimiter(',')
                            ->check(real_in(kLinkLossStart, "S").application_index(0))
                            ->check(real_in(kLinkLossDuration, "D").application_index(1));
    app.add_option("--disturbance", disturbance, "SV,SW: sigma of a random speed (m/s) and turn-rate (rad/s) "
                   "perturbation drawn per applied command")
        ->delimiter(',')
        ->check(real_in(kDisturbanceSpeed, "SV").application_index(0))
        ->check(real_in(kDisturbanceTurn, "SW").application_index(1))
        ->capture_default_str();
    add_ranged(app, "--start-utime-us", o->start_utime_us, "lockstep: wire time (us) of plant time 0, the "
               "session's epoch; realtime: the plant clock's reading at start. The whole run's wire times "
               "(start + duration) stay within 2^60 us", whole_in<std::int64_t>(0, TVO_WIRE_TIME_MAX_US, "us"));
    app.add_option("--lcm-url", o->lcm_url, "LCM URL for this run and the spawned firmware [default: "
                   "$LCM_DEFAULT_URL or LCM's udpm default]");
    app.add_option("--key-file", o->key_file, "authenticate every message both ways with this key file (32 bytes "
                   "as 64 hex digits, mode 0600: tools/keygen); the spawned firmware gets it too. Without it the "
                   "bus is unauthenticated (lab use)")
        ->check([](const std::string& path) {
            std::uint8_t key[TVO_AUTH_KEY_BYTES];
            char why[300];
            const int rc = tvo_auth_key_file_read(path.c_str(), key, why, sizeof(why));
            std::fill(std::begin(key), std::end(key), std::uint8_t{0});
            return rc == 0 ? std::string() : std::string(why);
        });
    add_ranged(app, "--sender-id", o->sender_id, "this plant's sender id on a keyed bus (unique per key holder)",
               whole_in<std::uint32_t>(0, UINT32_MAX, ""));
    app.add_option("--firmware", o->firmware, "tvo_firmware_node to spawn as a child process; without it one "
                   "must already be running on the same LCM URL");
    app.add_option("--out-dir", o->out_dir, "directory for run.csv, run.lcmlog (and the demo's run.png)")
        ->capture_default_str();
    app.add_option("--summary-json", o->summary_json, "JSON summary path [default: <out-dir>/summary.json]");
    add_ranged(app, "--max-output-mib", o->max_output_mib, "refuse a run whose files (run.csv, run.lcmlog, JSON) "
               "could exceed this many MiB, computed before it starts",
               whole_in<std::uint64_t>(1, kMaxOutputMib, "MiB"));
    app.add_flag("--dry-run", o->dry_run, "check the options, print what the run would do and write, and exit "
                 "without running");

    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    o->on_missing_answer = on_missing_answer == "hold" ? MissingAnswer::Hold : MissingAnswer::Fail;
    if (!parse_target_kind(target, &o->target)) {
        return fail("--target", "expected ellipse, circle or streamed, got '" + target + "'");
    }
    if (o->list_scenarios) {
        return print_scenario_list(std::cout, std::cerr);
    }
    if (!scenario_exists(o->scenario)) {
        const std::string path = scenario_path(o->scenario);
        std::error_code error;
        if (std::filesystem::is_directory(path, error)) {
            return fail("--scenario", path + " is a folder, not a scenario file: give one of its .yaml files "
                                      "(--list-scenarios lists the built-in ones)");
        }
        return fail("--scenario", "no scenario '" + o->scenario + "': no file " + path +
                                      " (--list-scenarios lists the built-in ones)");
    }
    ScenarioFile file;
    try {
        file = load_scenario_file(scenario_path(o->scenario));
    } catch (const ScenarioFileError& e) {
        std::cerr << kProgram << ": error: " << e.what() << '\n';
        return tvo_options::kBadCommandLine;
    }
    // The file's settings replace tvo_sim's defaults; an option given on the command line replaces both.
    const RunSettings& run = file.run;
    const auto unless_given = [&app](const char* option, const auto& from_file, auto* field) {
        if (from_file && app.count(option) == 0) {
            *field = *from_file;
        }
    };
    unless_given("--period-s", run.period_s, &o->period_s);
    unless_given("--delay-s", run.delay_s, &o->delay_s);
    unless_given("--sigma", run.sigma, &o->sigma);
    unless_given("--filter-tf-s", run.filter_tf_s, &o->filter_tf_s);
    unless_given("--seed", run.seed, &o->seed);
    unless_given("--gains", run.gains, &gains);
    unless_given("--omega-max-radps", run.omega_max_radps, &o->omega_max_radps);
    unless_given("--accel-max-mps2", run.accel_max_mps2, &o->accel_max_mps2);
    unless_given("--speed-max-mps", run.speed_max_mps, &o->speed_max_mps);
    unless_given("--min-speed-mps", run.min_speed_mps, &o->min_speed_mps);
    unless_given("--watchdog-periods", run.watchdog_periods, &o->watchdog_periods);
    unless_given("--drop-prob", run.drop_prob, &o->drop_prob);
    unless_given("--extra-delay-s", run.extra_delay_s, &o->extra_delay_s);
    unless_given("--disturbance", run.disturbance, &disturbance);
    unless_given("--link-loss", run.link_loss, &link_loss);
    // Flags only switch away from the default: the file's value stands unless the flag is given.
    o->delay_compensation = app.count("--no-compensation") == 0 && run.compensation.value_or(true);
    o->zoh_aware = app.count("--zoh-aware") > 0 || run.zoh_aware.value_or(false);
    o->position_only = app.count("--position-only") > 0 || run.position_only.value_or(false);
    o->realtime = app.count("--realtime") > 0;
    o->gain_kp = gains.first;
    o->gain_kd = gains.second;
    o->disturbance_speed_mps = disturbance.first;
    o->disturbance_turn_radps = disturbance.second;
    o->link_loss_start_s = link_loss.first;
    o->link_loss_duration_s = link_loss.second;
    return validate(o, file, delay->count() > 0 || run.delay_s.has_value(), app.count("--duration-s") > 0,
                    app.count("--robots") > 0, app.count("--target") > 0,
                    loss->count() > 0 || run.link_loss.has_value());
}

int print_scenario_list(std::ostream& out, std::ostream& err)
{
    int status = 0;
    // The built-ins by name (--scenario NAME), then the files of the folder's subfolders by the path to
    // give (tools/fleet FILE): relative to the working folder when inside it. At least two blanks
    // between the columns, however long the name.
    const auto print = [&](const std::string& path, const std::string& name) {
        try {
            const ScenarioFile file = load_scenario_file(path);
            out << std::left << std::setw(28) << name << "  " << file.description << '\n';
        } catch (const ScenarioFileError& e) {
            err << "tvo_sim: error: " << e.what() << '\n';
            status = 2;
        }
    };
    for (const std::string& path : scenario_folder_files()) {
        print(path, std::filesystem::path(path).stem().string());
    }
    for (const std::string& path : scenario_subfolder_files()) {
        std::error_code error;
        const std::filesystem::path relative = std::filesystem::relative(path, error);
        const bool inside = !error && !relative.empty() && *relative.begin() != "..";
        print(path, inside ? relative.string() : path);
    }
    return status;
}

}  // namespace tvo_host
