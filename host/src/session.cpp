// Session START/STOP with the firmware node; see session.hpp.
#include "session.hpp"

#include <sstream>
#include <stdexcept>
#include <utility>

#include "plant_wire.hpp"

extern "C" {
#include "session_codec.h"  // TVO_SESSION_TELEMETRY_DEFAULT_US: the node's default telemetry interval
#include "tvo/barrier.h"
}

namespace tvo_host {

namespace {

/// One time function of the plan as the wire's path_t (every field by name, nothing laid out).
tvo_lcm::path_t wire_path(const TargetPath& path)
{
    tvo_lcm::path_t wire{};
    switch (path.kind()) {
    case PathKind::Polynomial:
        wire.kind = tvo_lcm::path_t::KIND_POLYNOMIAL;
        for (std::size_t axis = 0; axis < 2; ++axis) {
            for (std::size_t j = 0; j < kPolyCoeffs; ++j) {
                wire.coeff[axis][j] = path.coefficients()[axis][j];
            }
        }
        return wire;
    case PathKind::Circle: wire.kind = tvo_lcm::path_t::KIND_CIRCLE; break;
    case PathKind::Ellipse: wire.kind = tvo_lcm::path_t::KIND_ELLIPSE; break;
    }
    const EllipseTarget& e = path.ellipse_params();
    wire.center_m[0] = e.center_m.x();
    wire.center_m[1] = e.center_m.y();
    wire.semi_axis_m[0] = e.semi_axis_m.x();  // a circle's radius
    wire.semi_axis_m[1] = e.semi_axis_m.y();
    wire.omega_radps = e.omega_radps;
    wire.phase_rad = e.phase_rad;
    wire.rotation_rad = e.rotation_rad;
    return wire;
}

/// Checked copy of a scenario's table into a fixed-size message field.
void require_fits(std::size_t count, std::size_t capacity, const std::string& what, const Scenario& scenario)
{
    if (count > capacity) {
        throw std::invalid_argument("scenario " + scenario.name + ": " + std::to_string(count) + " " + what +
                                    ", the session message carries " + std::to_string(capacity));
    }
}

void fill_robots(const Scenario& scenario, tvo_lcm::session_t* msg)
{
    require_fits(scenario.robot_count, tvo_lcm::session_t::MAX_ROBOTS, "robots", scenario);
    msg->robot_count = static_cast<std::int32_t>(scenario.robot_count);
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        tvo_lcm::robot_t& robot = msg->robot[r];
        robot.initial_speed_mps = 0.0;  // the robots start at rest
        robot.tracking_weight[0] = scenario.weights[r].x();
        robot.tracking_weight[1] = scenario.weights[r].y();
        if (scenario.streamed) {
            robot.target.kind = tvo_lcm::path_t::KIND_STREAMED;
        } else {
            robot.target = wire_path(scenario.targets[r]);
        }
    }
}

tvo_lcm::barrier_t wire_barrier(const BarrierOverrides& overrides)
{
    // The firmware's defaults, so that the host states only what a scenario changes.
    tvo_barrier_config_t defaults{};
    if (tvo_barrier_config_default(&defaults) != TVO_OK) {
        throw std::logic_error("tvo_barrier_config_default failed");
    }
    tvo_lcm::barrier_t b{};
    b.c0 = overrides.c0.value_or(static_cast<double>(defaults.c0));
    b.alpha_c_per_s = overrides.alpha_c_per_s.value_or(static_cast<double>(defaults.alpha_c_per_s));
    b.c_max = overrides.c_max.value_or(static_cast<double>(defaults.c_max));
    b.delta0 = overrides.delta0.value_or(static_cast<double>(defaults.delta0));
    b.alpha_s_per_s = overrides.alpha_s_per_s.value_or(static_cast<double>(defaults.alpha_s_per_s));
    b.slack_margin = overrides.slack_margin.value_or(static_cast<double>(defaults.slack_margin));
    b.relaxation_degree = overrides.relaxation_degree.value_or(defaults.relaxation_degree);
    return b;
}

void fill_constraints(const Scenario& s, tvo_lcm::session_t* msg)
{
    msg->barrier = wire_barrier(s.barrier);
    require_fits(s.distances.size(), tvo_lcm::session_t::MAX_DISTANCE_BOUNDS, "distance bounds", s);
    msg->distance_count = static_cast<std::int32_t>(s.distances.size());
    for (std::size_t i = 0; i < s.distances.size(); ++i) {
        const DistanceBound& d = s.distances[i];
        tvo_lcm::distance_bound_t& w = msg->distance[i];
        w.robot_a = static_cast<std::int32_t>(d.robot_a);
        w.robot_b = static_cast<std::int32_t>(d.robot_b);
        w.min_m = d.min_m;
        w.min_rate_mps = d.min_rate_mps;
        w.max_m = d.max_m;
        w.max_rate_mps = d.max_rate_mps;
    }
    require_fits(s.halfspaces.size(), tvo_lcm::session_t::MAX_HALFSPACES, "half-spaces", s);
    msg->halfspace_count = static_cast<std::int32_t>(s.halfspaces.size());
    for (std::size_t i = 0; i < s.halfspaces.size(); ++i) {
        const HalfSpace& h = s.halfspaces[i];
        tvo_lcm::halfspace_t& w = msg->halfspace[i];
        w.robot = static_cast<std::int32_t>(h.robot);
        for (int axis = 0; axis < 2; ++axis) {
            w.normal[axis] = h.normal[axis];
            w.normal_rate[axis] = h.normal_rate[axis];
        }
        w.bound_m = h.bound_m;
        w.bound_rate_mps = h.bound_rate_mps;
    }
    require_fits(s.obstacles.size(), tvo_lcm::session_t::MAX_OBSTACLES, "obstacles", s);
    msg->robot_radius_m = s.robot_radius_m;
    msg->obstacle_count = static_cast<std::int32_t>(s.obstacles.size());
    for (std::size_t i = 0; i < s.obstacles.size(); ++i) {
        tvo_lcm::obstacle_t& w = msg->obstacle[i];
        w.center_m[0] = s.obstacles[i].center_m.x();
        w.center_m[1] = s.obstacles[i].center_m.y();
        w.radius_m = s.obstacles[i].radius_m;
    }
    require_fits(s.offsets.size(), tvo_lcm::session_t::MAX_OFFSETS, "formation offsets", s);
    msg->offset_count = static_cast<std::int32_t>(s.offsets.size());
    for (std::size_t i = 0; i < s.offsets.size(); ++i) {
        const OffsetEquality& o = s.offsets[i];
        tvo_lcm::offset_t& w = msg->offset[i];
        w.robot_a = static_cast<std::int32_t>(o.robot_a);
        w.robot_b = static_cast<std::int32_t>(o.robot_b);
        w.offset = wire_path(o.offset);
    }
}

/// The option the user would change to fix a rejected parameter.
std::string option_for(std::int32_t param, const SimOptions& o)
{
    std::ostringstream out;
    switch (param) {
    case tvo_lcm::session_ack_t::PARAM_PERIOD: out << "--period-s " << o.period_s; break;
    case tvo_lcm::session_ack_t::PARAM_DELAY: out << "--delay-s " << o.delay_s; break;
    case tvo_lcm::session_ack_t::PARAM_FILTER_TF: out << "--filter-tf-s " << o.filter_tf_s; break;
    case tvo_lcm::session_ack_t::PARAM_GAINS: out << "--gains " << o.gain_kp << ',' << o.gain_kd; break;
    case tvo_lcm::session_ack_t::PARAM_OMEGA_MAX: out << "--omega-max-radps " << o.omega_max_radps; break;
    case tvo_lcm::session_ack_t::PARAM_ACCEL_MAX: out << "--accel-max-mps2 " << o.accel_max_mps2; break;
    case tvo_lcm::session_ack_t::PARAM_SPEED_MAX: out << "--speed-max-mps " << o.speed_max_mps; break;
    case tvo_lcm::session_ack_t::PARAM_MIN_SPEED: out << "--min-speed-mps " << o.min_speed_mps; break;
    case tvo_lcm::session_ack_t::PARAM_WATCHDOG: out << "--watchdog-periods " << o.watchdog_periods; break;
    case tvo_lcm::session_ack_t::PARAM_ROBOT_COUNT: out << "--robots " << o.robots; break;
    case tvo_lcm::session_ack_t::PARAM_EPOCH: out << "--start-utime-us " << o.start_utime_us; break;
    case tvo_lcm::session_ack_t::PARAM_TELEMETRY_EVERY: out << "--telemetry-every " << o.telemetry_every; break;
    default: break;
    }
    return out.str();
}

/// The different boots of a START's robots, in robot order of first appearance.
std::vector<std::int64_t> named_boots(const tvo_lcm::session_t& s)
{
    std::vector<std::int64_t> named;
    for (std::int32_t r = 0; r < s.robot_count && r < tvo_lcm::session_t::MAX_ROBOTS; ++r) {
        if (std::find(named.begin(), named.end(), s.node_boot_id[r]) == named.end()) {
            named.push_back(s.node_boot_id[r]);
        }
    }
    return named;
}
}  // namespace

std::int64_t telemetry_every_periods(std::int32_t telemetry_every, std::int64_t period_us)
{
    if (telemetry_every > 0) {
        return telemetry_every;
    }
    return (TVO_SESSION_TELEMETRY_DEFAULT_US + period_us - 1) / std::max<std::int64_t>(period_us, 1);
}

tvo_lcm::session_t make_start_session(const SimOptions& o, const Scenario& scenario, std::int32_t session_id,
                                      std::int64_t utime, std::int64_t epoch_utime, const NodeBoots& boots)
{
    tvo_lcm::session_t msg{};
    msg.utime = utime;
    msg.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
    msg.session_id = session_id;
    msg.action = tvo_lcm::session_t::ACTION_START;
    for (std::size_t r = 0; r < scenario.robot_count; ++r) {
        msg.node_boot_id[r] = boots[r];
    }
    msg.clock_source = o.realtime ? static_cast<std::int32_t>(tvo_lcm::session_t::CLOCK_NODE)
                                  : static_cast<std::int32_t>(tvo_lcm::session_t::CLOCK_PLANT);
    msg.epoch_utime = epoch_utime;
    msg.period_us = o.period_us;
    msg.delay_us = o.delay_us;
    msg.delay_compensation = o.delay_compensation;
    msg.zoh_aware = o.zoh_aware;
    msg.watchdog_periods = o.watchdog_periods;
    msg.telemetry_every = o.telemetry_every;
    msg.plant_kind = tvo_lcm::session_t::PLANT_UNICYCLE;
    msg.velocity_source = o.position_only ? static_cast<std::int32_t>(tvo_lcm::session_t::VELOCITY_FROM_POSITION)
                                          : static_cast<std::int32_t>(tvo_lcm::session_t::VELOCITY_FROM_POSE);
    msg.filter_tf_s = o.filter_tf_s;
    msg.gain_kp = o.gain_kp;
    msg.gain_kd = o.gain_kd;
    msg.omega_max_radps = o.omega_max_radps;
    msg.accel_max_mps2 = o.accel_max_mps2;
    msg.speed_max_mps = o.speed_max_mps;
    msg.min_speed_mps = o.min_speed_mps;
    fill_robots(scenario, &msg);
    fill_constraints(scenario, &msg);
    return msg;
}

std::string describe_rejection(const tvo_lcm::session_ack_t& ack, const SimOptions& options)
{
    std::ostringstream out;
    out << "the firmware rejected the session (" << tvo_protocol_status_str(ack.status) << ")";
    if (ack.own_robot >= 0) {
        out << " at the node of robot " << static_cast<int>(ack.own_robot);
    }
    if (ack.bad_param != tvo_lcm::session_ack_t::PARAM_NONE) {
        out << ": parameter " << tvo_protocol_param_str(ack.bad_param);
        const std::string option = option_for(ack.bad_param, options);
        if (!option.empty()) {
            out << " (" << option << ")";
        }
    }
    if (ack.bad_part != tvo_lcm::session_ack_t::PART_NONE) {
        out << ", part of the problem: " << tvo_protocol_part_str(ack.bad_part);
        if (ack.bad_index >= 0) {
            out << ", entry " << ack.bad_index;
        }
        out << " (scenario " << options.scenario;
        if (ack.bad_part == tvo_lcm::session_ack_t::PART_BARRIER) {
            out << ", --barrier-* options";
        }
        out << ")";
    }
    return out.str();
}

std::optional<NodeBoots> await_nodes(LcmTransport& transport, std::size_t robots, std::chrono::milliseconds timeout,
                                     const std::function<bool()>& keep_waiting)
{
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    std::optional<NodeBoots> boots = transport.nodes().assignment(robots);
    while (!boots) {
        if (!keep_waiting()) {
            return std::nullopt;
        }
        const auto now = std::chrono::steady_clock::now();
        if (now >= deadline) {
            throw TransportError("no node for every robot of the run announced itself on " TVO_CHANNEL_NODE " within " +
                                 std::to_string(timeout.count()) + " ms (heard: " + transport.nodes().describe() +
                                 "; a run of " + std::to_string(robots) +
                                 " robot(s) needs one node of every robot, or one node per robot: "
                                 "is tvo_firmware_node running on the same LCM URL" +
                                 (transport.keyed() ? std::string(", with the same --key-file") : std::string()) +
                                 "? pass --firmware PATH to spawn it)");
        }
        // A node announces itself every 250 ms while idle: short slices notice it and keep_waiting promptly.
        transport.wait(std::min(std::chrono::duration_cast<std::chrono::microseconds>(deadline - now),
                                std::chrono::microseconds(50000)));
        boots = transport.nodes().assignment(robots);
    }
    for (std::size_t r = 0; r < robots; ++r) {
        const tvo_lcm::node_status_t* node = transport.nodes().of_boot((*boots)[r]);
        if (node != nullptr && static_cast<std::size_t>(node->max_robots) < robots) {
            throw TransportError("the node " +
                                 (node->own_robot >= 0 ? "of robot " + std::to_string(node->own_robot)
                                                       : std::string("of every robot")) +
                                 " (boot " + std::to_string(node->boot_id) + ") takes sessions of up to " +
                                 std::to_string(node->max_robots) + " robots; this run has " + std::to_string(robots) +
                                 " (a node built with larger limits takes more: tvo_firmware_node_fleet)");
        }
    }
    return boots;
}

SessionClient::SessionClient(LcmTransport& transport, const tvo_lcm::session_t& start,
                             std::function<std::int64_t()> stamp)
    : transport_(transport), session_(start), stamp_(std::move(stamp)), named_(named_boots(start))
{
}

NodeBoots SessionClient::boots() const
{
    NodeBoots boots{};
    std::copy(std::begin(session_.node_boot_id), std::end(session_.node_boot_id), boots.begin());
    return boots;
}

void SessionClient::begin_exchange(std::int8_t action)
{
    awaited_action_ = action;
    acked_.assign(named_.size(), false);
    refusal_.reset();
    ack_ = tvo_lcm::session_ack_t{};
}

bool SessionClient::exchange_done() const
{
    return refusal_.has_value() || std::all_of(acked_.begin(), acked_.end(), [](bool b) { return b; });
}

void SessionClient::on_session_ack(const tvo_lcm::session_ack_t& ack)
{
    if (ack.session_id != session_.session_id || ack.action != awaited_action_) {
        return;
    }
    const auto named = std::find(named_.begin(), named_.end(), ack.boot_id);
    if (named == named_.end()) {
        return;  // not a node this session names (an ack of another boot cannot answer it)
    }
    acked_[static_cast<std::size_t>(named - named_.begin())] = true;
    ack_ = ack;
    if (ack.status != TVO_OK && !refusal_) {
        refusal_ = ack;
    }
}

void SessionClient::publish_start(std::optional<std::int64_t> utime)
{
    if (!first_copy_) {
        session_.utime = utime.value_or(stamp_());
    }
    first_copy_ = false;
    transport_.set_log_utime(session_.utime);
    transport_.publish(session_);
}

bool SessionClient::await_exchange(std::chrono::steady_clock::time_point deadline)
{
    while (!exchange_done()) {
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
    begin_exchange(tvo_lcm::session_t::ACTION_START);
    first_copy_ = true;
    repeats_.reset();
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        if (!keep_waiting()) {
            return false;
        }
        const auto now = std::chrono::steady_clock::now();
        if (repeats_.due(now)) {
            publish_start(std::nullopt);
            repeats_.sent(now);
        }
        if (await_exchange(std::min(deadline, repeats_.next(now)))) {
            return true;
        }
    }
    // A keyed node drops what it cannot verify without a word, so a key mismatch looks like silence.
    throw TransportError("no session ack from every named node within " + std::to_string(timeout.count()) +
                         " ms (is tvo_firmware_node running on the same LCM URL" +
                         (transport_.keyed() ? std::string(", with the same --key-file") : std::string()) +
                         "? pass --firmware PATH to spawn it)");
}

void SessionClient::restart(std::int32_t session_id, const NodeBoots& boots, std::int64_t utime)
{
    session_.session_id = session_id;
    session_.action = tvo_lcm::session_t::ACTION_START;
    session_.utime = utime;
    for (std::int32_t r = 0; r < session_.robot_count; ++r) {
        session_.node_boot_id[r] = boots[static_cast<std::size_t>(r)];
    }
    named_ = named_boots(session_);
    begin_exchange(tvo_lcm::session_t::ACTION_START);
    first_copy_ = true;
    repeats_.reset();
}

bool SessionClient::service(std::optional<std::int64_t> utime)
{
    if (exchange_done()) {
        return true;
    }
    const auto now = std::chrono::steady_clock::now();
    if (repeats_.due(now)) {
        publish_start(utime);
        repeats_.sent(now);
    }
    return false;
}

bool SessionClient::stop(std::int64_t utime, std::chrono::milliseconds timeout)
{
    transport_.set_listener(this);
    transport_.set_log_utime(utime);
    tvo_lcm::session_t stop = session_;
    stop.utime = utime;
    stop.action = tvo_lcm::session_t::ACTION_STOP;
    begin_exchange(tvo_lcm::session_t::ACTION_STOP);
    transport_.publish(stop);
    return await_exchange(std::chrono::steady_clock::now() + timeout);
}

}  // namespace tvo_host
