// tvo_sim's command line; see options.hpp.
#include "options.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <utility>

#include <unistd.h>

#include <CLI/CLI.hpp>

namespace tvo_host {

namespace {

constexpr double kUsPerS = 1e6;
// A period must be whole microseconds (the wire's clock); allow float round-off of the decimal input.
constexpr double kWholeUsTolerance = 1e-3;
// Upper bound on the injected latency: beyond it the plant would queue many periods of commands.
constexpr double kMaxExtraDelayS = 10.0;
// --link-loss ends within a day of plant time: keeps its microseconds far from int64 overflow.
constexpr double kMaxLinkLossEndS = 86400.0;

int fail(const std::string& option, const std::string& why)
{
    std::cerr << "tvo_sim: error: " << option << ": " << why << " (see --help)\n";
    return 2;
}

std::string one_line(std::string text)
{
    for (char& c : text) {
        c = (c == '\n') ? ' ' : c;
    }
    while (!text.empty() && text.back() == ' ') {
        text.pop_back();
    }
    return text;
}

/// "A,B" -> two finite numbers.
bool parse_pair(const std::string& text, double* first, double* second)
{
    const std::size_t comma = text.find(',');
    if (comma == std::string::npos) {
        return false;
    }
    const std::string a = text.substr(0, comma);
    const std::string b = text.substr(comma + 1);
    char* end_a = nullptr;
    char* end_b = nullptr;
    *first = std::strtod(a.c_str(), &end_a);
    *second = std::strtod(b.c_str(), &end_b);
    return !a.empty() && !b.empty() && *end_a == '\0' && *end_b == '\0' && std::isfinite(*first) &&
           std::isfinite(*second);
}

std::string number(double value)
{
    std::ostringstream out;
    out << value;
    return out.str();
}

/// Cross-field checks and derived microsecond timing; returns -1 or 2.
int validate(SimOptions* o, bool delay_given, bool duration_given, bool robots_given, bool target_given,
             bool link_loss_given)
{
    if (!scenario_exists(o->scenario)) {
        return fail("--scenario", "unknown scenario '" + o->scenario + "' (--list-scenarios lists them)");
    }
    if (o->scenario != "demo") {
        if (robots_given) {
            return fail("--robots", "only the demo takes a robot count (scenario " + o->scenario + " has its own)");
        }
        if (target_given && o->target != TargetKind::Streamed) {
            return fail("--target", "scenario " + o->scenario + " has its own targets (only 'streamed' applies)");
        }
        if (!duration_given) {
            o->duration_s = make_scenario(o->scenario, 1, TargetKind::Ellipse).duration_s;
        }
    }
    const auto& b = o->barrier;
    for (const auto& [name, value] : {std::pair<const char*, std::optional<double>>{"--barrier-c0", b.c0},
                                      {"--barrier-alpha-c", b.alpha_c_per_s},
                                      {"--barrier-c-max", b.c_max},
                                      {"--barrier-delta0", b.delta0},
                                      {"--barrier-alpha-s", b.alpha_s_per_s},
                                      {"--barrier-slack-margin", b.slack_margin}}) {
        // Ranges are the firmware's to judge (it names the part it rejects); here only numbers.
        if (value && !std::isfinite(*value)) {
            return fail(name, "must be a finite number");
        }
    }
    if (!std::isfinite(o->period_s) || !(o->period_s > 0.0)) {
        return fail("--period-s", "must be > 0, got " + number(o->period_s));
    }
    const double period_us = o->period_s * kUsPerS;
    o->period_us = static_cast<std::int64_t>(std::llround(period_us));
    if (o->period_us < 1 || std::abs(period_us - static_cast<double>(o->period_us)) > kWholeUsTolerance) {
        return fail("--period-s", "must be a whole number of microseconds, got " + number(o->period_s));
    }
    if (!delay_given) {
        o->delay_s = o->period_s / 2.0;
    }
    if (!std::isfinite(o->delay_s) || o->delay_s < 0.0 || o->delay_s > o->period_s) {
        return fail("--delay-s", "must be within 0 .. --period-s (" + number(o->period_s) + "), got " +
                                     number(o->delay_s));
    }
    o->delay_us = std::min<std::int64_t>(o->period_us, std::llround(o->delay_s * kUsPerS));
    if (!std::isfinite(o->duration_s) || !(o->duration_s > 0.0)) {
        return fail("--duration-s", "must be > 0, got " + number(o->duration_s));
    }
    o->steps = static_cast<std::int64_t>(std::llround(o->duration_s / o->period_s));
    if (o->steps < 1) {
        return fail("--duration-s", "must cover at least one period");
    }
    if (!std::isfinite(o->sigma) || o->sigma < 0.0) {
        return fail("--sigma", "must be >= 0, got " + number(o->sigma));
    }
    if (!std::isfinite(o->filter_tf_s)) {
        return fail("--filter-tf-s", "must be a finite number");
    }
    if (!std::isfinite(o->drop_prob) || o->drop_prob < 0.0 || o->drop_prob > 1.0) {
        return fail("--drop-prob", "must be within 0 .. 1, got " + number(o->drop_prob));
    }
    if (!std::isfinite(o->extra_delay_s) || o->extra_delay_s < 0.0 || o->extra_delay_s > kMaxExtraDelayS) {
        return fail("--extra-delay-s", "must be within 0 .. 10, got " + number(o->extra_delay_s));
    }
    o->extra_delay_us = static_cast<std::int64_t>(std::llround(o->extra_delay_s * kUsPerS));
    if (link_loss_given && (o->link_loss_start_s < 0.0 || !(o->link_loss_duration_s > 0.0) ||
                            o->link_loss_start_s + o->link_loss_duration_s > kMaxLinkLossEndS)) {
        return fail("--link-loss", "expected S >= 0 and D > 0 (seconds of plant time), got " +
                                       number(o->link_loss_start_s) + "," + number(o->link_loss_duration_s));
    }
    if (link_loss_given) {
        o->link_loss_start_us = std::llround(o->link_loss_start_s * kUsPerS);
        o->link_loss_end_us = std::llround((o->link_loss_start_s + o->link_loss_duration_s) * kUsPerS);
    }
    if (o->disturbance_speed_mps < 0.0 || o->disturbance_turn_radps < 0.0) {
        return fail("--disturbance", "sigmas must be >= 0");
    }
    if (o->robots < 1 || o->robots > kMaxRobots) {
        return fail("--robots", "must be 1 .. 4, got " + std::to_string(o->robots));
    }
    if (!std::isfinite(o->answer_timeout_s) || !(o->answer_timeout_s > 0.0)) {
        return fail("--answer-timeout-s", "must be > 0, got " + number(o->answer_timeout_s));
    }
    if (o->start_utime_us < 0) {
        return fail("--start-utime-us", "must be >= 0");
    }
    if (o->out_dir.empty()) {
        return fail("--out-dir", "must not be empty");
    }
    if (!o->firmware.empty() && access(o->firmware.c_str(), X_OK) != 0) {
        return fail("--firmware", "cannot execute '" + o->firmware + "'");
    }
    if (o->summary_json.empty()) {
        o->summary_json = o->out_dir + "/summary.json";
    }
    return -1;
}

}  // namespace

int parse_options(int argc, char** argv, SimOptions* o)
{
    CLI::App app{"Closes the TV-O unicycle controller (tvo_firmware_node) in the loop with an exact plant "
                 "simulation over LCM, hardware-in-the-loop style. Writes a CSV, an LCM log and a JSON "
                 "summary to --out-dir and prints a summary table.",
                 "tvo_sim"};
    app.get_formatter()->column_width(36);
    std::string gains = "40,13";
    std::string disturbance = "0,0";
    std::string target = "ellipse";
    std::string link_loss;
    std::string on_missing_answer = "fail";

    app.add_option("--period-s", o->period_s, "sampling period h, seconds (whole microseconds)")
        ->capture_default_str();
    CLI::Option* delay = app.add_option("--delay-s", o->delay_s,
                                        "computation delay tau, 0 .. h: the pose is sampled at t_{n+1} - tau and "
                                        "the command applied at t_{n+1} [default: h/2]");
    app.add_flag("--no-compensation", "do not predict the pose over tau in the controller");
    app.add_flag("--zoh-aware", "evaluate the law at the middle of each held interval (tracking error second "
                 "order in h instead of first)");
    app.add_option("--sigma", o->sigma,
                   "measurement noise sigma: position (m, per axis), heading (rad) and speed (m/s)")
        ->capture_default_str();
    app.add_option("--seed", o->seed, "seed of the noise, drop and disturbance streams")->capture_default_str();
    app.add_option("--duration-s", o->duration_s, "simulated time T, seconds")->capture_default_str();
    app.add_flag("--position-only",
                 "measure positions only (the first sample also carries the initial heading); the controller "
                 "derives y' with its dirty-derivative filter");
    app.add_option("--filter-tf-s", o->filter_tf_s, "dirty-derivative time constant T_f, seconds")
        ->capture_default_str();
    app.add_option("--gains", gains, "KP,KD of s^2 + KD s + KP")->capture_default_str();
    app.add_option("--omega-max-radps", o->omega_max_radps, "turn-rate limit")->capture_default_str();
    app.add_option("--accel-max-mps2", o->accel_max_mps2, "acceleration limit")->capture_default_str();
    app.add_option("--speed-max-mps", o->speed_max_mps, "speed limit")->capture_default_str();
    app.add_option("--min-speed-mps", o->min_speed_mps, "1/v regularisation floor")->capture_default_str();
    app.add_option("--watchdog-periods", o->watchdog_periods, "safe stop after this many periods without a "
                   "valid measurement")->capture_default_str();
    app.add_option("--scenario", o->scenario, "what to run: demo, formation-max, formation-bilateral, obstacles, "
                   "obstacles-infeasible-target, infeasible-start, formation-equality (--list-scenarios)")
        ->capture_default_str();
    app.add_flag("--list-scenarios", o->list_scenarios, "list the scenarios with one line each and exit");
    app.add_option("--robots", o->robots, "demo: number of unicycles, 1 .. 4 (the demo picture turned per robot)")
        ->capture_default_str();
    app.add_option("--target", target, "demo: ellipse | circle (on-board targets); any scenario: streamed (the "
                   "targets sent on TVO_TARGET every period)")->capture_default_str();
    app.add_option("--barrier-c0", o->barrier.c0, "barrier: c(0) [default: the scenario's, else the firmware's]");
    app.add_option("--barrier-alpha-c", o->barrier.alpha_c_per_s, "barrier: growth rate of c(t), 1/s");
    app.add_option("--barrier-c-max", o->barrier.c_max, "barrier: cap of c(t)");
    app.add_option("--barrier-delta0", o->barrier.delta0, "barrier: delta(t) = delta0 / c(t)");
    app.add_option("--barrier-alpha-s", o->barrier.alpha_s_per_s, "barrier: decay rate of the slack s(t), 1/s");
    app.add_option("--barrier-slack-margin", o->barrier.slack_margin, "barrier: epsilon_s of the slack rule");
    app.add_option("--barrier-degree", o->barrier.relaxation_degree, "barrier: relaxation degree m_r (>= 3)");
    app.add_flag("--realtime", "run on the monotonic clock at 1/h with the node keeping the schedule on its own "
                 "clock (session CLOCK_NODE; commands applied at their utime, or on arrival if late) instead of "
                 "lockstep");
    app.add_option("--answer-timeout-s", o->answer_timeout_s, "lockstep: longest wait for the firmware's answer")
        ->capture_default_str();
    app.add_option("--on-missing-answer", on_missing_answer, "lockstep: when no answer comes within "
                   "--answer-timeout-s, fail (exit code 1) or hold (count it as lost, the plant holds its "
                   "command, the run goes on)")->capture_default_str();
    app.add_option("--drop-prob", o->drop_prob, "probability that a measurement is lost (never published; the "
                   "plant holds the last command)")->capture_default_str();
    app.add_option("--extra-delay-s", o->extra_delay_s, "extra latency: each command takes effect this long "
                   "after its utime (unknown to the controller)")->capture_default_str();
    app.add_option("--link-loss", link_loss, "S,D: no measurement is sent for sample times in [S, S + D) "
                   "seconds of plant time (a link outage; the node's answers still arrive)");
    app.add_option("--disturbance", disturbance, "SV,SW: sigma of a random speed (m/s) and turn-rate (rad/s) "
                   "perturbation drawn per applied command")->capture_default_str();
    app.add_option("--start-utime-us", o->start_utime_us, "lockstep: wire time (us) of plant time 0, the "
                   "session's epoch; realtime: the plant clock's reading at start")->capture_default_str();
    app.add_option("--lcm-url", o->lcm_url, "LCM URL for this run and the spawned firmware [default: "
                   "$LCM_DEFAULT_URL or LCM's udpm default]");
    app.add_option("--firmware", o->firmware, "tvo_firmware_node to spawn as a child process; without it one "
                   "must already be running on the same LCM URL");
    app.add_option("--out-dir", o->out_dir, "directory for run.csv, run.lcmlog (and the demo's run.png)")
        ->capture_default_str();
    app.add_option("--summary-json", o->summary_json, "JSON summary path [default: <out-dir>/summary.json]");

    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp&) {
        std::cout << app.help();
        return 0;
    } catch (const CLI::CallForAllHelp&) {
        std::cout << app.help("", CLI::AppFormatMode::All);
        return 0;
    } catch (const CLI::ParseError& e) {
        std::cerr << "tvo_sim: error: " << one_line(e.what()) << " (see --help)\n";
        return 2;
    }
    o->delay_compensation = app.count("--no-compensation") == 0;
    o->zoh_aware = app.count("--zoh-aware") > 0;
    o->position_only = app.count("--position-only") > 0;
    o->realtime = app.count("--realtime") > 0;
    if (!parse_pair(gains, &o->gain_kp, &o->gain_kd)) {
        return fail("--gains", "expected KP,KD (two numbers), got '" + gains + "'");
    }
    if (!parse_pair(disturbance, &o->disturbance_speed_mps, &o->disturbance_turn_radps)) {
        return fail("--disturbance", "expected SV,SW (two numbers), got '" + disturbance + "'");
    }
    const bool link_loss_given = app.count("--link-loss") > 0;
    if (link_loss_given && !parse_pair(link_loss, &o->link_loss_start_s, &o->link_loss_duration_s)) {
        return fail("--link-loss", "expected S,D (two numbers, seconds), got '" + link_loss + "'");
    }
    if (on_missing_answer == "fail") {
        o->on_missing_answer = MissingAnswer::Fail;
    } else if (on_missing_answer == "hold") {
        o->on_missing_answer = MissingAnswer::Hold;
    } else {
        return fail("--on-missing-answer", "expected fail or hold, got '" + on_missing_answer + "'");
    }
    if (!parse_target_kind(target, &o->target)) {
        return fail("--target", "expected ellipse, circle or streamed, got '" + target + "'");
    }
    if (o->list_scenarios) {
        print_scenario_list(std::cout);
        return 0;
    }
    return validate(o, delay->count() > 0, app.count("--duration-s") > 0, app.count("--robots") > 0,
                    app.count("--target") > 0, link_loss_given);
}

void print_scenario_list(std::ostream& out)
{
    for (const ScenarioInfo& info : scenario_catalog()) {
        out << std::left << std::setw(30) << info.name << info.summary << '\n';
    }
}

}  // namespace tvo_host
