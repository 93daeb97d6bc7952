// Session START/STOP with the firmware node; see session.hpp.
#include "session.hpp"

#include <sstream>

namespace tvo_host {

namespace {
// START is repeated at this interval until acknowledged (LCM drops messages nobody subscribed yet).
constexpr std::chrono::milliseconds kStartRepeat{100};
// Parameter block stride per robot for circle and ellipse targets (see session_t.lcm).
constexpr std::size_t kTargetStride = 8;

void fill_targets(const Scenario& scenario, tvo_lcm::session_t* msg)
{
    switch (scenario.kind) {
    case TargetKind::Ellipse:
        msg->target_kind = tvo_lcm::session_t::TARGET_ELLIPSE;
        break;
    case TargetKind::Circle:
        msg->target_kind = tvo_lcm::session_t::TARGET_CIRCLE;
        break;
    case TargetKind::Streamed:
        msg->target_kind = tvo_lcm::session_t::TARGET_STREAMED;
        return;
    }
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        const EllipseTarget& t = scenario.targets[r];
        double* p = msg->target_params + r * kTargetStride;
        p[0] = t.center_m.x();
        p[1] = t.center_m.y();
        if (scenario.kind == TargetKind::Circle) {
            p[2] = t.semi_axis_m.x();
            p[3] = t.omega_radps;
            p[4] = t.phase_rad;
        } else {
            p[2] = t.semi_axis_m.x();
            p[3] = t.semi_axis_m.y();
            p[4] = t.omega_radps;
            p[5] = t.phase_rad;
            p[6] = t.rotation_rad;
        }
    }
}

/// The option the user would change to fix a rejected parameter.
std::string option_for(std::int32_t param, const SimOptions& o)
{
    std::ostringstream out;
    switch (param) {
    case TVO_PARAM_PERIOD: out << "--period-s " << o.period_s; break;
    case TVO_PARAM_DELAY: out << "--delay-s " << o.delay_s; break;
    case TVO_PARAM_FILTER_TF: out << "--filter-tf-s " << o.filter_tf_s; break;
    case TVO_PARAM_GAINS: out << "--gains " << o.gain_kp << ',' << o.gain_kd; break;
    case TVO_PARAM_OMEGA_MAX: out << "--omega-max-radps " << o.omega_max_radps; break;
    case TVO_PARAM_ACCEL_MAX: out << "--accel-max-mps2 " << o.accel_max_mps2; break;
    case TVO_PARAM_SPEED_MAX: out << "--speed-max-mps " << o.speed_max_mps; break;
    case TVO_PARAM_MIN_SPEED: out << "--min-speed-mps " << o.min_speed_mps; break;
    case TVO_PARAM_WATCHDOG: out << "--watchdog-periods " << o.watchdog_periods; break;
    case TVO_PARAM_ROBOT_COUNT: out << "--robots " << o.robots; break;
    default: break;
    }
    return out.str();
}
}  // namespace

tvo_lcm::session_t make_start_session(const SimOptions& o, const Scenario& scenario, std::int64_t session_id)
{
    tvo_lcm::session_t msg{};
    msg.utime = o.start_utime_us;
    msg.session_id = session_id;
    msg.action = tvo_lcm::session_t::ACTION_START;
    msg.epoch_utime = o.start_utime_us;  // the objective's t = 0 is plant time 0
    msg.period_us = o.period_us;
    msg.delay_us = o.delay_us;
    msg.delay_compensation = o.delay_compensation;
    msg.velocity_source = o.position_only ? static_cast<std::int32_t>(tvo_lcm::session_t::VELOCITY_FROM_POSITION)
                                          : static_cast<std::int32_t>(tvo_lcm::session_t::VELOCITY_FROM_POSE);
    msg.filter_tf_s = o.filter_tf_s;
    msg.gain_kp = o.gain_kp;
    msg.gain_kd = o.gain_kd;
    msg.omega_max_radps = o.omega_max_radps;
    msg.accel_max_mps2 = o.accel_max_mps2;
    msg.speed_max_mps = o.speed_max_mps;
    msg.min_speed_mps = o.min_speed_mps;
    msg.watchdog_periods = o.watchdog_periods;
    msg.robot_count = static_cast<std::int32_t>(scenario.robot_count);
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        msg.initial_speed_mps[r] = 0.0;  // the robots start at rest
        msg.tracking_weight[r][0] = scenario.weights[r].x();
        msg.tracking_weight[r][1] = scenario.weights[r].y();
    }
    fill_targets(scenario, &msg);
    return msg;
}

std::string describe_rejection(const tvo_lcm::session_ack_t& ack, const SimOptions& options)
{
    std::ostringstream out;
    out << "the firmware rejected the session (" << tvo_status_str(static_cast<tvo_status_t>(ack.status)) << ")";
    if (ack.bad_param != TVO_PARAM_NONE) {
        out << ": parameter " << tvo_param_str(static_cast<tvo_param_t>(ack.bad_param));
        const std::string option = option_for(ack.bad_param, options);
        if (!option.empty()) {
            out << " (" << option << ")";
        }
    }
    return out.str();
}

SessionClient::SessionClient(LcmTransport& transport, const tvo_lcm::session_t& start)
    : transport_(transport), session_(start)
{
}

void SessionClient::on_session_ack(const tvo_lcm::session_ack_t& ack)
{
    if (ack.session_id == session_.session_id && ack.action == awaited_action_) {
        ack_ = ack;
        acked_ = true;
    }
}

bool SessionClient::await_ack(std::int8_t action, std::chrono::steady_clock::time_point deadline)
{
    awaited_action_ = action;
    while (!acked_) {
        const auto now = std::chrono::steady_clock::now();
        if (now >= deadline) {
            return false;
        }
        const auto left = std::chrono::duration_cast<std::chrono::microseconds>(deadline - now);
        if (transport_.wait(left) == WaitResult::Interrupted) {
            return false;
        }
    }
    return true;
}

bool SessionClient::start(std::chrono::milliseconds timeout, const std::function<bool()>& keep_waiting)
{
    transport_.set_listener(this);
    transport_.set_log_utime(session_.utime);
    acked_ = false;
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (!keep_waiting()) {
            return false;
        }
        transport_.publish(session_);
        if (await_ack(tvo_lcm::session_t::ACTION_START, std::chrono::steady_clock::now() + kStartRepeat)) {
            return true;
        }
    }
    throw TransportError("no session ack from the firmware node within " + std::to_string(timeout.count()) +
                         " ms (is tvo_firmware_node running on the same LCM URL? pass --firmware PATH to spawn it)");
}

bool SessionClient::stop(std::int64_t utime, std::chrono::milliseconds timeout)
{
    transport_.set_listener(this);
    transport_.set_log_utime(utime);
    tvo_lcm::session_t stop = session_;
    stop.utime = utime;
    stop.action = tvo_lcm::session_t::ACTION_STOP;
    acked_ = false;
    transport_.publish(stop);
    return await_ack(tvo_lcm::session_t::ACTION_STOP, std::chrono::steady_clock::now() + timeout);
}

}  // namespace tvo_host
