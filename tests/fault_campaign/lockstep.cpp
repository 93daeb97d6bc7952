// The campaign's lockstep plant; see lockstep.hpp.
#include "lockstep.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace campaign {

namespace {
constexpr double kSPerUs = 1e-6;
// Wall-clock limits that only a broken node reaches (a lockstep answer takes well under 1 ms).
constexpr std::chrono::seconds kAnswerTimeout{10};
constexpr std::chrono::seconds kStartTimeout{20};
constexpr std::chrono::milliseconds kStartRepeat{100};   // the plant rule: repeat START every 100 ms
constexpr std::chrono::milliseconds kResendInterval{200};
constexpr std::chrono::seconds kExitTimeout{10};
constexpr std::size_t kMaxProblems = 8;
// "The loop tracks": the fault-free loop sits at 1.3e-4 m on this ellipse (README, demo; the
// reference runs print their own figure). A fault's disturbance decays with the closed-loop poles
// s = -5 and -8 (k_p = 40, k_d = 13), by e^-20 over the 4 s every case leaves after its last fault.
// 1e-3 m is 8x the discretization floor: a loop that lost track (held, stopped, restarted from a
// wrong state) is centimetres to metres off.
constexpr double kTrackingBoundM = 1e-3;
constexpr std::int64_t kTrackingWindowPeriods = 100;   // the last second at h = 10 ms

// The node announces itself at its first poll and then every 250 ms while idle, 1 s while running, and
// at once on START and STOP: 3 s is well above any of these.
constexpr std::chrono::seconds kAnnouncementTimeout{3};

const std::int32_t kHolding = static_cast<std::int32_t>(Header::FLAG_HOLDING);
const std::int32_t kSafeStop = static_cast<std::int32_t>(Header::FLAG_SAFE_STOP);

std::string describe(const Command& c)
{
    std::ostringstream out;
    out << "session " << c.header.session_id << " seq " << c.header.measurement_sequence << " robot "
        << static_cast<int>(c.header.robot) << " utime " << c.header.utime << " " << status_text(c.header.status)
        << " flags 0x" << std::hex << c.header.flags << std::dec << " v " << c.speed_mps << " w " << c.turn_rate_radps;
    return out.str();
}

bool is_zero(const Command& c)
{
    return c.speed_mps == 0.0f && c.turn_rate_radps == 0.0f;
}
}  // namespace

NodeCounts counts_of(const tvo_lcm::node_counters_t& c)
{
    NodeCounts n;
    n.accepted = c.accepted;
    for (int i = 0; i < tvo_lcm::node_counters_t::STATUS_SLOTS; ++i) {
        n.refused += c.refused[i];
        if (c.refused[i] != 0) {
            n.refused_by_status += " [" + std::to_string(i) + "]=" + std::to_string(c.refused[i]);
        }
    }
    n.malformed = c.malformed;
    n.unauthenticated = c.unauthenticated;
    n.replayed = c.replayed;
    n.wrong_boot = c.wrong_boot;
    n.idle = c.idle;
    n.other_session = c.other_session;
    n.safe_stops = c.safe_stops;
    n.targets_refused = c.targets_refused;
    n.speed_mismatch = c.speed_mismatch;
    return n;
}

NodeCounts counts_between(const tvo_lcm::node_counters_t& earlier, const tvo_lcm::node_counters_t& later)
{
    tvo_lcm::node_counters_t d = later;
    d.accepted -= earlier.accepted;
    for (int i = 0; i < tvo_lcm::node_counters_t::STATUS_SLOTS; ++i) {
        d.refused[i] -= earlier.refused[i];
    }
    d.malformed -= earlier.malformed;
    d.unauthenticated -= earlier.unauthenticated;
    d.replayed -= earlier.replayed;
    d.wrong_boot -= earlier.wrong_boot;
    d.idle -= earlier.idle;
    d.other_session -= earlier.other_session;
    d.predicted -= earlier.predicted;
    d.safe_stops -= earlier.safe_stops;
    d.targets_refused -= earlier.targets_refused;
    d.speed_mismatch -= earlier.speed_mismatch;
    d.sessions -= earlier.sessions;
    return counts_of(d);
}

bool LockstepRun::Answer::operator==(const Answer& o) const
{
    return speed_mps == o.speed_mps && turn_rate_radps == o.turn_rate_radps && utime == o.utime &&
           status == o.status && flags == o.flags;
}

LockstepRun::LockstepRun(Context& ctx, const LockstepConfig& config)
    : ctx_(ctx),
      config_(config),
      session_(demo_session(config.session_id, config.start_utime_us, config.epoch_utime_us, config.timing)),
      plant_(1, {config.start_pose}),
      now_us_(config.start_utime_us),
      last_applied_us_(config.start_utime_us)
{
}

LockstepRun::~LockstepRun() = default;

std::int64_t LockstepRun::apply_utime(std::int64_t n) const
{
    return config_.epoch_utime_us + (n + 1) * config_.timing.period_us;
}

std::int64_t LockstepRun::sample_utime(std::int64_t n) const
{
    return apply_utime(n) - config_.timing.delay_us;
}

void LockstepRun::prepare()
{
    if (prepared_) {
        return;
    }
    prepared_ = true;
    const std::int64_t known = ctx_.bus.node_boot();
    if (config_.spawn_node && !ctx_.node_path.empty()) {
        node_ = std::make_unique<NodeProcess>(ctx_.node_path, ctx_.lcm_url, ctx_.key_file);
        node_->spawn(config_.keep_running, config_.node_stderr_path);
        boot_ = ctx_.bus.await_boot(known, kStartTimeout);   // a new process: a new boot
    } else {
        boot_ = known != 0 ? known : ctx_.bus.await_boot(0, kStartTimeout);
    }
    if (boot_ == 0) {
        throw std::runtime_error("no node announced a new boot on " TVO_CHANNEL_NODE " within " +
                                 std::to_string(kStartTimeout.count()) + " s");
    }
    session_.node_boot_id[0] = boot_;
    ctx_.bus.clear();
    processed_ = 0;
}

void LockstepRun::start()
{
    prepare();
    restart_session();
}

void LockstepRun::restart_session()
{
    // Rule 1: the node's boot, heard from its announcements (prepare(), crash_node_and_restart()).
    session_.node_boot_id[0] = boot_;
    tvo_lcm::session_t start = session_;
    start.utime = now_us_;
    const std::size_t first_ack = ctx_.bus.acks.size();
    const std::size_t first_announcement = ctx_.bus.announcements.size();
    const tvo_lcm::session_ack_t* ack = nullptr;
    auto acked = [&] {
        for (std::size_t i = first_ack; i < ctx_.bus.acks.size(); ++i) {
            const auto& a = ctx_.bus.acks[i];
            if (a.session_id == start.session_id && a.action == tvo_lcm::session_t::ACTION_START && a.boot_id == boot_) {
                ack = &ctx_.bus.acks[i];
                return true;
            }
        }
        return false;
    };
    const auto deadline = std::chrono::steady_clock::now() + kStartTimeout;
    while (!acked()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            throw std::runtime_error("no ack to START of session " + std::to_string(start.session_id) + " within " +
                                     std::to_string(kStartTimeout.count()) + " s");
        }
        ctx_.bus.publish(start);
        ctx_.bus.wait_until(acked, kStartRepeat);
    }
    if (ack->status != 0 || ack->running_session_id != start.session_id) {
        throw std::runtime_error("START of session " + std::to_string(start.session_id) + " refused: " +
                                 status_text(ack->status) + ", bad_param " + std::to_string(ack->bad_param));
    }
    start_ack_ = *ack;
    // The node announces itself at once when it takes a START: its counters before the session's samples.
    const tvo_lcm::node_status_t* running = ctx_.bus.await_announcement(
        first_announcement, boot_,
        [&](const tvo_lcm::node_status_t& s) {
            return s.state == tvo_lcm::node_status_t::STATE_RUNNING && s.session_id == start.session_id;
        },
        kAnnouncementTimeout);
    if (running != nullptr) {
        start_counters_ = running->counters;
    }
}

tvo_lcm::session_ack_t LockstepRun::request(const tvo_lcm::session_t& msg, std::chrono::milliseconds repeat)
{
    const std::size_t first_ack = ctx_.bus.acks.size();
    std::size_t found = 0;
    auto acked = [&] {
        for (std::size_t i = first_ack; i < ctx_.bus.acks.size(); ++i) {
            const auto& a = ctx_.bus.acks[i];
            if (a.session_id == msg.session_id && a.action == msg.action) {
                found = i;
                return true;
            }
        }
        return false;
    };
    const auto deadline = std::chrono::steady_clock::now() + kAnswerTimeout;
    while (!acked()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            throw std::runtime_error("no ack to session message (id " + std::to_string(msg.session_id) +
                                     ", action " + std::to_string(msg.action) + ")");
        }
        ctx_.bus.publish(msg);
        ctx_.bus.wait_until(acked, repeat);
    }
    return ctx_.bus.acks[found];
}

void LockstepRun::send_until_answered(const Sample& m, Expect::Kind kind, const std::string& label)
{
    const std::size_t before = ctx_.bus.commands.size();
    send_expecting(m, kind, label);
    resend_until_answered(m, before, label);
}

void LockstepRun::send_genuine_until_answered(const Sample& m)
{
    const std::size_t before = ctx_.bus.commands.size();
    send_genuine(m);
    resend_until_answered(m, before, "genuine sample " + std::to_string(m.header.sequence));
}

void LockstepRun::resend_until_answered(const Sample& m, std::size_t commands_before, const std::string& label)
{
    const auto deadline = std::chrono::steady_clock::now() + kStartTimeout;
    while (!ctx_.bus.wait_until([&] { return ctx_.bus.commands.size() > commands_before; }, kResendInterval)) {
        if (std::chrono::steady_clock::now() >= deadline) {
            throw std::runtime_error("no answer to sample " + std::to_string(m.header.sequence) + " (" + label + ")");
        }
        ctx_.bus.publish(m);
        Expect repeat;
        repeat.kind = Expect::Kind::Optional;
        repeat.session_id = m.header.session_id;
        repeat.sequence = m.header.sequence;
        repeat.utime = m.header.utime;
        expected_.push_back(repeat);
    }
}

void LockstepRun::run(const Hook& hook)
{
    for (std::int64_t n = config_.first_sequence; n < config_.first_sequence + config_.periods; ++n) {
        step(n, hook);
    }
}

void LockstepRun::step(std::int64_t n, const Hook& hook)
{
    current_step_ = n;
    advance_to(sample_utime(n));
    if (hook) {
        hook(*this, n);
    } else {
        send_genuine(measure(n));
    }
    settle();
    const std::int64_t apply_us = apply_utime(n);
    advance_to(apply_us);
    // The plant's own watchdog (the node cannot act during silence in CLOCK_PLANT).
    const std::int64_t silence_us = config_.timing.watchdog_periods * config_.timing.period_us;
    const auto& input = plant_.input(0);
    if (apply_us - last_applied_us_ >= silence_us && (input.speed_mps != 0.0 || input.turn_rate_radps != 0.0)) {
        plant_.hold(0, tvo_host::UnicycleInput{});
        ++plant_watchdog_stops;
    }
    double x = 0.0;
    double y = 0.0;
    demo_target(session_, apply_us, &x, &y);
    errors_.emplace_back(apply_us, (plant_.state(0).position_m - Eigen::Vector2d(x, y)).norm());
}

Sample LockstepRun::measure(std::int64_t n) const
{
    Sample m{};
    m.header.utime = now_us_;
    m.header.session_id = session_.session_id;
    m.header.sequence = static_cast<std::int32_t>(n);
    m.header.robot = 0;
    m.has = tvo_lcm::unicycle_sample_t::HAS_HEADING | tvo_lcm::unicycle_sample_t::HAS_SPEED;
    m.position_m[0] = plant_.state(0).position_m.x();
    m.position_m[1] = plant_.state(0).position_m.y();
    m.heading_rad = static_cast<float>(std::remainder(plant_.state(0).heading_rad, 2.0 * M_PI));  // the wire's range
    m.speed_mps = static_cast<float>(plant_.input(0).speed_mps);
    return m;
}

void LockstepRun::publish_expect(const Sample& m, Expect e)
{
    e.session_id = m.header.session_id;
    e.sequence = m.header.sequence;
    e.robot = m.header.robot;
    e.utime = m.header.utime;
    ctx_.bus.publish(m);
    expected_.push_back(e);
}

void LockstepRun::send_genuine(const Sample& m)
{
    sent_sequences_.insert(m.header.sequence);
    ++genuine_sent;
    Expect e;
    e.kind = Expect::Kind::Accepted;
    e.genuine = true;
    e.apply_utime = apply_utime(m.header.sequence);
    publish_expect(m, e);
}

void LockstepRun::send_genuine_refused(const Sample& m, std::int32_t status, const std::string& label)
{
    sent_sequences_.insert(m.header.sequence);
    ++genuine_sent;
    Expect e;
    e.kind = Expect::Kind::Refused;
    e.genuine = true;
    e.status = status;
    e.label = label;
    publish_expect(m, e);
}

void LockstepRun::send_stray(const Sample& m, std::int32_t status, const std::string& label, bool match_by_order)
{
    Expect e;
    e.kind = Expect::Kind::Refused;
    e.status = status;
    e.label = label;
    e.match_by_order = match_by_order;
    publish_expect(m, e);
}

void LockstepRun::send_refused_unanswered(const Sample& m, const std::string& label)
{
    Expect e;
    e.kind = Expect::Kind::Ignored;
    e.counted_refusal = true;
    e.label = label;
    publish_expect(m, e);
}

void LockstepRun::send_expecting(const Sample& m, Expect::Kind kind, const std::string& label)
{
    Expect e;
    e.kind = kind;
    e.label = label;
    e.genuine = kind == Expect::Kind::Ignored && m.header.session_id == session_.session_id;
    if (e.genuine) {
        sent_sequences_.insert(m.header.sequence);
        ++genuine_sent;
    }
    publish_expect(m, e);
}

void LockstepRun::unanswered(const Expect& e)
{
    silent_refusals += e.counted_refusal ? 1 : 0;
    if (e.genuine) {   // the plant's own sample, dropped: a period it holds its command
        ++genuine_held;
        held_steps.push_back(current_step_);
    }
    if (!e.label.empty()) {
        outcomes_.push_back({e.label, true, "no answer", 0, 0});
    }
}

void LockstepRun::send_raw(const char* channel, const std::vector<std::uint8_t>& bytes, Expect expect)
{
    ctx_.bus.publish_raw(channel, bytes);
    expected_.push_back(expect);
}

void LockstepRun::settle()
{
    auto required_left = [this] {
        return std::any_of(expected_.begin(), expected_.end(), [](const Expect& e) {
            return e.kind != Expect::Kind::Ignored && e.kind != Expect::Kind::Optional;
        });
    };
    for (;;) {
        while (processed_ < ctx_.bus.commands.size()) {
            process(ctx_.bus.commands[processed_++]);
        }
        if (!required_left()) {
            return;
        }
        if (!ctx_.bus.wait_until([this] { return processed_ < ctx_.bus.commands.size(); }, kAnswerTimeout)) {
            const Expect& e = *std::find_if(expected_.begin(), expected_.end(), [](const Expect& x) {
                return x.kind != Expect::Kind::Ignored && x.kind != Expect::Kind::Optional;
            });
            throw std::runtime_error("no answer within " + std::to_string(kAnswerTimeout.count()) +
                                     " s to the sample of session " + std::to_string(e.session_id) + " seq " +
                                     std::to_string(e.sequence) + (e.label.empty() ? "" : " (" + e.label + ")"));
        }
    }
}

void LockstepRun::problem(const std::string& text)
{
    if (problems.size() < kMaxProblems) {
        problems.push_back(text);
    }
}

void LockstepRun::process(const ReceivedCommand& received)
{
    const Command& cmd = received.msg;
    const Header& h = cmd.header;
    ctx_.audit.add(cmd);
    const std::int64_t in_force_before = in_force_sequence_;
    const std::size_t pending_before = pending_.size();
    bool matched = false;
    applied_safe_stop_for_own_ = false;
    while (!expected_.empty() && !matched) {
        const Expect e = expected_.front();
        const bool key = h.session_id == e.session_id && h.measurement_sequence == e.sequence && h.robot == e.robot;
        if (e.kind == Expect::Kind::Ignored) {
            expected_.pop_front();
            if (key) {
                ++unexpected_answers;
                problem("an ignored message was answered: " + describe(cmd));
                if (!e.label.empty()) {
                    outcomes_.push_back({e.label, false, "answered: " + describe(cmd), h.status, h.flags});
                }
                matched = true;
            } else {
                unanswered(e);
            }
            continue;
        }
        if (e.kind == Expect::Kind::Optional) {
            expected_.pop_front();
            if (key) {
                if (!e.label.empty()) {
                    outcomes_.push_back({e.label, true, "answered: " + describe(cmd), h.status, h.flags});
                }
                if (h.status != 0 && h.session_id == session_.session_id) {
                    ++refusal_answers;
                }
                matched = true;
            } else if (!e.label.empty()) {
                outcomes_.push_back({e.label, true, "no answer", 0, 0});
            }
            continue;
        }
        if (key || e.match_by_order) {
            expected_.pop_front();
            verify(e, cmd);
        } else {
            ++unexpected_answers;
            problem("a command answering nothing expected (next expected: seq " + std::to_string(e.sequence) +
                    "): " + describe(cmd));
        }
        matched = true;
    }
    if (!matched) {
        ++unexpected_answers;
        problem("a command answering nothing sent: " + describe(cmd));
    }
    // The plant's rule: any safe stop for its session, whatever it answers, takes effect on arrival.
    if (h.session_id == session_.session_id && (h.flags & kSafeStop) != 0) {
        ++safe_stop_answers;
        apply(cmd, now_us_, applied_safe_stop_for_own_);
    }
    const bool applied = pending_.size() != pending_before || in_force_sequence_ != in_force_before;
    shadow_literal_plant(cmd, applied);
}

void LockstepRun::verify(const Expect& e, const Command& cmd)
{
    const Header& h = cmd.header;
    const bool safe_stop = (h.flags & kSafeStop) != 0;
    const bool holding = (h.flags & kHolding) != 0;
    if (!e.match_by_order && h.utime < e.utime) {
        ++stamped_before_measurement;
        problem("answer stamped before its measurement (" + std::to_string(e.utime) + "): " + describe(cmd));
    }
    const Answer answer{cmd.speed_mps, cmd.turn_rate_radps, h.utime, h.status, h.flags};
    // The plant's rule: its own sample's computed answer (status 0; it knows which message that is),
    // newer than the command in force; a refusal only repeats the command in force; safe stops: process().
    const bool own_session = h.session_id == session_.session_id;
    const bool plant_applies = own_session && e.genuine && h.status == 0 &&
                               h.measurement_sequence > in_force_sequence_ && !safe_stop;
    if (own_session && h.status != 0) {
        ++refusal_answers;
    }
    switch (e.kind) {
    case Expect::Kind::Accepted: {
        const bool ok = h.status == 0 && !holding && !safe_stop && h.utime == e.apply_utime && h.robot == 0;
        genuine_answers_[e.sequence] = answer;
        if (ok) {
            ++genuine_accepted;
            held_ = answer;
            consecutive_refusals_ = 0;
        } else {
            ++genuine_wrong;
            problem("genuine sample " + std::to_string(e.sequence) + " (apply at " + std::to_string(e.apply_utime) +
                    ") answered " + describe(cmd));
        }
        if (h.status != 0 || holding) {
            ++genuine_held;
            held_steps.push_back(current_step_);
        }
        break;
    }
    case Expect::Kind::Refused: {
        // After watchdog_periods consecutive refusals the answer is a safe stop: allowed from the
        // watchdog_periods-th on, required after it.
        ++consecutive_refusals_;
        const long watchdog_at = config_.timing.watchdog_periods;
        const bool watchdog = safe_stop && h.status == Header::STATUS_ERR_WATCHDOG && consecutive_refusals_ >= watchdog_at;
        const bool watchdog_due = consecutive_refusals_ > watchdog_at;
        const bool status_ok =
            watchdog || (h.status != 0 && (e.status == Expect::kAnyStatus || h.status == e.status));
        const bool flags_ok = watchdog || (holding && !safe_stop);
        const bool values_ok = watchdog ? is_zero(cmd)
                                        : (static_cast<double>(cmd.speed_mps) == held_.speed_mps &&
                                           static_cast<double>(cmd.turn_rate_radps) == held_.turn_rate_radps);
        const bool utime_ok = e.match_by_order || h.utime == e.utime;
        const bool ok = status_ok && flags_ok && values_ok && utime_ok && (watchdog || !watchdog_due);
        if (e.genuine) {
            ++genuine_held;
            held_steps.push_back(current_step_);
        }
        if (watchdog) {
            held_ = Answer{0.0, 0.0, h.utime, h.status, h.flags};
        }
        std::ostringstream figure;
        figure << "refusal " << consecutive_refusals_ << " in a row: " << status_text(h.status)
               << (holding ? ", HOLDING" : "") << (safe_stop ? ", SAFE_STOP" : "")
               << (values_ok ? ", the held command" : ", NOT the held command") << ", utime ";
        if (h.utime == e.utime) {
            figure << "= its stamp";
        } else {
            figure << h.utime << " (its stamp " << e.utime << ")";
        }
        if (e.match_by_order) {
            figure << ", echoes sequence " << h.measurement_sequence;
        }
        if (!e.label.empty()) {
            outcomes_.push_back({e.label, ok, figure.str(), h.status, h.flags});
        } else if (!ok) {
            problem("refusal expected (" + status_text(e.status) + "): " + describe(cmd));
            ++genuine_wrong;
        }
        break;
    }
    case Expect::Kind::Ignored:
    case Expect::Kind::Optional:
        break;
    }
    if (plant_applies) {
        apply(cmd, std::max(h.utime, now_us_), true);
    }
    applied_safe_stop_for_own_ = e.genuine;
}

void LockstepRun::apply(const Command& cmd, std::int64_t at_us, bool answers_own_sample)
{
    // A safe stop answering a stray that reused one of its sequences must not hide its own answer.
    if (answers_own_sample && cmd.header.measurement_sequence > in_force_sequence_) {
        in_force_sequence_ = cmd.header.measurement_sequence;
    }
    const Pending p{at_us, tvo_host::UnicycleInput{cmd.speed_mps, cmd.turn_rate_radps}};
    const auto at = std::upper_bound(pending_.begin(), pending_.end(), at_us,
                                     [](std::int64_t t, const Pending& q) { return t < q.apply_us; });
    pending_.insert(at, p);
}

void LockstepRun::shadow_literal_plant(const Command& cmd, bool applied)
{
    // The spec's rule read literally: its id, and a sequence it sent newer than the one in force, or a
    // safe stop. It cannot tell a stray's answer from its own when the stray reuses its sequence.
    const Header& h = cmd.header;
    const bool safe_stop = (h.flags & kSafeStop) != 0;
    const bool literal = h.session_id == session_.session_id &&
                         ((sent_sequences_.count(h.measurement_sequence) != 0 && h.measurement_sequence > literal_in_force_) ||
                          safe_stop);
    if (literal && h.measurement_sequence > literal_in_force_) {
        literal_in_force_ = h.measurement_sequence;
    }
    if (literal != applied) {
        ++literal_plant_diffs;
    }
}

void LockstepRun::advance_to(std::int64_t t_us)
{
    auto integrate = [this](std::int64_t to_us) {
        if (to_us > now_us_) {
            plant_.advance(static_cast<double>(to_us - now_us_) * kSPerUs);
            now_us_ = to_us;
        }
    };
    while (!pending_.empty() && pending_.front().apply_us <= t_us) {
        const Pending p = pending_.front();
        pending_.erase(pending_.begin());
        integrate(p.apply_us);
        plant_.hold(0, p.input);
        last_applied_us_ = std::max(p.apply_us, now_us_);
    }
    if (stalled_) {
        plant_.hold(0, tvo_host::UnicycleInput{});
    }
    integrate(t_us);
}

void LockstepRun::crash_node_and_restart()
{
    if (!node_) {
        throw std::runtime_error("this case restarts the node: it needs --node PATH");
    }
    // The telemetry of the last answer first: the kill then never falls between a command and its telemetry.
    ctx_.bus.wait_until([this] { return ctx_.bus.telemetry.size() >= ctx_.bus.commands.size(); }, kAnswerTimeout);
    node_->kill_now();
    node_->spawn(config_.keep_running, config_.node_stderr_path);
    // The new process announces a new boot at once (its counter file never gives one twice).
    const std::int64_t boot = ctx_.bus.await_boot(boot_, kStartTimeout);
    if (boot == 0) {
        throw std::runtime_error("the restarted node announced no new boot (above " + std::to_string(boot_) + ")");
    }
    boot_ = boot;
    start_counters_.reset();   // the new boot's counters start again
}

void LockstepRun::stop()
{
    settle();
    ctx_.bus.pump(std::chrono::milliseconds(100));   // a late extra answer shows up as unexpected
    while (processed_ < ctx_.bus.commands.size()) {
        process(ctx_.bus.commands[processed_++]);
    }
    while (!expected_.empty()) {   // left: ignored or optional messages that got no answer
        const Expect e = expected_.front();
        expected_.pop_front();
        unanswered(e);
    }
    // The node publishes each answer's telemetry right after it (the session asks it every period):
    // the last command's is the last to come.
    const auto same_period = [](const Header& a, const Header& b) {
        return a.utime == b.utime && a.session_id == b.session_id && a.measurement_sequence == b.measurement_sequence;
    };
    if (!ctx_.bus.commands.empty() && ctx_.bus.commands.back().msg.header.measurement_sequence >= 0) {
        const Header last = ctx_.bus.commands.back().msg.header;
        ctx_.bus.wait_until(
            [&] {
                return std::any_of(ctx_.bus.telemetry.rbegin(), ctx_.bus.telemetry.rend(),
                                   [&](const auto& t) { return same_period(t.header, last); });
            },
            kAnswerTimeout);
    }
    const std::size_t commands = ctx_.bus.commands.size();
    const std::size_t telemetry = ctx_.bus.telemetry.size();
    // Each answer's telemetry: same utime, session, sequence, status and flags. The node's own safe stops
    // (sequence -1) have none.
    std::multiset<std::tuple<std::int64_t, std::int32_t, std::int32_t, std::int32_t, std::int32_t>> tel_keys;
    for (const auto& t : ctx_.bus.telemetry) {
        const Header& h = t.header;
        tel_keys.insert({h.utime, h.session_id, h.measurement_sequence, h.status, h.flags});
    }
    long without_telemetry = 0;
    long own_stops = 0;
    std::string first_without;
    for (const auto& rx : ctx_.bus.commands) {
        const Header& c = rx.msg.header;
        const auto it = tel_keys.find({c.utime, c.session_id, c.measurement_sequence, c.status, c.flags});
        if (it != tel_keys.end()) {
            tel_keys.erase(it);
        } else if (c.measurement_sequence == -1) {
            ++own_stops;
        } else if (without_telemetry++ == 0) {
            first_without = " (first: " + describe(rx.msg) + ")";
        }
    }
    tvo_lcm::session_t stop_msg = session_;
    stop_msg.utime = now_us_;
    stop_msg.action = tvo_lcm::session_t::ACTION_STOP;
    const std::size_t first_announcement = ctx_.bus.announcements.size();
    const tvo_lcm::session_ack_t ack = request(stop_msg);
    // The node announces itself at once when a STOP ended its session: its counters at the end.
    const tvo_lcm::node_status_t* idle = ctx_.bus.await_announcement(
        first_announcement, boot_,
        [](const tvo_lcm::node_status_t& s) { return s.state == tvo_lcm::node_status_t::STATE_IDLE; },
        kAnnouncementTimeout);
    if (idle != nullptr && start_counters_) {
        counters_ = counts_between(*start_counters_, idle->counters);
    }
    if (idle != nullptr) {
        final_counters_ = counts_of(idle->counters);
    }
    int exit_code = 0;
    if (node_ && !config_.keep_running) {
        exit_code = node_->wait_exit(kExitTimeout);
    }
    std::ostringstream figure;
    figure << "session " << session_.session_id << ": " << commands << " commands, " << telemetry << " telemetry, "
           << without_telemetry << " answers without their telemetry" << first_without << " (+ " << own_stops
           << " of the node's own safe stops, which have none); STOP " << status_text(ack.status) << ", running "
           << ack.running_session_id << "; announcement after it " << (idle != nullptr ? "heard" : "NOT heard");
    if (node_ && !config_.keep_running) {
        figure << "; node exit code " << exit_code;
    }
    ctx_.report.check(without_telemetry == 0 && ack.status == 0 && ack.running_session_id == -1 && idle != nullptr &&
                          exit_code == 0,
                      "run ends cleanly: a telemetry per answer, STOP acked OK, the node announces itself idle" +
                          std::string(node_ && !config_.keep_running ? ", the node exits with 0" : ""),
                      figure.str());
}

double LockstepRun::max_error_last(std::int64_t periods) const
{
    double worst = 0.0;
    const std::size_t n = errors_.size();
    const std::size_t from = n > static_cast<std::size_t>(periods) ? n - static_cast<std::size_t>(periods) : 0;
    for (std::size_t i = from; i < n; ++i) {
        worst = std::max(worst, errors_[i].second);
    }
    return worst;
}

double LockstepRun::max_error_between(std::int64_t from_utime, std::int64_t to_utime) const
{
    double worst = 0.0;
    for (const auto& [t, e] : errors_) {
        if (t >= from_utime && t < to_utime) {
            worst = std::max(worst, e);
        }
    }
    return worst;
}

// ---- Shared checks -------------------------------------------------------------------------------

void check_tracking(Report& report, const LockstepRun& run, const std::string& what)
{
    const double worst = run.max_error_last(kTrackingWindowPeriods);
    report.check(std::isfinite(worst) && worst < kTrackingBoundM, what + ": the loop tracks (error over the last 1 s)",
                 "max " + fmt(worst) + " m, bound " + fmt(kTrackingBoundM) + " m");
}

void check_genuine(Report& report, const LockstepRun& run, const std::vector<std::int64_t>& fault_steps,
                   long expected_accepted, long expected_stopped)
{
    std::string first;
    for (std::size_t i = 0; i < run.problems.size() && i < 2; ++i) {
        first += (first.empty() ? "; first: " : " | ") + run.problems[i];
    }
    const long want = expected_accepted >= 0 ? expected_accepted : run.genuine_sent - expected_stopped;
    report.check(run.genuine_wrong == expected_stopped && run.genuine_accepted == want,
                 "every genuine sample meant to be accepted is: status 0, applied at a_j",
                 std::to_string(run.genuine_accepted) + " accepted of " + std::to_string(want) + ", " +
                     std::to_string(run.genuine_wrong) + " answered otherwise" + first);
    // Holding after each bad message: the genuine samples held between it and the next one.
    std::vector<long> per_fault(fault_steps.size(), 0);
    long before_first = 0;
    for (const std::int64_t step : run.held_steps) {
        const auto after = std::upper_bound(fault_steps.begin(), fault_steps.end(), step);
        if (after == fault_steps.begin()) {
            ++before_first;
        } else {
            ++per_fault[static_cast<std::size_t>(after - fault_steps.begin() - 1)];
        }
    }
    const long worst = per_fault.empty() ? 0 : *std::max_element(per_fault.begin(), per_fault.end());
    std::string list;
    for (const long h : per_fault) {
        list += (list.empty() ? "" : ",") + std::to_string(h);
    }
    report.check(before_first == 0 && worst <= 1,
                 fault_steps.empty() ? "no period of holding (genuine samples answered HOLDING / non-zero)"
                                     : "at most one period of holding after each bad message",
                 std::to_string(run.genuine_held) + " genuine samples held" +
                     (fault_steps.empty() ? "" : "; per bad message [" + list + "]") +
                     (before_first > 0 ? "; " + std::to_string(before_first) + " before any fault" : ""));
    report.check(run.unexpected_answers == 0, "no command answers a message it should not (or nothing sent)",
                 std::to_string(run.unexpected_answers) + " unexpected");
    report.check(run.stamped_before_measurement == 0, "no answer stamped before the measurement it answers",
                 std::to_string(run.stamped_before_measurement) + " stamped before");
    if (run.literal_plant_diffs > 0) {
        report.note("a plant applying the spec's rule literally (its sequences, newer than in force, or a "
                    "safe stop) treats commands differently from this plant, which knows its own messages",
                    std::to_string(run.literal_plant_diffs) + " commands");
    }
    if (run.plant_watchdog_stops > 0) {
        report.note("the plant's own watchdog stopped the robot (no command for watchdog_periods)",
                    std::to_string(run.plant_watchdog_stops) + " times");
    }
}

void check_same_as_reference(Report& report, const LockstepRun& reference, const LockstepRun& run)
{
    long compared = 0;
    long differ = 0;
    long missing = 0;
    std::string first;
    for (const auto& [seq, answer] : reference.genuine_answers()) {
        const auto it = run.genuine_answers().find(seq);
        if (it == run.genuine_answers().end()) {
            ++missing;
            continue;
        }
        ++compared;
        if (!(it->second == answer)) {
            if (differ == 0) {
                first = "; first at seq " + std::to_string(seq) + ": v " + fmt(it->second.speed_mps, 17) + " vs " +
                        fmt(answer.speed_mps, 17) + ", w " + fmt(it->second.turn_rate_radps, 17) + " vs " +
                        fmt(answer.turn_rate_radps, 17);
            }
            ++differ;
        }
    }
    report.check(differ == 0 && missing == 0 && compared > 0,
                 "nothing kept from a refused message: every genuine answer bit for bit as in the run without it",
                 std::to_string(compared) + " compared, " + std::to_string(differ) + " differ, " +
                     std::to_string(missing) + " missing" + first);
}

void check_counters(Report& report, const LockstepRun& run)
{
    if (!run.counters()) {
        report.check(false, "the node's counters agree with the answers", "no announcement at START or after STOP");
        return;
    }
    const NodeCounts& c = *run.counters();
    report.check(c.accepted == run.genuine_accepted && c.refused == run.refusal_answers + run.silent_refusals &&
                     c.safe_stops == run.safe_stop_answers,
                 "the node's counters (its announcements at START and after STOP) agree with the answers the plant saw",
                 "accepted " + std::to_string(c.accepted) + " (plant " + std::to_string(run.genuine_accepted) +
                     "), refused " + std::to_string(c.refused) + " (plant " + std::to_string(run.refusal_answers) +
                     " answered + " + std::to_string(run.silent_refusals) + " not answered)" + c.refused_by_status + ", safe stops " + std::to_string(c.safe_stops) + " (plant " +
                     std::to_string(run.safe_stop_answers) + "), malformed " + std::to_string(c.malformed) +
                     ", other session " + std::to_string(c.other_session) + ", idle " + std::to_string(c.idle) +
                     ", targets refused " + std::to_string(c.targets_refused));
}

long count_lines(const std::string& path)
{
    std::ifstream in(path);
    long lines = 0;
    std::string line;
    while (std::getline(in, line)) {
        ++lines;
    }
    return lines;
}

void check_outcomes(Report& report, const LockstepRun& run)
{
    for (const auto& o : run.outcomes()) {
        report.check(o.ok, o.label, o.figure);
    }
}

}  // namespace campaign
