// Plant-side closed loop; see sim_loop.hpp.
#include "sim_loop.hpp"

#include <algorithm>
#include <cmath>
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
// Lockstep: longest wait for the node to acknowledge a re-sent START (as for the first START).
constexpr std::chrono::milliseconds kRestartTimeout{5000};

using Header = tvo_lcm::command_header_t;

bool is_fault(std::int32_t status, std::int32_t flags)
{
    const auto bad_flags = static_cast<std::int32_t>(Header::FLAG_HOLDING | Header::FLAG_SAFE_STOP);
    return status != 0 || (flags & bad_flags) != 0;
}

bool is_safe_stop(std::int32_t flags)
{
    return (flags & static_cast<std::int32_t>(Header::FLAG_SAFE_STOP)) != 0;
}

/// A command the plant can act on: a time within the wire's range (so no arithmetic on it can
/// overflow) and finite inputs.
bool well_formed(const JointCommand& command, std::size_t robots)
{
    if (command.utime < 0 || command.utime > TVO_WIRE_TIME_MAX_US) {
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
      sent_(static_cast<std::size_t>(options.steps), false),
      telemetry_every_(telemetry_every_periods(options.telemetry_every, options.period_us))
{
    pending_.reserve(kPendingReserve);
    telemetry_sequence_.fill(-1);
    bind_nodes();
}

void SimLoop::bind_nodes()
{
    const std::vector<std::int64_t>& named = session_.named();
    roles_.assign(named.size(), -1);
    running_seen_.assign(named.size(), -1);
    for (std::size_t i = 0; i < named.size(); ++i) {
        const tvo_lcm::node_status_t* node = transport_.nodes().of_boot(named[i]);
        roles_[i] = node != nullptr ? node->own_robot : static_cast<std::int8_t>(-1);
    }
}

std::int64_t SimLoop::silence_limit_us() const
{
    // A CLOCK_NODE node stops the robots itself within (watchdog_periods + 1) h of the last accepted apply
    // instant, and says so every period: the plant gives it one more period (for the link) before it
    // takes the silence for a dead node or link. CLOCK_PLANT (lockstep) counts unanswered samples instead.
    return (options_.watchdog_periods + 2) * options_.period_us;
}

bool SimLoop::telemetry_due(std::int64_t sequence) const
{
    return sequence % telemetry_every_ == 0;
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
    const std::int64_t arrival_us = options_.realtime ? std::max(now_us_, wall_plant_us()) : now_us_;
    if (silent_since_us_) {
        // The node speaks: rule 5's silence starts over, from the command's apply instant (the node's own
        // watchdog counts from there) or its arrival, whichever is later.
        silent_since_us_ = std::max({*silent_since_us_, arrival_us, command.utime - epoch_utime_});
    }
    const bool usable = well_formed(command, robots);
    metrics_.add_command(command.turn_rate_radps.data(), usable ? robots : 0,
                         !usable || is_fault(command.status, command.flags),
                         (command.flags & static_cast<std::int32_t>(TVO_FLAG_REGULARIZED)) != 0);
    const bool answers_ours = sent(command.measurement_sequence);
    if (answers_ours && command.measurement_sequence >= answered_sequence_) {
        answered_sequence_ = command.measurement_sequence;
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
    if (answers_ours) {
        // A safe stop may answer a stray (a sequence we never sent) or be the node's own (-1): it must
        // not make our newer samples' answers look old.
        last_queued_sequence_ = std::max<std::int64_t>(last_queued_sequence_, command.measurement_sequence);
    }
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
    if (restart_pending_ && restart_begun_) {
        session_.on_session_ack(ack);  // the new session's START (the node's repeated acks of the first go nowhere)
    }
}

void SimLoop::on_telemetry(const tvo_lcm::telemetry_t& telemetry)
{
    const tvo_lcm::command_header_t& h = telemetry.header;
    if (h.session_id != session_.session_id() || h.robot < 0 ||
        static_cast<std::size_t>(h.robot) >= scenario_.robot_count) {
        return;
    }
    const auto r = static_cast<std::size_t>(h.robot);
    if (h.measurement_sequence < telemetry_sequence_[r]) {
        return;
    }
    telemetry_sequence_[r] = h.measurement_sequence;
    telemetry_[r].barrier_c = telemetry.barrier_c;
    telemetry_[r].barrier_slack = telemetry.barrier_slack;
    telemetry_[r].regularization = telemetry.regularization;
}

void SimLoop::on_node_status(const tvo_lcm::node_status_t& status)
{
    (void)status;  // the transport's directory has it: judge every named node by its current role
    if (restart_pending_) {
        return;
    }
    const std::vector<std::int64_t>& named = session_.named();
    for (std::size_t i = 0; i < named.size(); ++i) {
        const tvo_lcm::node_status_t* node = transport_.nodes().current(roles_[i]);
        if (node == nullptr) {
            continue;
        }
        if (node->boot_id != named[i]) {
            begin_restart(true);  // the node restarted: the session it ran is gone
            return;
        }
        if (node->state == tvo_lcm::node_status_t::STATE_RUNNING && node->session_id == session_.session_id()) {
            running_seen_[i] = std::max(running_seen_[i], node->utime);
        } else if (node->state == tvo_lcm::node_status_t::STATE_IDLE && running_seen_[i] >= 0 &&
                   node->utime > running_seen_[i]) {
            begin_restart(true);  // it ran ours, and now runs nothing
            return;
        }
    }
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
        target_.header.utime = utime;
        target_.header.session_id = session_.session_id();
        target_.header.sequence = static_cast<std::int32_t>(sequence);
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            const auto deriv = scenario_.targets[r].derivatives(t_s);
            target_.header.robot = static_cast<std::int8_t>(r);
            for (int axis = 0; axis < 2; ++axis) {
                target_.position_m[axis] = deriv[0][axis];
                target_.velocity_mps[axis] = static_cast<float>(deriv[1][axis]);
                target_.acceleration_mps2[axis] = static_cast<float>(deriv[2][axis]);
                target_.jerk_mps3[axis] = static_cast<float>(deriv[3][axis]);
            }
            transport_.publish(target_);
        }
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
    measurement_.sequence = static_cast<std::int32_t>(sequence);
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
    // Before any command, silence counts from when the first sample went out, not from its stamp: a slow
    // link can deliver the START's ack after the epoch, and the node cannot answer a sample not yet sent.
    silent_since_us_ = silent_since_us_.value_or(options_.realtime ? std::max(sample_us, wall_plant_us()) : sample_us);
    transport_.publish(measurement_);
    return true;
}

SimLoop::Answer SimLoop::await_answer(std::int64_t sequence)
{
    // Every robot's command, and its telemetry when this period carries some (the node sends it right
    // after the commands of every telemetry_every-th sequence): waiting for both keeps the CSV's
    // telemetry columns in step, and the run deterministic.
    const auto timeout = std::chrono::duration_cast<std::chrono::microseconds>(
        std::chrono::duration<double>(options_.answer_timeout_s));
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    const bool with_telemetry = telemetry_due(sequence);
    const auto telemetry_in = [&] {
        for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
            if (telemetry_sequence_[r] < sequence) {
                return false;
            }
        }
        return true;
    };
    const auto answered = [&] { return answered_sequence_ >= sequence && (!with_telemetry || telemetry_in()); };
    while (!answered()) {
        if (stopping()) {
            return Answer::Interrupted;
        }
        if (restart_pending_) {
            return Answer::Restart;  // a node restarted or lost the session: this sample will not be answered
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline -
                                                                                std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            const bool no_command = answered_sequence_ < sequence;
            if (options_.on_missing_answer == MissingAnswer::Hold) {
                ++(no_command ? counts_.lost_answers : counts_.lost_telemetry);
                unanswered_streak_ = no_command ? unanswered_streak_ + 1 : 0;
                if (unanswered_streak_ >= options_.watchdog_periods) {
                    begin_restart(false);  // rule 5: the node fell silent for watchdog_periods periods
                }
                return Answer::Lost;
            }
            throw TransportError(std::string(no_command ? "no command" : "no telemetry") +
                                 " from the firmware node answering measurement " + std::to_string(sequence) +
                                 " within " + std::to_string(options_.answer_timeout_s) + " s (wall clock)");
        }
        transport_.wait(left);
    }
    unanswered_streak_ = 0;
    return Answer::Received;
}

void SimLoop::begin_restart(bool new_session)
{
    if (restart_pending_) {
        return;
    }
    // Stop the robots now (a plant's own safe stop, in force until a command of the new session) ...
    const std::int64_t now = options_.realtime ? std::max(now_us_, wall_plant_us()) : now_us_;
    advance_to(now);
    pending_.clear();
    applied_ = PendingCommand{};
    applied_.apply_us = now;
    applied_.sequence = -1;
    applied_.flags = static_cast<std::int32_t>(Header::FLAG_SAFE_STOP);
    for (std::size_t r = 0; r < scenario_.robot_count; ++r) {
        plant_.hold(r, UnicycleInput{});
    }
    last_queued_sequence_ = std::max(last_queued_sequence_, answered_sequence_);
    // ... and start a new session: its START names the nodes' current boots, once they are heard.
    restart_pending_ = true;
    restart_begun_ = false;
    restart_new_session_ = new_session;
    silent_since_us_.reset();
    ++counts_.session_restarts;
}

void SimLoop::service_restart()
{
    if (restart_refused_) {
        throw TransportError("a node lost the session and refused the new one: " +
                             describe_rejection(*restart_refused_, options_));
    }
    if (!restart_pending_) {
        return;
    }
    // Stamped with the plant's clock now (lockstep: its simulated time): a session's first sample must
    // follow its START closely.
    const std::optional<std::int64_t> utime =
        options_.realtime ? std::nullopt : std::optional<std::int64_t>(epoch_utime_ + now_us_);
    if (!restart_begun_) {
        const std::optional<NodeBoots> boots = transport_.nodes().assignment(scenario_.robot_count);
        if (!boots) {
            return;  // rule 1 again: not every robot has a node yet
        }
        // A node that restarted or lost the session needs a new one, of a fresh id (the node's replace rule;
        // the other nodes of a fleet still run the old id). Silence alone: the same START again, which a
        // node that still runs it acks as a repeat, changing nothing.
        const bool same = !restart_new_session_ && *boots == session_.boots();
        const auto id = same ? session_.session_id()
                             : static_cast<std::int32_t>((static_cast<std::uint32_t>(session_.session_id()) + 1u) &
                                                         0x7fffffffu);
        session_.restart(id, *boots, utime.value_or(clock_.now_utime()));
        restart_begun_ = true;
    }
    if (!session_.service(utime)) {
        return;
    }
    if (session_.refused()) {
        restart_refused_ = session_.ack();
        throw TransportError("a node lost the session and refused the new one: " +
                             describe_rejection(*restart_refused_, options_));
    }
    restart_pending_ = false;
    restart_begun_ = false;
    bind_nodes();
    silent_since_us_.reset();  // counted again from the new session's first sample
    unanswered_streak_ = 0;
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
            throw TransportError("a node restarted, lost the session or fell silent, and no new session was acknowledged "
                                 "by every robot's node within " +
                                 std::to_string(kRestartTimeout.count()) + " ms (heard: " +
                                 transport_.nodes().describe() + ")");
        }
        transport_.wait(std::chrono::duration_cast<std::chrono::microseconds>(
            std::min(deadline, now + std::chrono::milliseconds(50)) - now));
    }
    return true;
}

bool SimLoop::wait_until(std::int64_t t_us)
{
    for (;;) {
        service_restart();
        const std::int64_t now = wall_plant_us();
        if (!restart_pending_ && silent_since_us_ && now - *silent_since_us_ >= silence_limit_us()) {
            begin_restart(false);  // rule 5: the node fell silent (not even its own safe stops came)
        }
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
                      applied_.flags, telemetry_[r]);
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
        if (publish_sample(n, sample_us) && !options_.realtime && await_answer(n) == Answer::Interrupted) {
            interrupted = true;
            break;
        }
        if (!options_.realtime && restart_pending_ && !await_restart()) {
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
