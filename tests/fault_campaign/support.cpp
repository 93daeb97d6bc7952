// The fault campaign's plumbing; see support.hpp.
#include "support.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "target_path.hpp"

extern "C" {
#include "auth_key_file.h"
}

extern "C" {
#include "tvo/barrier.h"
}

extern char** environ;

namespace campaign {

namespace {
// The node computes in float32: a limit sent as a double is held as the nearest float, at most half
// an ulp (6e-8 relative) above it. 1e-6 admits that rounding and nothing a real overshoot would be.
constexpr double kLimitRelTol = 1e-6;
// Longest single LCM wait, so deadlines are noticed promptly.
constexpr int kSliceMs = 20;
constexpr double kPi = 3.14159265358979323846;
}  // namespace

void Report::begin_case(const std::string& name)
{
    case_ = name;
    std::cout << "== case " << name << std::endl;
}

bool Report::check(bool ok, const std::string& what, const std::string& figure)
{
    ++checks_;
    if (!ok) {
        ++failures_;
    }
    std::cout << (ok ? "PASS " : "FAIL ") << case_ << ": " << what << " (" << figure << ")" << std::endl;
    return ok;
}

void Report::note(const std::string& what, const std::string& figure)
{
    std::cout << "NOTE " << case_ << ": " << what << " (" << figure << ")" << std::endl;
}

std::string status_text(std::int32_t status)
{
    return "status " + std::to_string(status) + " (" + tvo_protocol_status_str(status) + ")";
}

std::string fmt(double value, int precision)
{
    std::ostringstream out;
    out.precision(precision);
    out << value;
    return out.str();
}

std::int64_t monotonic_us()
{
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return static_cast<std::int64_t>(ts.tv_sec) * 1000000 + ts.tv_nsec / 1000;
}

// ---- Bus -----------------------------------------------------------------------------------------

Bus::Bus(const std::string& url) : lcm_(url)
{
    if (!lcm_.good()) {
        throw std::runtime_error("cannot open LCM at '" + url + "'");
    }
    lcm_.subscribe(TVO_CHANNEL_COMMAND, &Bus::on_frame, this)->setQueueCapacity(0);  // LCM drops past 30, silently
    lcm_.subscribe(TVO_CHANNEL_TELEMETRY, &Bus::on_frame, this)->setQueueCapacity(0);
    lcm_.subscribe(TVO_CHANNEL_SESSION_ACK, &Bus::on_frame, this);
    lcm_.subscribe(TVO_CHANNEL_NODE, &Bus::on_frame, this);
}

Bus::~Bus()
{
    tvo_auth_clear(&auth_);
}

void Bus::set_key(const std::uint8_t (&key)[TVO_AUTH_KEY_BYTES], std::uint32_t sender_id)
{
    // As tvo_sim's transport: counters follow the wall clock, so every run of a case (and a restarted
    // node) sees this plant's counters rise.
    tvo_auth_status_t status = tvo_auth_init(&auth_, key, sender_id, 1u);
    if (status == TVO_AUTH_OK) {
        status = tvo_auth_follow_clock(&auth_, tvo_auth_wall_clock_counter);
    }
    if (status != TVO_AUTH_OK) {
        throw std::runtime_error(std::string("authentication set-up failed: ") + tvo_auth_status_str(status));
    }
    sent.clear();
    dropped_unauthenticated = 0;
    dropped_replayed = 0;
}

void Bus::clear_key()
{
    tvo_auth_clear(&auth_);
    sent.clear();
}

std::vector<std::uint8_t> signed_frame(tvo_auth_t* signer, const char* channel, std::vector<std::uint8_t> message)
{
    const std::size_t length = message.size();
    message.resize(length + TVO_AUTH_TRAILER_BYTES);
    std::size_t signed_length = 0;
    const tvo_auth_status_t status =
        tvo_auth_sign(signer, channel, message.data(), length, message.size(), &signed_length);
    if (status != TVO_AUTH_OK) {
        throw std::runtime_error(std::string("cannot sign for ") + channel + ": " + tvo_auth_status_str(status));
    }
    message.resize(signed_length);
    return message;
}

std::vector<std::uint8_t> Bus::sign(const char* channel, std::vector<std::uint8_t> message)
{
    return signed_frame(&auth_, channel, std::move(message));
}

template <class M>
void Bus::publish_message(const char* channel, const M& msg)
{
    if (!keyed()) {
        lcm_.publish(channel, &msg);
        return;
    }
    std::vector<std::uint8_t> frame = sign(channel, encode(msg));
    publish_raw(channel, frame);
    sent.push_back(Frame{channel, std::move(frame)});
}

void Bus::publish(const Sample& msg) { publish_message(TVO_CHANNEL_SAMPLE, msg); }
void Bus::publish(const tvo_lcm::session_t& msg) { publish_message(TVO_CHANNEL_SESSION, msg); }
void Bus::publish(const tvo_lcm::target_t& msg) { publish_message(TVO_CHANNEL_TARGET, msg); }

void Bus::publish_raw(const char* channel, const std::vector<std::uint8_t>& bytes)
{
    lcm_.publish(channel, bytes.data(), static_cast<unsigned int>(bytes.size()));
}

bool Bus::wait_until(const std::function<bool()>& done, std::chrono::microseconds timeout)
{
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (!done()) {
        const auto left =
            std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
        if (left.count() <= 0) {
            return done();
        }
        lcm_.handleTimeout(static_cast<int>(std::min<std::int64_t>(left.count(), kSliceMs)));
    }
    return true;
}

void Bus::pump(std::chrono::microseconds duration)
{
    wait_until([] { return false; }, duration);
}

void Bus::clear()
{
    pump(std::chrono::milliseconds(50));
    commands.clear();
    telemetry.clear();
    acks.clear();
    // The announcements stay: the node's boot is known from them, whoever runs next.
}

std::int64_t Bus::node_boot() const
{
    std::int64_t boot = 0;
    for (const Announcement& a : announcements) {
        if (a.status.own_robot == -1 && a.status.protocol_version == tvo_lcm::node_status_t::PROTOCOL_VERSION) {
            boot = std::max(boot, a.status.boot_id);
        }
    }
    return boot;
}

std::int64_t Bus::await_boot(std::int64_t above, std::chrono::milliseconds timeout)
{
    wait_until([&] { return node_boot() > above; }, timeout);
    return node_boot() > above ? node_boot() : 0;
}

const tvo_lcm::node_status_t* Bus::await_announcement(std::size_t after, std::int64_t boot,
                                                      const std::function<bool(const tvo_lcm::node_status_t&)>& ok,
                                                      std::chrono::milliseconds timeout)
{
    const tvo_lcm::node_status_t* found = nullptr;
    wait_until(
        [&] {
            for (std::size_t i = after; i < announcements.size(); ++i) {
                if (announcements[i].status.boot_id == boot && ok(announcements[i].status)) {
                    found = &announcements[i].status;
                    return true;
                }
            }
            return false;
        },
        timeout);
    return found;
}

void Bus::on_frame(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
{
    const auto* data = static_cast<const std::uint8_t*>(rbuf->data);
    std::size_t size = rbuf->data_size;
    if (keyed()) {
        const tvo_auth_status_t status = tvo_auth_open(&auth_, channel.c_str(), data, size, &size);
        if (status != TVO_AUTH_OK) {
            ++(status == TVO_AUTH_ERR_REPLAY ? dropped_replayed : dropped_unauthenticated);
            return;
        }
    }
    const int length = static_cast<int>(size);
    if (channel == TVO_CHANNEL_COMMAND) {
        Command msg{};
        if (msg.decode(data, 0, length) >= 0) {
            commands.push_back(ReceivedCommand{msg, monotonic_us()});
        }
    } else if (channel == TVO_CHANNEL_NODE) {
        tvo_lcm::node_status_t msg{};
        if (msg.decode(data, 0, length) >= 0) {
            announcements.push_back(Announcement{msg, monotonic_us()});
        }
    } else if (channel == TVO_CHANNEL_TELEMETRY) {
        tvo_lcm::telemetry_t msg{};
        if (msg.decode(data, 0, length) >= 0) {
            telemetry.push_back(msg);
        }
    } else if (channel == TVO_CHANNEL_SESSION_ACK) {
        tvo_lcm::session_ack_t msg{};
        if (msg.decode(data, 0, length) >= 0) {
            acks.push_back(msg);
        }
    }
}

// ---- NodeProcess ---------------------------------------------------------------------------------

NodeProcess::NodeProcess(std::string path, std::string url, std::string key_file)
    : path_(std::move(path)), url_(std::move(url)), key_file_(std::move(key_file))
{
}

NodeProcess::~NodeProcess()
{
    terminate();
}

void NodeProcess::spawn(bool keep_running, const std::string& stderr_path)
{
    if (access(path_.c_str(), X_OK) != 0) {
        throw std::runtime_error("cannot execute the node '" + path_ + "': " + std::strerror(errno));
    }
    std::vector<std::string> args{path_, "--lcm-url", url_, "--exit-with-parent", "--boot-file", kBootFile};
    if (keep_running) {
        args.emplace_back("--keep-running");
    }
    if (!key_file_.empty()) {
        args.emplace_back("--key-file");
        args.emplace_back(key_file_);
    }
    std::vector<char*> argv;
    for (std::string& arg : args) {
        argv.push_back(arg.data());
    }
    argv.push_back(nullptr);
    exit_code_ = -1;
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    if (!stderr_path.empty()) {
        posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_path.c_str(), O_WRONLY | O_CREAT | O_APPEND,
                                         0644);
    }
    const int err = posix_spawn(&pid_, path_.c_str(), &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (err != 0) {
        pid_ = -1;
        throw std::runtime_error("cannot start the node '" + path_ + "': " + std::strerror(err));
    }
}

bool NodeProcess::running()
{
    if (pid_ <= 0) {
        return false;
    }
    int status = 0;
    const pid_t done = waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
        exit_code_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
        pid_ = -1;
        return false;
    }
    return done == 0;
}

void NodeProcess::kill_now()
{
    if (running()) {
        kill(pid_, SIGKILL);
        wait_exit(std::chrono::milliseconds(10000));
    }
}

int NodeProcess::wait_exit(std::chrono::milliseconds timeout)
{
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (running()) {
        if (std::chrono::steady_clock::now() >= deadline) {
            return -1;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return exit_code_;
}

void NodeProcess::terminate()
{
    if (running()) {
        kill(pid_, SIGTERM);
        if (wait_exit(std::chrono::milliseconds(2000)) < 0) {
            kill_now();
        }
    }
}

// ---- The session ---------------------------------------------------------------------------------

tvo_lcm::session_t demo_session(std::int32_t session_id, std::int64_t start_utime_us, std::int64_t epoch_utime_us,
                                const Timing& timing, std::int64_t node_boot)
{
    tvo_lcm::session_t s{};
    s.utime = start_utime_us;
    s.protocol_version = tvo_lcm::node_status_t::PROTOCOL_VERSION;
    s.session_id = session_id;
    s.action = tvo_lcm::session_t::ACTION_START;
    s.node_boot_id[0] = node_boot;
    s.telemetry_every = 1;  // a telemetry after every answer: the campaign checks each
    s.clock_source = timing.clock_source;
    s.epoch_utime = epoch_utime_us;
    s.period_us = timing.period_us;
    s.delay_us = timing.delay_us;
    s.delay_compensation = true;
    s.zoh_aware = false;
    s.watchdog_periods = timing.watchdog_periods;
    s.plant_kind = tvo_lcm::session_t::PLANT_UNICYCLE;
    s.velocity_source = tvo_lcm::session_t::VELOCITY_FROM_POSE;
    s.filter_tf_s = 0.05;
    s.gain_kp = 40.0;
    s.gain_kd = 13.0;
    s.omega_max_radps = 2.0 * kPi;
    s.accel_max_mps2 = 15.0;
    s.speed_max_mps = 5.0;
    s.min_speed_mps = 0.05;
    s.robot_count = 1;
    tvo_lcm::robot_t& robot = s.robot[0];
    robot.initial_speed_mps = 0.0;
    robot.tracking_weight[0] = 1.0;
    robot.tracking_weight[1] = 1.0;
    robot.target.kind = tvo_lcm::path_t::KIND_ELLIPSE;
    robot.target.center_m[0] = 0.0;
    robot.target.center_m[1] = 0.0;
    robot.target.semi_axis_m[0] = 3.0;
    robot.target.semi_axis_m[1] = 1.5;
    robot.target.omega_radps = 2.0 * kPi / 10.0;
    robot.target.phase_rad = 0.0;
    robot.target.rotation_rad = 0.0;
    // The firmware's own barrier defaults (unused without inequalities, but a valid block).
    tvo_barrier_config_t barrier{};
    if (tvo_barrier_config_default(&barrier) != TVO_OK) {
        throw std::logic_error("tvo_barrier_config_default failed");
    }
    s.barrier.c0 = static_cast<double>(barrier.c0);
    s.barrier.alpha_c_per_s = static_cast<double>(barrier.alpha_c_per_s);
    s.barrier.c_max = static_cast<double>(barrier.c_max);
    s.barrier.delta0 = static_cast<double>(barrier.delta0);
    s.barrier.alpha_s_per_s = static_cast<double>(barrier.alpha_s_per_s);
    s.barrier.slack_margin = static_cast<double>(barrier.slack_margin);
    s.barrier.relaxation_degree = barrier.relaxation_degree;
    return s;
}

void demo_target(const tvo_lcm::session_t& session, std::int64_t utime_us, double* x_m, double* y_m)
{
    const tvo_lcm::path_t& p = session.robot[0].target;
    tvo_host::EllipseTarget e;
    e.center_m = Eigen::Vector2d(p.center_m[0], p.center_m[1]);
    e.semi_axis_m = Eigen::Vector2d(p.semi_axis_m[0], p.semi_axis_m[1]);
    e.omega_radps = p.omega_radps;
    e.phase_rad = p.phase_rad;
    e.rotation_rad = p.rotation_rad;
    const Eigen::Vector2d y = e.position(static_cast<double>(utime_us - session.epoch_utime) * 1e-6);
    *x_m = y.x();
    *y_m = y.y();
}

// ---- CommandAudit --------------------------------------------------------------------------------

void CommandAudit::add(const Command& cmd)
{
    ++commands;
    const bool safe_stop = (cmd.header.flags & static_cast<std::int32_t>(Header::FLAG_SAFE_STOP)) != 0;
    safe_stops += safe_stop ? 1 : 0;
    const double v = cmd.speed_mps;
    const double w = cmd.turn_rate_radps;
    const bool finite = cmd.header.robot == 0 && std::isfinite(v) && std::isfinite(w);  // another robot: a bad command
    if (std::isfinite(v) && std::isfinite(w)) {
        max_abs_omega = std::max(max_abs_omega, std::fabs(w));
        max_abs_speed = std::max(max_abs_speed, std::fabs(v));
    }
    const bool within =
        std::fabs(w) <= omega_max_radps * (1.0 + kLimitRelTol) && std::fabs(v) <= speed_max_mps * (1.0 + kLimitRelTol);
    const bool zero = v == 0.0 && w == 0.0;
    non_finite += finite ? 0 : 1;
    beyond_limit += (finite && !within) ? 1 : 0;
    safe_stop_not_zero += (safe_stop && !zero) ? 1 : 0;
}

void CommandAudit::report(Report& report) const
{
    report.check(non_finite == 0, "no command with a non-finite value",
                 std::to_string(non_finite) + " of " + std::to_string(commands) + " commands");
    report.check(beyond_limit == 0, "no command beyond a limit (|omega| <= omega_max, |v| <= speed_max)",
                 std::to_string(beyond_limit) + " beyond; max |omega| " + fmt(max_abs_omega, 9) + " rad/s of " +
                     fmt(omega_max_radps, 9) + ", max |v| " + fmt(max_abs_speed, 4) + " m/s of " +
                     fmt(speed_max_mps, 3));
    report.check(safe_stop_not_zero == 0, "every safe stop is exactly v = omega = 0",
                 std::to_string(safe_stop_not_zero) + " of " + std::to_string(safe_stops) + " safe stops not zero");
}

}  // namespace campaign
