// Session START/STOP with the firmware node; see session.hpp.
#include "session.hpp"

#include <sstream>
#include <stdexcept>

extern "C" {
#include "tvo/barrier.h"
}

namespace tvo_host {

namespace {
// START is repeated at this interval until acknowledged (LCM drops messages nobody subscribed yet).
constexpr std::chrono::milliseconds kStartRepeat{100};
// Parameter block strides per robot in target_params (see session_t.lcm): circle and ellipse use 8
// values per robot, polynomials 16 (8 coefficients per axis).
constexpr std::size_t kTargetStride = 8;
constexpr std::size_t kPolyRobotStride = 16;

std::int32_t wire_kind(PathKind kind)
{
    switch (kind) {
    case PathKind::Polynomial: return tvo_lcm::session_t::TARGET_POLYNOMIAL;
    case PathKind::Circle: return tvo_lcm::session_t::TARGET_CIRCLE;
    case PathKind::Ellipse: return tvo_lcm::session_t::TARGET_ELLIPSE;
    }
    throw std::logic_error("unknown path kind");
}

std::size_t wire_stride(PathKind kind)
{
    return kind == PathKind::Polynomial ? kPolyRobotStride : kTargetStride;
}

/// One path in the firmware's block layout (p points at the block's first value).
void fill_path(const TargetPath& path, double* p)
{
    if (path.kind() == PathKind::Polynomial) {
        for (std::size_t axis = 0; axis < 2; ++axis) {
            for (std::size_t j = 0; j < kPolyCoeffs; ++j) {
                p[axis * kPolyCoeffs + j] = path.coefficients()[axis][j];
            }
        }
        return;
    }
    const EllipseTarget& e = path.ellipse_params();
    p[0] = e.center_m.x();
    p[1] = e.center_m.y();
    if (path.kind() == PathKind::Circle) {
        p[2] = e.semi_axis_m.x();
        p[3] = e.omega_radps;
        p[4] = e.phase_rad;
    } else {
        p[2] = e.semi_axis_m.x();
        p[3] = e.semi_axis_m.y();
        p[4] = e.omega_radps;
        p[5] = e.phase_rad;
        p[6] = e.rotation_rad;
    }
}

void fill_targets(const Scenario& scenario, tvo_lcm::session_t* msg)
{
    if (scenario.streamed) {
        msg->target_kind = tvo_lcm::session_t::TARGET_STREAMED;
        return;
    }
    // The wire has one target kind for all robots.
    const PathKind kind = scenario.targets[0].kind();
    msg->target_kind = wire_kind(kind);
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        if (scenario.targets[r].kind() != kind) {
            throw std::invalid_argument("scenario " + scenario.name + ": every robot's target must be of one kind");
        }
        fill_path(scenario.targets[r], msg->target_params + r * wire_stride(kind));
    }
}

void fill_barrier(const BarrierOverrides& overrides, tvo_lcm::session_t* msg)
{
    // The firmware's defaults, so that the host states only what a scenario changes.
    tvo_barrier_config_t defaults{};
    if (tvo_barrier_config_default(&defaults) != TVO_OK) {
        throw std::logic_error("tvo_barrier_config_default failed");
    }
    msg->barrier_c0 = overrides.c0.value_or(static_cast<double>(defaults.c0));
    msg->barrier_alpha_c_per_s = overrides.alpha_c_per_s.value_or(static_cast<double>(defaults.alpha_c_per_s));
    msg->barrier_c_max = overrides.c_max.value_or(static_cast<double>(defaults.c_max));
    msg->barrier_delta0 = overrides.delta0.value_or(static_cast<double>(defaults.delta0));
    msg->barrier_alpha_s_per_s = overrides.alpha_s_per_s.value_or(static_cast<double>(defaults.alpha_s_per_s));
    msg->barrier_slack_margin = overrides.slack_margin.value_or(static_cast<double>(defaults.slack_margin));
    msg->barrier_relaxation_degree = overrides.relaxation_degree.value_or(defaults.relaxation_degree);
}

/// Checked copy of a scenario's table into a fixed-size message field.
void require_fits(std::size_t count, std::size_t capacity, const std::string& what, const Scenario& scenario)
{
    if (count > capacity) {
        throw std::invalid_argument("scenario " + scenario.name + ": " + std::to_string(count) + " " + what +
                                    ", the session message carries " + std::to_string(capacity));
    }
}

void fill_constraints(const Scenario& s, tvo_lcm::session_t* msg)
{
    fill_barrier(s.barrier, msg);
    require_fits(s.distances.size(), tvo_lcm::session_t::MAX_DISTANCE_BOUNDS, "distance bounds", s);
    msg->distance_count = static_cast<std::int32_t>(s.distances.size());
    for (std::size_t i = 0; i < s.distances.size(); ++i) {
        const DistanceBound& d = s.distances[i];
        msg->distance_robot_a[i] = static_cast<std::int32_t>(d.robot_a);
        msg->distance_robot_b[i] = static_cast<std::int32_t>(d.robot_b);
        msg->distance_min_m[i] = d.min_m;
        msg->distance_min_rate_mps[i] = d.min_rate_mps;
        msg->distance_max_m[i] = d.max_m;
        msg->distance_max_rate_mps[i] = d.max_rate_mps;
    }
    require_fits(s.halfspaces.size(), tvo_lcm::session_t::MAX_HALFSPACES, "half-spaces", s);
    msg->halfspace_count = static_cast<std::int32_t>(s.halfspaces.size());
    for (std::size_t i = 0; i < s.halfspaces.size(); ++i) {
        const HalfSpace& h = s.halfspaces[i];
        msg->halfspace_robot[i] = static_cast<std::int32_t>(h.robot);
        for (int axis = 0; axis < 2; ++axis) {
            msg->halfspace_normal[i][axis] = h.normal[axis];
            msg->halfspace_normal_rate[i][axis] = h.normal_rate[axis];
        }
        msg->halfspace_bound_m[i] = h.bound_m;
        msg->halfspace_bound_rate_mps[i] = h.bound_rate_mps;
    }
    require_fits(s.obstacles.size(), tvo_lcm::session_t::MAX_OBSTACLES, "obstacles", s);
    msg->robot_radius_m = s.robot_radius_m;
    msg->obstacle_count = static_cast<std::int32_t>(s.obstacles.size());
    for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
        msg->obstacle_center_m[i][0] = s.obstacles[i].center_m.x();
        msg->obstacle_center_m[i][1] = s.obstacles[i].center_m.y();
        msg->obstacle_radius_m[i] = s.obstacles[i].radius_m;
    }
    require_fits(s.offsets.size(), tvo_lcm::session_t::MAX_OFFSETS, "formation offsets", s);
    msg->offset_count = static_cast<std::int32_t>(s.offsets.size());
    for (std::size_t i = 0; i < s.offsets.size(); ++i) {
        const OffsetEquality& o = s.offsets[i];
        msg->offset_robot_a[i] = static_cast<std::int32_t>(o.robot_a);
        msg->offset_robot_b[i] = static_cast<std::int32_t>(o.robot_b);
        msg->offset_kind[i] = wire_kind(o.offset.kind());
        fill_path(o.offset, msg->offset_params[i]);
    }
}

const char* part_name(std::int32_t part)
{
    switch (part) {
    case tvo_lcm::session_ack_t::PART_ROBOTS: return "robots/targets";
    case tvo_lcm::session_ack_t::PART_BARRIER: return "barrier";
    case tvo_lcm::session_ack_t::PART_DISTANCE: return "distance bounds";
    case tvo_lcm::session_ack_t::PART_HALFSPACE: return "half-spaces";
    case tvo_lcm::session_ack_t::PART_OBSTACLES: return "obstacles";
    case tvo_lcm::session_ack_t::PART_OFFSETS: return "formation offsets";
    default: return "unknown";
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
    msg.zoh_aware = o.zoh_aware;
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
    fill_constraints(scenario, &msg);
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
    if (ack.bad_part != tvo_lcm::session_ack_t::PART_NONE) {
        out << ", part of the problem: " << part_name(ack.bad_part) << " (scenario " << options.scenario;
        if (ack.bad_part == tvo_lcm::session_ack_t::PART_BARRIER) {
            out << ", --barrier-* options";
        }
        out << ")";
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
