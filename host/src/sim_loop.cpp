// Plant-side closed loop; see sim_loop.hpp.
#include "sim_loop.hpp"

#include <algorithm>
#include <string>

namespace tvo_host {

namespace {
constexpr double kSPerUs = 1e-6;
// Realtime: longest single wait, so a signal or a due command is noticed promptly.
constexpr std::chrono::microseconds kRealtimeSlice{2000};
// Enough pending commands for the longest allowed extra delay at the shortest period seen in practice.
constexpr std::size_t kPendingReserve = 1024;
// Constraint checks along the exact arcs at least this often (plant time): at 5 m/s a robot moves
// 5 mm between checks.
constexpr std::int64_t kCheckStepUs = 1000;

bool is_fault(std::int32_t status, std::int32_t flags)
{
    const auto bad_flags = static_cast<std::int32_t>(TVO_FLAG_HOLDING | TVO_FLAG_SAFE_STOP);
    return status != 0 || (flags & bad_flags) != 0;
}
}  // namespace

SimLoop::SimLoop(const SimOptions& options, const Scenario& scenario, LcmTransport& transport, RunRecorder& recorder,
                 TrackingMetrics& metrics, ConstraintMonitor& monitor, const volatile std::sig_atomic_t& stop_signal)
    : options_(options),
      scenario_(scenario),
      transport_(transport),
      recorder_(recorder),
      metrics_(metrics),
      monitor_(monitor),
      stop_signal_(stop_signal),
      plant_(scenario.robot_count, scenario.starts),
      noise_(MeasurementNoiseConfig{options.sigma, options.sigma, options.sigma}, options.seed),
      disturbance_(DisturbanceConfig{options.disturbance_speed_mps, options.disturbance_turn_radps}, options.seed),
      faults_(FaultConfig{options.drop_prob, options.extra_delay_us}, options.seed)
{
    pending_.reserve(kPendingReserve);
}

std::int64_t SimLoop::wall_plant_us() const
{
    return std::chrono::duration_cast<std::chrono::microseconds>(std::chrono::steady_clock::now() - wall_epoch_)
        .count();
}

void SimLoop::on_command(const tvo_lcm::command_t& command)
{
    const std::size_t robots = scenario_.robot_count;
    const bool count_ok = command.robot_count == static_cast<std::int32_t>(robots);
    metrics_.add_command(command.turn_rate_radps, count_ok ? robots : 0,
                         !count_ok || is_fault(command.status, command.flags),
                         (command.flags & static_cast<std::int32_t>(TVO_FLAG_REGULARIZED)) != 0);
    answered_sequence_ = std::max(answered_sequence_, command.measurement_sequence);
    // Only the newest answer may actuate: a repeat or an older one would move the plant back in time.
    if (!count_ok || command.measurement_sequence <= last_queued_sequence_) {
        return;
    }
    last_queued_sequence_ = command.measurement_sequence;
    PendingCommand pending;
    pending.apply_us = command.utime - options_.start_utime_us + faults_.extra_delay_us();
    pending.sequence = command.measurement_sequence;
    pending.status = command.status;
    pending.flags = command.flags;
    for (std::size_t r = 0; r < robots; ++r) {
        pending.input[r] = UnicycleInput{command.speed_mps[r], command.turn_rate_radps[r]};
    }
    const std::int64_t now_us = options_.realtime ? std::max(now_us_, wall_plant_us()) : now_us_;
    if (pending.apply_us < now_us) {
        ++late_commands_;
        // The plant cannot go back in time: a realtime robot acts on arrival, lockstep discards it
        // (only a dropped period's holding command can arrive late there).
        if (!options_.realtime) {
            return;
        }
        pending.apply_us = now_us;
    }
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), pending.apply_us,
                                     [](std::int64_t t, const PendingCommand& p) { return t < p.apply_us; });
    pending_.insert(at, pending);
}

void SimLoop::on_telemetry(const tvo_lcm::telemetry_t& telemetry)
{
    if (telemetry.measurement_sequence < telemetry_sequence_) {
        return;
    }
    telemetry_sequence_ = telemetry.measurement_sequence;
    telemetry_.barrier_c = telemetry.barrier_c;
    telemetry_.barrier_slack = telemetry.barrier_slack;
    telemetry_.regularization = telemetry.regularization;
}

void SimLoop::check_constraints(std::int64_t t_us)
{
    // The interior points of the held arcs since now_us_, then t_us itself; the plant's own state is
    // advanced in one piece (integrate_to), exactly as without the checks.
    Positions positions{};
    for (std::int64_t at = now_us_ + kCheckStepUs; at < t_us; at += kCheckStepUs) {
        const double dt_s = static_cast<double>(at - now_us_) * kSPerUs;
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            positions[r] = exact_arc(plant_.state(r), plant_.input(r), dt_s).position_m;
        }
        monitor_.observe(static_cast<double>(at) * kSPerUs, positions);
    }
}

void SimLoop::integrate_to(std::int64_t t_us)
{
    if (t_us > now_us_) {
        check_constraints(t_us);
        plant_.advance(static_cast<double>(t_us - now_us_) * kSPerUs);
        now_us_ = t_us;
        Positions positions{};
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            positions[r] = plant_.state(r).position_m;
        }
        monitor_.observe(static_cast<double>(now_us_) * kSPerUs, positions);
    }
}

void SimLoop::advance_to(std::int64_t t_us)
{
    // A command due at exactly t_us is in force at t_us (a sample there sees its speed).
    while (!pending_.empty() && pending_.front().apply_us <= t_us) {
        const PendingCommand command = pending_.front();
        pending_.erase(pending_.begin());
        integrate_to(command.apply_us);
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            plant_.hold(r, disturbance_.perturb(command.input[r]));
        }
        applied_ = command;
    }
    integrate_to(t_us);
}

void SimLoop::publish_sample(std::int64_t sequence, std::int64_t sample_us)
{
    const std::int64_t utime = options_.start_utime_us + sample_us;
    const auto robots = static_cast<std::int32_t>(scenario_.robot_count);
    const double t_s = static_cast<double>(sample_us) * kSPerUs;
    if (scenario_.streamed) {
        // The target source is independent of the pose sensor: it is streamed even when a pose is lost.
        target_.utime = utime;
        target_.sequence = sequence;
        target_.robot_count = robots;
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            const auto deriv = scenario_.targets[r].derivatives(t_s);
            for (int axis = 0; axis < 2; ++axis) {
                target_.position_m[r][axis] = deriv[0][axis];
                target_.velocity_mps[r][axis] = deriv[1][axis];
                target_.acceleration_mps2[r][axis] = deriv[2][axis];
                target_.jerk_mps3[r][axis] = deriv[3][axis];
            }
        }
        transport_.publish(target_);
    }
    if (faults_.drop_measurement()) {
        return;
    }
    measurement_.utime = utime;
    measurement_.sequence = sequence;
    measurement_.robot_count = robots;
    // Position-only: the first sample still carries the heading, which the controller needs to start.
    const bool send_heading = !options_.position_only || !heading_sent_;
    measurement_.heading_valid = send_heading;
    measurement_.speed_valid = !options_.position_only;
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        const RobotSample sample = noise_.measure(plant_.state(r), plant_.input(r));
        measurement_.position_m[r][0] = sample.position_m.x();
        measurement_.position_m[r][1] = sample.position_m.y();
        measurement_.heading_rad[r] = send_heading ? sample.heading_rad : 0.0;
        measurement_.speed_mps[r] = options_.position_only ? 0.0 : sample.speed_mps;
    }
    heading_sent_ = true;
    transport_.publish(measurement_);
}

bool SimLoop::await_answer(std::int64_t sequence)
{
    // The telemetry follows its command: waiting for both keeps the CSV's telemetry columns in step.
    const auto timeout = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::duration<double>(options_.answer_timeout_s));
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (answered_sequence_ < sequence || telemetry_sequence_ < sequence) {
        if (stopping()) {
            return false;
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline -
                                                                                std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            throw TransportError(std::string(answered_sequence_ < sequence ? "no command" : "no telemetry") +
                                 " from the firmware node answering measurement " +
                                 std::to_string(sequence) + " within " + std::to_string(options_.answer_timeout_s) +
                                 " s (wall clock)");
        }
        transport_.wait(left);
    }
    return true;
}

bool SimLoop::wait_until(std::int64_t t_us)
{
    for (;;) {
        const std::int64_t now = wall_plant_us();
        if (now >= t_us) {
            return true;
        }
        if (stopping()) {
            return false;
        }
        transport_.set_log_utime(options_.start_utime_us + now);
        transport_.wait(std::min(std::chrono::microseconds(t_us - now), kRealtimeSlice));
    }
}

void SimLoop::record(std::int64_t t_us)
{
    const double t_s = static_cast<double>(t_us) * kSPerUs;
    double worst_m = 0.0;
    const auto references = scenario_.references(t_s);
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        const double error_m = (plant_.state(r).position_m - references[r]).norm();
        worst_m = std::max(worst_m, error_m);
        recorder_.row(t_s, r, plant_.state(r), references[r], error_m, applied_.input[r], applied_.status,
                      applied_.flags, telemetry_);
    }
    metrics_.add_error_sample(t_s, worst_m);
}

LoopResult SimLoop::run()
{
    LoopResult result;
    transport_.set_listener(this);
    const auto wall_start = std::chrono::steady_clock::now();
    wall_epoch_ = wall_start;
    Positions start{};
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        start[r] = plant_.state(r).position_m;
    }
    monitor_.observe(0.0, start);
    record(0);
    for (std::int64_t n = 0; n < options_.steps; ++n) {
        const std::int64_t apply_us = (n + 1) * options_.period_us;
        const std::int64_t sample_us = apply_us - options_.delay_us;
        if (stopping() || (options_.realtime && !wait_until(sample_us))) {
            result.interrupted = true;
            break;
        }
        advance_to(sample_us);
        transport_.set_log_utime(options_.start_utime_us + sample_us);
        const std::uint64_t drops_before = faults_.drops();
        publish_sample(n, sample_us);
        const bool dropped = faults_.drops() != drops_before;
        if (!options_.realtime && !dropped && !await_answer(n)) {
            result.interrupted = true;
            break;
        }
        if (options_.realtime && !wait_until(apply_us)) {
            result.interrupted = true;
            break;
        }
        advance_to(apply_us);
        record(apply_us);
        result.steps = n + 1;
    }
    result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    result.drops = faults_.drops();
    result.late_commands = late_commands_;
    return result;
}

}  // namespace tvo_host
