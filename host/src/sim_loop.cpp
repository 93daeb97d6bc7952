// Plant-side closed loop; see sim_loop.hpp.
#include "sim_loop.hpp"

#include <algorithm>
#include <cmath>
#include <string>

extern "C" {
}

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
// Lockstep: longest wait for the node to acknowledge a re-sent START (as for the first START).
constexpr std::chrono::milliseconds kRestartTimeout{5000};

bool is_fault(std::int32_t status, std::int32_t flags)
{
    const auto bad_flags = static_cast<std::int32_t>(tvo_lcm::command_t::FLAG_HOLDING | tvo_lcm::command_t::FLAG_SAFE_STOP);
    return status != 0 || (flags & bad_flags) != 0;
}

bool is_safe_stop(std::int32_t flags)
{
    return (flags & static_cast<std::int32_t>(tvo_lcm::command_t::FLAG_SAFE_STOP)) != 0;
}

/// A command the plant can act on: a time within the wire's range (so no arithmetic on it can
/// overflow), our robot count and finite inputs.
bool well_formed(const JointCommand& command, std::size_t robots)
{
    if (command.utime < 0 || command.utime > TVO_WIRE_TIME_MAX_US ||
        command.robot_count != static_cast<std::int32_t>(robots)) {
        return false;
    }
    for (std::size_t r = 0; r < robots; ++r) {
        if (!std::isfinite(command.speed_mps[r]) || !std::isfinite(command.turn_rate_radps[r])) {
            return false;
        }
    }
    return true;
}
}  // namespace

SimLoop::SimLoop(const SimOptions& options, const Scenario& scenario, LcmTransport& transport, SessionClient& session,
                 const PlantClock& clock, RunRecorder& recorder, TrackingMetrics& metrics, ConstraintMonitor& monitor,
                 const volatile std::sig_atomic_t& stop_signal)
    : options_(options),
      scenario_(scenario),
      transport_(transport),
      session_(session),
      clock_(clock),
      recorder_(recorder),
      metrics_(metrics),
      monitor_(monitor),
      stop_signal_(stop_signal),
      epoch_utime_(session.start_message().epoch_utime),
      plant_(scenario.robot_count, scenario.starts),
      noise_(MeasurementNoiseConfig{options.sigma, options.sigma, options.sigma}, options.seed),
      disturbance_(DisturbanceConfig{options.disturbance_speed_mps, options.disturbance_turn_radps}, options.seed),
      faults_(FaultConfig{options.drop_prob, options.extra_delay_us}, options.seed),
      sent_(static_cast<std::size_t>(options.steps), false)
{
    pending_.reserve(kPendingReserve);
}

std::int64_t SimLoop::wall_plant_us() const
{
    return clock_.now_utime() - epoch_utime_;
}

bool SimLoop::sent(std::int64_t sequence) const
{
    return sequence >= 0 && sequence < options_.steps && sent_[static_cast<std::size_t>(sequence)];
}

std::int64_t SimLoop::sample_time_us(std::int64_t sequence) const
{
    return (sequence + 1) * options_.period_us - options_.delay_us;
}

void SimLoop::on_command(const JointCommand& command)
{
    if (command.session_id != session_.session_id()) {
        ++counts_.other_session_commands;
        return;
    }
    const std::size_t robots = scenario_.robot_count;
    const bool usable = well_formed(command, robots);
    metrics_.add_command(command.turn_rate_radps.data(), usable ? robots : 0,
                         !usable || is_fault(command.status, command.flags),
                         (command.flags & static_cast<std::int32_t>(TVO_FLAG_REGULARIZED)) != 0);
    if (command.status == static_cast<std::int32_t>(tvo_lcm::command_t::STATUS_ERR_NO_SESSION) && !restart_pending_ &&
        command.measurement_sequence > restart_acked_through_sequence_) {
        // The node lost our session (it restarted): START again, from the loop (not from inside LCM's handler).
        restart_pending_ = true;
        restart_repeats_.reset();
        ++counts_.session_restarts;
    }
    const bool answers_ours = sent(command.measurement_sequence);
    if (answers_ours && command.measurement_sequence >= answered_sequence_) {
        answered_sequence_ = command.measurement_sequence;
        answered_status_ = command.status;
    }
    const bool safe_stop = is_safe_stop(command.flags);
    if (usable && answers_ours && command.status != TVO_OK && !safe_stop) {
        return; // a refusal only repeats the command in force: nothing to apply (README, plant rules)
    }
    // Only the newest computed answer (or a safe stop) may actuate: a repeat, an older answer or a
    // sequence we never sent (a stray message) would move the plant back in time or hijack it.
    if (!usable || !((answers_ours && command.measurement_sequence > last_queued_sequence_) || safe_stop)) {
        ++counts_.ignored_commands;
        return;
    }
    const std::int64_t arrival_us = options_.realtime ? std::max(now_us_, wall_plant_us()) : now_us_;
    if (options_.realtime && options_.has_link_loss()) {
        if (answers_ours && command.status == TVO_OK &&
            sample_time_us(command.measurement_sequence) < options_.link_loss_start_us) {
            last_answer_before_loss_utime_ = std::max(last_answer_before_loss_utime_.value_or(command.utime),
                                                      command.utime);
        }
        if (safe_stop && arrival_us >= options_.link_loss_start_us && !first_safe_stop_after_loss_utime_) {
            first_safe_stop_after_loss_utime_ = command.utime;
        }
    }
    last_queued_sequence_ = std::max(last_queued_sequence_, command.measurement_sequence);
    PendingCommand pending;
    pending.apply_us = command.utime - epoch_utime_ + faults_.extra_delay_us();
    pending.sequence = command.measurement_sequence;
    pending.status = command.status;
    pending.flags = command.flags;
    for (std::size_t r = 0; r < robots; ++r) {
        pending.input[r] = UnicycleInput{command.speed_mps[r], command.turn_rate_radps[r]};
    }
    if (safe_stop) {
        pending.apply_us = arrival_us; // stopping is never put off (nor taken back to the past)
    }
    if (pending.apply_us < arrival_us) {
        // The node's own safe stops are stamped when published: they always act on arrival.
        counts_.late_commands += command.measurement_sequence >= 0 ? 1u : 0u;
        // The plant cannot go back in time: a realtime robot acts on arrival, lockstep discards it
        // (only an answer given up on with --on-missing-answer hold can arrive late there).
        if (!options_.realtime) {
            return;
        }
        pending.apply_us = arrival_us;
    }
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), pending.apply_us,
                                     [](std::int64_t t, const PendingCommand& p) { return t < p.apply_us; });
    pending_.insert(at, pending);
}

void SimLoop::on_session_ack(const tvo_lcm::session_ack_t& ack)
{
    if (!restart_pending_ || !session_.is_start_ack(ack)) {
        return;  // e.g. the node's repeated ack of a START sent twice at the start
    }
    restart_pending_ = false;
    // Measurements sent until now may still reach the node before this START did: their
    // tvo_lcm::command_t::STATUS_ERR_NO_SESSION answers belong to this restart, not to a new one.
    restart_acked_through_sequence_ = last_sent_sequence_;
    if (ack.status != TVO_OK) {
        restart_refused_ = ack;
    }
}

void SimLoop::on_telemetry(const tvo_lcm::telemetry_t& telemetry)
{
    if (telemetry.session_id != session_.session_id()) {
        return;
    }
    counts_.node_counters = telemetry.counters;
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
        counts_.safe_stop_commands += is_safe_stop(command.flags) ? 1u : 0u;
    }
    integrate_to(t_us);
}

bool SimLoop::publish_sample(std::int64_t sequence, std::int64_t sample_us)
{
    const std::int64_t utime = epoch_utime_ + sample_us;
    const auto robots = static_cast<std::int32_t>(scenario_.robot_count);
    const double t_s = static_cast<double>(sample_us) * kSPerUs;
    if (scenario_.streamed) {
        // The target source is independent of the pose sensor: it is streamed even when a pose is lost.
        target_.utime = utime;
        target_.session_id = session_.session_id();
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
    if (options_.link_lost_at(sample_us)) {
        ++counts_.link_lost_measurements;
        return false;
    }
    if (faults_.drop_measurement()) {
        return false;
    }
    measurement_.utime = utime;
    measurement_.session_id = session_.session_id();
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
    sent_[static_cast<std::size_t>(sequence)] = true;
    last_sent_sequence_ = sequence;
    transport_.publish(measurement_);
    return true;
}

SimLoop::Answer SimLoop::await_answer(std::int64_t sequence)
{
    // The telemetry follows its command: waiting for both keeps the CSV's telemetry columns in step.
    // A node without our session answers tvo_lcm::command_t::STATUS_ERR_NO_SESSION and has no telemetry to send.
    const auto timeout = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::duration<double>(options_.answer_timeout_s));
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    const auto answered = [&] {
        return answered_sequence_ >= sequence &&
               (telemetry_sequence_ >= sequence || answered_status_ == static_cast<std::int32_t>(tvo_lcm::command_t::STATUS_ERR_NO_SESSION));
    };
    while (!answered()) {
        if (stopping()) {
            return Answer::Interrupted;
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline -
                                                                                std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            const bool no_command = answered_sequence_ < sequence;
            if (options_.on_missing_answer == MissingAnswer::Hold) {
                ++(no_command ? counts_.lost_answers : counts_.lost_telemetry);
                return Answer::Lost;
            }
            throw TransportError(std::string(no_command ? "no command" : "no telemetry") +
                                 " from the firmware node answering measurement " + std::to_string(sequence) +
                                 " within " + std::to_string(options_.answer_timeout_s) + " s (wall clock)");
        }
        transport_.wait(left);
    }
    return Answer::Received;
}

void SimLoop::service_restart()
{
    if (restart_refused_) {
        throw TransportError("the node lost the session and refused it again: " +
                             describe_rejection(*restart_refused_, options_));
    }
    if (!restart_pending_) {
        return;
    }
    const auto now = std::chrono::steady_clock::now();
    if (restart_repeats_.due(now)) {
        // Stamped with the plant's clock now (lockstep: its simulated time): the node's first sample
        // of a session must follow its START closely.
        session_.send_start_again(options_.realtime ? std::nullopt : std::optional<std::int64_t>(epoch_utime_ + now_us_));
        restart_repeats_.sent(now);
    }
}

bool SimLoop::await_restart()
{
    const auto deadline = std::chrono::steady_clock::now() + kRestartTimeout;
    for (service_restart(); restart_pending_; service_restart()) {
        if (stopping()) {
            return false;
        }
        const auto now = std::chrono::steady_clock::now();
        if (now >= deadline) {
            throw TransportError("the node lost the session and did not acknowledge it again within " +
                                 std::to_string(kRestartTimeout.count()) + " ms");
        }
        const auto until_repeat = restart_repeats_.next(now);
        transport_.wait(std::chrono::duration_cast<std::chrono::microseconds>(std::min(deadline, until_repeat) - now));
    }
    return true;
}

bool SimLoop::wait_until(std::int64_t t_us)
{
    for (;;) {
        service_restart();
        const std::int64_t now = wall_plant_us();
        if (now >= t_us) {
            return true;
        }
        if (stopping()) {
            return false;
        }
        transport_.set_log_utime(epoch_utime_ + now);
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
    transport_.set_listener(this);
    bool interrupted = options_.realtime && !wait_until(0);  // realtime: plant time 0 is the epoch
    const auto wall_start = std::chrono::steady_clock::now();
    Positions start{};
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        start[r] = plant_.state(r).position_m;
    }
    monitor_.observe(0.0, start);
    record(0);
    for (std::int64_t n = 0; n < options_.steps && !interrupted; ++n) {
        const std::int64_t apply_us = (n + 1) * options_.period_us;
        const std::int64_t sample_us = sample_time_us(n);
        if (stopping() || (options_.realtime && !wait_until(sample_us))) {
            interrupted = true;
            break;
        }
        advance_to(sample_us);
        transport_.set_log_utime(epoch_utime_ + sample_us);
        if (publish_sample(n, sample_us) && !options_.realtime &&
            (await_answer(n) == Answer::Interrupted || !await_restart())) {
            interrupted = true;
            break;
        }
        if (options_.realtime && !wait_until(apply_us)) {
            interrupted = true;
            break;
        }
        advance_to(apply_us);
        record(apply_us);
        counts_.steps = n + 1;
    }
    LoopResult result = counts_;
    result.interrupted = interrupted;
    result.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    result.drops = faults_.drops();
    if (last_answer_before_loss_utime_ && first_safe_stop_after_loss_utime_) {
        result.first_safe_stop_after_loss_s =
            static_cast<double>(*first_safe_stop_after_loss_utime_ - *last_answer_before_loss_utime_) * kSPerUs;
    }
    return result;
}

}  // namespace tvo_host
