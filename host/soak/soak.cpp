// tvo_soak: the demo's closed loop in lockstep over hours of simulated time, in one process and as
// fast as the CPU allows. The firmware is the node itself (firmware/edge/node.h: tvo_node_handle
// with LCM-encoded messages and a publish callback, the code the board runs), the plant is the
// host's exact unicycle (tvo_plant), the session is the demo's START as tvo_sim builds it
// (CLOCK_PLANT, h = 10 ms, tau = 5 ms, compensation on, the ellipse target), its epoch a little
// below 2^32 us so that the run crosses the node's uint32 tick wrap-around (every 71.6 min).
//
// Per period n: the plant moves along its held arc to the sample instant (n + 1) h - tau, the
// sample (unicycle_sample_t, sequence n) goes into the node, the node's command must answer it for
// the apply instant (n + 1) h, with its telemetry (the session asks it every period); the plant
// applies it there and the tracking error is taken at that instant.
// --constrained adds a half-space x <= b (default 2.9 m) that the ellipse (|x| <= 3 m) leaves on
// every lap, so the robot rides its boundary for part of each lap (8 % at 2.9 m, 27 % at 2 m) and the
// barrier's c(t) sits at its cap from 9.2 s on.
//
// Exit codes: 0 the run completed with no fault, no non-finite value and every measurement
// answered as the protocol says; 1 it did not (figures still written); 2 bad command line.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "command_line.hpp"
#include "lcm_messages.hpp"
#include "noise.hpp"
#include "options.hpp"
#include "plant.hpp"
#include "progress_line.hpp"
#include "scenario.hpp"
#include "plant_wire.hpp"
#include "session.hpp"

extern "C" {
#include "node.h"
}

namespace {

using tvo_host::UnicycleInput;
using tvo_host::UnicycleState;

constexpr double kPi = 3.14159265358979323846;
constexpr double kSPerUs = 1e-6;
constexpr double kSPerHour = 3600.0;
constexpr std::int64_t kTickSpanUs = std::int64_t{1} << 32;  // the node's uint32 microsecond tick wraps here
constexpr std::int32_t kSessionId = 1;                        // one session per process: any id >= 0
constexpr std::int64_t kBootId = 1;                           // the in-process node's boot: any > 0
// Option ranges (checked before any work; exit 2 naming the option).
constexpr double kMinHours = 0.001;   // 360 periods
constexpr double kMaxHours = 240.0;   // ten days: 86.4 M periods (2.2 min of CPU here)
constexpr double kMaxBelowWrapS = 4294.0;  // less than one tick span: the first wrap lies within the run's first span
constexpr double kMaxTraceHours = 1.0;     // --trace-csv: one row per period, ~200 bytes: at most ~75 MB
constexpr std::int64_t kProgressEverySteps = 4096;  // the progress line reads the clock this often, not every period
// --constrained: x <= bound for robot 0 (the demo's ellipse reaches x = 3 m; its start is at x = -1 m).
constexpr double kDefaultHalfSpaceXMaxM = 2.9;
constexpr double kMinHalfSpaceXMaxM = 0.5;
constexpr double kMaxHalfSpaceXMaxM = 3.5;
// Constraint checks along the exact arcs at least this often (as tvo_sim's kCheckStepUs).
constexpr std::int64_t kCheckStepUs = 1000;
// c(t) counts as at its cap within this relative distance (the telemetry carries it as a double
// from the core's float, so equality is too strict).
constexpr double kCapRelTolerance = 1e-6;

struct SoakOptions {
    double hours{24.0};
    double below_wrap_s{60.0};
    bool constrained{false};
    double halfspace_x_max_m{kDefaultHalfSpaceXMaxM};
    std::string json_path;
    std::string trace_csv_path;
};

std::string number_text(double value)
{
    std::ostringstream out;
    out << std::setprecision(4) << value;
    return out.str();
}

constexpr const char* kProgram = "tvo_soak";

int fail_option(const std::string& option, const std::string& why)
{
    return tvo_options::option_error(kProgram, option, why);
}

/// Returns tvo_options::kRun to run, or the exit code (0 after --help, 2 for a bad command line).
int parse_soak_options(int argc, char** argv, SoakOptions* o)
{
    CLI::App app{"The demo's closed loop in lockstep over hours of simulated time, in-process: the firmware "
                 "node's raw-bytes entry (LCM-encoded messages) against the exact unicycle plant. Prints a "
                 "table; --json writes the same figures.",
                 "tvo_soak"};
    app.add_option("--simulated-hours", o->hours, "simulated time, hours (0.001 .. 240)")->capture_default_str();
    app.add_option("--below-wrap-s", o->below_wrap_s,
                   "the session's epoch lies this many seconds below 2^32 us, the tick wrap (0 .. 4294)")
        ->capture_default_str();
    app.add_flag("--constrained", o->constrained,
                 "add the half-space x <= --halfspace-x-max-m, which the ellipse target (|x| <= 3 m) leaves on "
                 "every lap; the barrier's c(t) reaches its cap after 9.2 s and stays there");
    app.add_option("--halfspace-x-max-m", o->halfspace_x_max_m,
                   "--constrained: the half-space's bound, 0.5 .. 3.5 m (2.9: the target leaves it by 0.1 m, "
                   "crossing at 0.48 m/s; 2: by 1 m, crossing at 1.4 m/s)")
        ->capture_default_str();
    app.add_option("--json", o->json_path, "write the figures to this JSON file");
    app.add_option("--trace-csv", o->trace_csv_path,
                   "write one row per period (pose, reference, command, barrier) to this CSV; runs of at most 1 "
                   "simulated hour");
    const int parsed = tvo_options::parse_command_line(app, argc, argv, kProgram);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    if (!std::isfinite(o->hours) || o->hours < kMinHours || o->hours > kMaxHours) {
        return fail_option("--simulated-hours", "must be within 0.001 .. 240");
    }
    if (!std::isfinite(o->below_wrap_s) || o->below_wrap_s < 0.0 || o->below_wrap_s > kMaxBelowWrapS) {
        return fail_option("--below-wrap-s", "must be within 0 .. 4294");
    }
    if (!std::isfinite(o->halfspace_x_max_m) || o->halfspace_x_max_m < kMinHalfSpaceXMaxM ||
        o->halfspace_x_max_m > kMaxHalfSpaceXMaxM) {
        return fail_option("--halfspace-x-max-m", "must be within 0.5 .. 3.5");
    }
    if (app.count("--halfspace-x-max-m") > 0 && !o->constrained) {
        return fail_option("--halfspace-x-max-m", "applies with --constrained only");
    }
    if (app.count("--json") > 0 && o->json_path.empty()) {
        return fail_option("--json", "needs a file path");
    }
    if (app.count("--trace-csv") > 0 && (o->trace_csv_path.empty() || o->hours > kMaxTraceHours)) {
        return fail_option("--trace-csv", "needs a file path and --simulated-hours of at most 1");
    }
    return tvo_options::kRun;
}

/// What the node published during one tvo_node_handle call, decoded.
struct NodeOutputs {
    int commands{0};
    int telemetries{0};
    int acks{0};
    int announcements{0};
    int undecodable{0};
    tvo_lcm::unicycle_command_t command{};
    tvo_lcm::telemetry_t telemetry{};
    tvo_lcm::session_ack_t ack{};

    void clear()
    {
        commands = telemetries = acks = announcements = undecodable = 0;
    }
};

extern "C" void on_node_publish(void* context, int channel, const std::uint8_t* data, std::uint32_t length)
{
    auto* out = static_cast<NodeOutputs*>(context);
    const int size = static_cast<int>(length);
    switch (channel) {
    case TVO_NODE_CH_COMMAND:
        out->commands += 1;
        out->undecodable += out->command.decode(data, 0, size) < 0 ? 1 : 0;
        break;
    case TVO_NODE_CH_TELEMETRY:
        out->telemetries += 1;
        out->undecodable += out->telemetry.decode(data, 0, size) < 0 ? 1 : 0;
        break;
    case TVO_NODE_CH_SESSION_ACK:
        out->acks += 1;
        out->undecodable += out->ack.decode(data, 0, size) < 0 ? 1 : 0;
        break;
    case TVO_NODE_CH_NODE:
        out->announcements += 1;  // at once when a START is taken: not an answer to a sample
        break;
    default:
        out->undecodable += 1;
        break;
    }
}

/// Wraps of the uint32 tick seen in a stream of wire stamps (each one later than or equal to the last).
class TickWrapCounter {
public:
    void see(std::int64_t stamp_us)
    {
        if (has_last_ && static_cast<std::uint32_t>(stamp_us) < static_cast<std::uint32_t>(last_us_)) {
            ++wraps_;
        }
        has_last_ = true;
        last_us_ = stamp_us;
    }
    std::int64_t wraps() const { return wraps_; }

private:
    bool has_last_{false};
    std::int64_t last_us_{0};
    std::int64_t wraps_{0};
};

template <class T, std::size_t N>
bool all_finite(const T (&values)[N])
{
    return std::all_of(std::begin(values), std::end(values), [](T v) { return std::isfinite(v); });
}

bool command_finite(const tvo_lcm::unicycle_command_t& c)
{
    return std::isfinite(c.speed_mps) && std::isfinite(c.turn_rate_radps);
}

bool telemetry_finite(const tvo_lcm::telemetry_t& t)
{
    return all_finite(t.gradient) && all_finite(t.gradient_rate) && all_finite(t.output_m) &&
           all_finite(t.output_rate_mps) && all_finite(t.output_accel_mps2) && std::isfinite(t.speed_state_mps) &&
           std::isfinite(t.regularization) && std::isfinite(t.barrier_c) && std::isfinite(t.barrier_slack);
}

/// Figures of one run (the JSON keys, in the order written).
struct SoakFigures {
    double simulated_s{0.0};
    std::int64_t steps{0};
    std::int64_t tick_wraps{0};
    std::string error_reference;          // what the tracking error is measured against
    double max_error_m_last_hour{0.0};
    double max_error_m_last_period{0.0};  // the target's last lap (10 s)
    double final_error_m{0.0};
    std::vector<double> max_error_m_by_hour;
    double max_objective_time_error_s_last_hour{0.0};  // |t the law used - (n + 1) h|
    std::uint64_t faults{0};
    std::uint64_t nonfinite{0};
    std::uint64_t unexpected_answers{0};  // not exactly one command + telemetry for period n + 1
    double commands_per_s{0.0};
    double wall_s{0.0};
    // --constrained
    double max_violation_m{0.0};               // max of x - b along the arcs, over the run
    double max_violation_m_last_hour{0.0};
    double barrier_c_max{0.0};                 // the session's cap
    double barrier_c_at_cap_frac{0.0};         // share of steps whose telemetry has c(t) at its cap
    double barrier_c_reaches_cap_s{-1.0};      // first apply instant with c at its cap (-1: never)
};

/// Tracking error windows: per simulated hour, the last hour, the target's last lap.
class ErrorWindows {
public:
    ErrorWindows(double duration_s, double lap_s)
        : last_hour_from_s_(std::max(0.0, duration_s - kSPerHour)), last_lap_from_s_(std::max(0.0, duration_s - lap_s)),
          by_hour_(static_cast<std::size_t>(std::ceil(duration_s / kSPerHour)), 0.0)
    {
    }

    void add(double t_s, double error_m)
    {
        const auto hour = std::min(by_hour_.size() - 1, static_cast<std::size_t>(t_s / kSPerHour));
        by_hour_[hour] = std::max(by_hour_[hour], error_m);
        if (t_s > last_hour_from_s_) {
            last_hour_ = std::max(last_hour_, error_m);
        }
        if (t_s > last_lap_from_s_) {
            last_lap_ = std::max(last_lap_, error_m);
        }
        final_ = error_m;
    }
    bool in_last_hour(double t_s) const { return t_s > last_hour_from_s_; }

    double last_hour() const { return last_hour_; }
    double last_lap() const { return last_lap_; }
    double final_error() const { return final_; }
    const std::vector<double>& by_hour() const { return by_hour_; }

private:
    double last_hour_from_s_;
    double last_lap_from_s_;
    std::vector<double> by_hour_;
    double last_hour_{0.0};
    double last_lap_{0.0};
    double final_{0.0};
};

/// The demo's session and scenario, plus the half-space with --constrained.
struct SoakSetup {
    tvo_host::SimOptions sim;
    tvo_host::Scenario scenario;
    std::int64_t epoch_utime{0};
    std::int64_t steps{0};
};

SoakSetup make_setup(const SoakOptions& o)
{
    SoakSetup s;
    // tvo_sim's defaults are the demo's: h = 10 ms, tau = 5 ms, compensation on, gains (40, 13).
    s.sim.realtime = false;
    s.sim.telemetry_every = 1;  // every answer's telemetry: the law's time and c(t) checked every period
    s.scenario = tvo_host::make_demo_scenario(1, tvo_host::TargetKind::Ellipse);
    if (o.constrained) {
        tvo_host::HalfSpace half;
        half.robot = 0;
        half.normal = Eigen::Vector2d::UnitX();
        half.bound_m = o.halfspace_x_max_m;
        s.scenario.halfspaces.push_back(half);
    }
    s.steps = static_cast<std::int64_t>(std::llround(o.hours * kSPerHour / (static_cast<double>(s.sim.period_us) * kSPerUs)));
    s.epoch_utime = kTickSpanUs - static_cast<std::int64_t>(std::llround(o.below_wrap_s * 1e6));
    return s;
}

/// The position the robot should be at: the target, or with --constrained its projection onto x <= b
/// (the constrained minimiser of |y - y_d|^2).
Eigen::Vector2d reference_at(const SoakSetup& s, double t_s)
{
    Eigen::Vector2d y = s.scenario.targets[0].position(t_s);
    for (const tvo_host::HalfSpace& h : s.scenario.halfspaces) {
        const double excess = h.normal.dot(y) - h.bound_m;
        if (excess > 0.0) {
            y -= excess * h.normal / h.normal.squaredNorm();
        }
    }
    return y;
}

double worst_violation(const SoakSetup& s, const Eigen::Vector2d& y)
{
    double worst = -std::numeric_limits<double>::infinity();
    for (const tvo_host::HalfSpace& h : s.scenario.halfspaces) {
        worst = std::max(worst, h.normal.dot(y) - h.bound_m);
    }
    return worst;
}

class SoakRun {
public:
    SoakRun(const SoakSetup& setup, const std::string& trace_csv_path)
        : setup_(setup), node_(std::make_unique<tvo_node_t>()),
          plant_(setup.scenario.robot_count, setup.scenario.starts),
          sensor_(tvo_host::MeasurementNoiseConfig{}, 1),
          errors_(static_cast<double>(setup.steps * setup.sim.period_us) * kSPerUs,
                  2.0 * kPi / setup.scenario.targets[0].ellipse_params().omega_radps)
    {
        if (tvo_node_init(node_.get(), -1, kBootId, on_node_publish, &out_) != 0) {
            throw std::runtime_error("tvo_node_init failed");
        }
        if (!trace_csv_path.empty()) {
            trace_.open(trace_csv_path);
            if (!trace_) {
                throw std::runtime_error("cannot write " + trace_csv_path);
            }
            trace_ << "t_s,x_m,y_m,heading_rad,reference_x_m,reference_y_m,error_m,speed_mps,turn_rate_radps,status,"
                      "flags,objective_time_s,barrier_c,barrier_slack,gradient_x,gradient_y,accel_x_mps2,accel_y_mps2\n";
            trace_ << std::setprecision(9);
        }
        figures_.max_violation_m = -std::numeric_limits<double>::infinity();
        figures_.max_violation_m_last_hour = -std::numeric_limits<double>::infinity();
    }

    /// START; false (with a message) if the node did not accept it.
    bool start()
    {
        tvo_host::NodeBoots boots{};
        boots[0] = kBootId;
        const tvo_lcm::session_t start = tvo_host::make_start_session(setup_.sim, setup_.scenario, kSessionId,
                                                                      setup_.epoch_utime, setup_.epoch_utime, boots);
        figures_.barrier_c_max = start.barrier.c_max;
        handle(TVO_NODE_CH_SESSION, start, setup_.epoch_utime);
        wraps_.see(setup_.epoch_utime);
        if (out_.acks != 1 || out_.undecodable != 0 || out_.ack.status != TVO_OK) {
            std::cerr << "tvo_soak: error: the node did not accept the session (acks " << out_.acks << ", status "
                      << out_.ack.status << ", parameter " << out_.ack.bad_param << ")\n";
            return false;
        }
        return true;
    }

    SoakFigures run()
    {
        const std::int64_t h = setup_.sim.period_us;
        const std::int64_t tau = setup_.sim.delay_us;
        std::int64_t at_cap_steps = 0;
        const auto wall_start = std::chrono::steady_clock::now();
        tvo_host::ProgressLine progress("tvo_soak", setup_.steps);
        for (std::int64_t n = 0; n < setup_.steps; ++n) {
            if (n % kProgressEverySteps == 0) {
                progress.update(n, "periods");
            }
            const std::int64_t sample_us = (n + 1) * h - tau;
            const std::int64_t apply_us = (n + 1) * h;
            advance_to(sample_us);
            publish_measurement(n, sample_us);
            const bool answered = check_answer(n, apply_us);
            if (answered) {
                const std::int64_t command_us =
                    std::clamp(out_.command.header.utime - setup_.epoch_utime, sample_us, apply_us);
                advance_to(command_us);
                if (command_finite(out_.command)) {
                    plant_.hold(0, UnicycleInput{out_.command.speed_mps, out_.command.turn_rate_radps});
                }
            }
            advance_to(apply_us);
            const double t_s = static_cast<double>(apply_us) * kSPerUs;
            const double error_m = (plant_.state(0).position_m - reference_at(setup_, t_s)).norm();
            figures_.nonfinite += std::isfinite(error_m) ? 0u : 1u;
            errors_.add(t_s, std::isfinite(error_m) ? error_m : std::numeric_limits<double>::infinity());
            if (trace_.is_open()) {
                write_trace_row(t_s, error_m);
            }
            if (out_.telemetries == 1 && errors_.in_last_hour(t_s)) {
                figures_.max_objective_time_error_s_last_hour =
                    std::max(figures_.max_objective_time_error_s_last_hour, std::abs(objective_time_s() - t_s));
            }
            if (!setup_.scenario.halfspaces.empty() && out_.telemetries == 1 &&
                out_.telemetry.barrier_c >= figures_.barrier_c_max * (1.0 - kCapRelTolerance)) {
                ++at_cap_steps;
                if (figures_.barrier_c_reaches_cap_s < 0.0) {
                    figures_.barrier_c_reaches_cap_s = t_s;
                }
            }
        }
        progress.clear();
        figures_.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
        if (trace_.is_open() && !trace_.flush()) {
            throw std::runtime_error("writing the trace failed");
        }
        figures_.steps = setup_.steps;
        figures_.simulated_s = static_cast<double>(setup_.steps * h) * kSPerUs;
        figures_.tick_wraps = wraps_.wraps();
        figures_.commands_per_s = figures_.wall_s > 0.0 ? static_cast<double>(setup_.steps) / figures_.wall_s : 0.0;
        figures_.max_error_m_last_hour = errors_.last_hour();
        figures_.max_error_m_last_period = errors_.last_lap();
        figures_.final_error_m = errors_.final_error();
        figures_.max_error_m_by_hour = errors_.by_hour();
        figures_.error_reference =
            setup_.scenario.halfspaces.empty()
                ? "distance to the target"
                : "distance to the target's projection onto x <= " + number_text(setup_.scenario.halfspaces[0].bound_m) +
                      " m (the constrained minimiser)";
        if (!setup_.scenario.halfspaces.empty()) {
            figures_.barrier_c_at_cap_frac = static_cast<double>(at_cap_steps) / static_cast<double>(setup_.steps);
        }
        return figures_;
    }

private:
    double objective_time_s() const { return static_cast<double>(out_.telemetry.objective_time_us) * kSPerUs; }

    template <class Msg>
    void handle(int channel, const Msg& msg, std::int64_t node_now_us)
    {
        const int size = msg.getEncodedSize();
        buffer_.resize(static_cast<std::size_t>(size));
        msg.encode(buffer_.data(), 0, size);
        out_.clear();
        tvo_node_handle(node_.get(), channel, buffer_.data(), static_cast<std::uint32_t>(size), node_now_us);
    }

    /// Moves the plant along its held arc to plant time t_us, checking the constraint on the way.
    void advance_to(std::int64_t t_us)
    {
        if (t_us <= now_us_) {
            return;
        }
        if (!setup_.scenario.halfspaces.empty()) {
            for (std::int64_t at = now_us_ + kCheckStepUs; at <= t_us; at += kCheckStepUs) {
                const double dt_s = static_cast<double>(at - now_us_) * kSPerUs;
                observe_constraint(at, tvo_host::exact_arc(plant_.state(0), plant_.input(0), dt_s).position_m);
            }
        }
        plant_.advance(static_cast<double>(t_us - now_us_) * kSPerUs);
        now_us_ = t_us;
        if (!setup_.scenario.halfspaces.empty()) {
            observe_constraint(t_us, plant_.state(0).position_m);
        }
    }

    void write_trace_row(double t_s, double error_m)
    {
        const UnicycleState& state = plant_.state(0);
        const Eigen::Vector2d reference = reference_at(setup_, t_s);
        const bool has_telemetry = out_.telemetries == 1;
        trace_ << t_s << ',' << state.position_m.x() << ',' << state.position_m.y() << ',' << state.heading_rad << ','
               << reference.x() << ',' << reference.y() << ',' << error_m << ',' << plant_.input(0).speed_mps << ','
               << plant_.input(0).turn_rate_radps << ',' << (out_.commands == 1 ? out_.command.header.status : -1) << ','
               << (out_.commands == 1 ? out_.command.header.flags : 0) << ','
               << (has_telemetry ? objective_time_s() : 0.0) << ','
               << (has_telemetry ? out_.telemetry.barrier_c : 0.0f) << ','
               << (has_telemetry ? out_.telemetry.barrier_slack : 0.0f) << ','
               << (has_telemetry ? out_.telemetry.gradient[0] : 0.0f) << ','
               << (has_telemetry ? out_.telemetry.gradient[1] : 0.0f) << ','
               << (has_telemetry ? out_.telemetry.output_accel_mps2[0] : 0.0f) << ','
               << (has_telemetry ? out_.telemetry.output_accel_mps2[1] : 0.0f) << '\n';
    }

    void observe_constraint(std::int64_t t_us, const Eigen::Vector2d& y)
    {
        const double v = worst_violation(setup_, y);
        figures_.max_violation_m = std::max(figures_.max_violation_m, v);
        if (errors_.in_last_hour(static_cast<double>(t_us) * kSPerUs)) {
            figures_.max_violation_m_last_hour = std::max(figures_.max_violation_m_last_hour, v);
        }
    }

    void publish_measurement(std::int64_t sequence, std::int64_t sample_us)
    {
        const tvo_host::RobotSample sample = sensor_.measure(plant_.state(0), plant_.input(0));
        tvo_host::JointMeasurement m;
        m.utime = setup_.epoch_utime + sample_us;
        m.session_id = kSessionId;
        m.sequence = static_cast<std::int32_t>(sequence);
        m.robot_count = 1;
        m.position_m[0] = {sample.position_m.x(), sample.position_m.y()};
        m.heading_rad[0] = sample.heading_rad;
        m.speed_mps[0] = sample.speed_mps;
        m.heading_valid = true;
        m.speed_valid = true;
        tvo_host::to_wire(m, 0, &sample_);  // as tvo_sim sends it (the heading wrapped)
        wraps_.see(sample_.header.utime);
        // CLOCK_PLANT: the node's clock does not enter the schedule; it runs with the plant's here.
        handle(TVO_NODE_CH_SAMPLE, sample_, sample_.header.utime);
    }

    /// Counts faults, non-finite values and answers that break the protocol; true if a command of
    /// ours answering `sequence` came (the plant may apply it).
    bool check_answer(std::int64_t sequence, std::int64_t apply_us)
    {
        const tvo_lcm::command_header_t& c = out_.command.header;
        const bool one_each = out_.commands == 1 && out_.telemetries == 1 && out_.acks == 0 && out_.undecodable == 0;
        const bool ours = out_.commands == 1 && c.session_id == kSessionId && c.measurement_sequence == sequence &&
                          c.robot == 0;
        const bool on_time = out_.commands == 1 && c.utime == setup_.epoch_utime + apply_us;
        const bool telemetry_matches = out_.telemetries == 1 && out_.telemetry.header.utime == c.utime &&
                                       out_.telemetry.header.measurement_sequence == sequence;
        figures_.unexpected_answers += (one_each && ours && on_time && telemetry_matches) ? 0u : 1u;
        if (out_.commands >= 1) {
            wraps_.see(c.utime);
            const auto bad_flags = static_cast<std::int32_t>(tvo_lcm::command_header_t::FLAG_HOLDING |
                                                             tvo_lcm::command_header_t::FLAG_SAFE_STOP);
            figures_.faults += (c.status != TVO_OK || (c.flags & bad_flags) != 0) ? 1u : 0u;
            figures_.nonfinite += command_finite(out_.command) ? 0u : 1u;
        }
        if (out_.telemetries >= 1) {
            figures_.nonfinite += telemetry_finite(out_.telemetry) ? 0u : 1u;
        }
        return out_.commands == 1 && ours && c.utime >= setup_.epoch_utime;
    }

    const SoakSetup& setup_;
    std::unique_ptr<tvo_node_t> node_;  // tens of kilobytes: not on the stack
    NodeOutputs out_;
    std::vector<std::uint8_t> buffer_;
    tvo_host::UnicyclePlant plant_;
    tvo_host::MeasurementNoise sensor_;  // noiseless: the true pose, heading wrapped, as tvo_sim sends it
    tvo_lcm::unicycle_sample_t sample_{};
    std::int64_t now_us_{0};
    TickWrapCounter wraps_;
    ErrorWindows errors_;
    SoakFigures figures_;
    std::ofstream trace_;
};

/// Non-finite doubles as JSON null (nlohmann would write null anyway; explicit for the table too).
nlohmann::ordered_json number_or_null(double value)
{
    return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json(nullptr);
}

nlohmann::ordered_json to_json(const SoakFigures& f, const SoakOptions& o, const SoakSetup& s)
{
    nlohmann::ordered_json j;
    j["simulated_s"] = f.simulated_s;
    j["steps"] = f.steps;
    j["tick_wraps"] = f.tick_wraps;
    j["max_error_m_last_hour"] = number_or_null(f.max_error_m_last_hour);
    j["faults"] = f.faults;
    j["nonfinite"] = f.nonfinite;
    j["commands_per_s"] = f.commands_per_s;
    j["error_reference"] = f.error_reference;
    j["max_error_m_last_period"] = number_or_null(f.max_error_m_last_period);
    j["final_error_m"] = number_or_null(f.final_error_m);
    nlohmann::ordered_json by_hour = nlohmann::ordered_json::array();
    for (double e : f.max_error_m_by_hour) {
        by_hour.push_back(number_or_null(e));
    }
    j["max_error_m_by_hour"] = by_hour;
    j["max_objective_time_error_s_last_hour"] = f.max_objective_time_error_s_last_hour;
    j["unexpected_answers"] = f.unexpected_answers;
    j["wall_s"] = f.wall_s;
    j["constrained"] = o.constrained;
    j["first_stamp_us"] = s.epoch_utime;
    j["period_us"] = s.sim.period_us;
    j["delay_us"] = s.sim.delay_us;
    j["core_scalar"] = TVO_USE_DOUBLE ? "double" : "float";
    if (o.constrained) {
        j["halfspace_x_max_m"] = o.halfspace_x_max_m;
        j["max_violation_m"] = number_or_null(f.max_violation_m);
        j["max_violation_m_last_hour"] = number_or_null(f.max_violation_m_last_hour);
        j["barrier_c_max"] = f.barrier_c_max;
        j["barrier_c_at_cap_frac"] = f.barrier_c_at_cap_frac;
        j["barrier_c_reaches_cap_s"] = f.barrier_c_reaches_cap_s;
    }
    return j;
}

void print_table(std::ostream& out, const SoakFigures& f, const SoakOptions& o)
{
    const auto row = [&out](const std::string& key, const std::string& value) {
        out << "  " << std::left << std::setw(38) << key << value << '\n';
    };
    const auto num = number_text;
    out << "tvo_soak: " << (o.constrained ? "constrained (x <= " + number_text(o.halfspace_x_max_m) + " m), " : "")
        << "core "
        << (TVO_USE_DOUBLE ? "double" : "float") << '\n';
    row("simulated_s", num(f.simulated_s));
    row("steps", std::to_string(f.steps));
    row("tick_wraps", std::to_string(f.tick_wraps));
    row("max_error_m_last_hour", num(f.max_error_m_last_hour));
    row("max_error_m_last_period", num(f.max_error_m_last_period));
    row("final_error_m", num(f.final_error_m));
    row("max_objective_time_error_s_last_hour", num(f.max_objective_time_error_s_last_hour));
    row("faults", std::to_string(f.faults));
    row("nonfinite", std::to_string(f.nonfinite));
    row("unexpected_answers", std::to_string(f.unexpected_answers));
    row("commands_per_s", num(f.commands_per_s) + " (wall clock, " + num(f.wall_s) + " s)");
    if (o.constrained) {
        row("max_violation_m", num(f.max_violation_m));
        row("max_violation_m_last_hour", num(f.max_violation_m_last_hour));
        row("barrier_c_at_cap_frac", num(f.barrier_c_at_cap_frac) + " (cap " + num(f.barrier_c_max) +
                                         ", reached at " + num(f.barrier_c_reaches_cap_s) + " s)");
    }
    out << "  error: " << f.error_reference << "; max per simulated hour (m):";
    for (double e : f.max_error_m_by_hour) {
        out << ' ' << num(e);
    }
    out << '\n';
}

}  // namespace

int main(int argc, char** argv)
{
    SoakOptions options;
    const int parsed = parse_soak_options(argc, argv, &options);
    if (parsed != tvo_options::kRun) {
        return parsed;
    }
    return tvo_options::run_reporting_errors(kProgram, [&options] {
        const SoakSetup setup = make_setup(options);
        SoakRun run(setup, options.trace_csv_path);
        if (!run.start()) {
            return 1;
        }
        const SoakFigures figures = run.run();
        print_table(std::cout, figures, options);
        if (!options.json_path.empty()) {
            std::ofstream file(options.json_path);
            file << to_json(figures, options, setup).dump(2) << '\n';
            if (!file.flush()) {
                std::cerr << kProgram << ": error: writing " << options.json_path << " failed\n";
                return 1;
            }
        }
        if (figures.faults != 0 || figures.nonfinite != 0 || figures.unexpected_answers != 0) {
            std::cerr << "tvo_soak: the run had faults, non-finite values or unexpected answers (see above)\n";
            return 1;
        }
        return 0;
    });
}
