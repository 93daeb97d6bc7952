// The fault campaign's plumbing: printed checks, the LCM bus as the plant sees it, the node as a
// child process, and the START message of the default ellipse session.
#pragma once

#include <sys/types.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "tvo_lcm/node_status_t.hpp"
#include "tvo_lcm/session_ack_t.hpp"
#include "tvo_lcm/session_t.hpp"
#include "tvo_lcm/target_t.hpp"
#include "tvo_lcm/telemetry_t.hpp"
#include "tvo_lcm/unicycle_command_t.hpp"
#include "tvo_lcm/unicycle_sample_t.hpp"

extern "C" {
#include "auth.h"
#include "channels.h"
#include "tvo/status.h"
}

namespace campaign {

/// The campaign's plant has one robot: its sample and the node's command for it (wire v3).
using Sample = tvo_lcm::unicycle_sample_t;
using Command = tvo_lcm::unicycle_command_t;
using Header = tvo_lcm::command_header_t;

/// One line per check, "PASS|FAIL <case>: <what> (<measured figure>)"; counts the failures.
class Report {
public:
    void begin_case(const std::string& name);
    bool check(bool ok, const std::string& what, const std::string& figure);
    /// A measured figure that is not a pass/fail criterion.
    void note(const std::string& what, const std::string& figure);
    int failures() const { return failures_; }
    int checks() const { return checks_; }

private:
    std::string case_;
    int failures_{0};
    int checks_{0};
};

/// "status 16 (implausible stamp)".
std::string status_text(std::int32_t status);
std::string fmt(double value, int precision = 3);

/// Plant-side monotonic clock in microseconds (CLOCK_MONOTONIC).
std::int64_t monotonic_us();

struct ReceivedCommand {
    Command msg;
    std::int64_t arrival_mono_us{0};
};

/// A node's announcement (TVO_NODE) as it arrived.
struct Announcement {
    tvo_lcm::node_status_t status;
    std::int64_t arrival_mono_us{0};
};

/// One frame as it went on the wire: a channel and its bytes (with the trailer on a keyed bus).
struct Frame {
    std::string channel;
    std::vector<std::uint8_t> bytes;
};

/// message followed by its authentication trailer from signer (consumes one of its counters).
std::vector<std::uint8_t> signed_frame(tvo_auth_t* signer, const char* channel, std::vector<std::uint8_t> message);

/// The plant's LCM endpoint: publishes on the protocol's channels, keeps every command, telemetry,
/// ack and node announcement in arrival order. Keyed (set_key), it is a genuine key holder as tvo_sim is: it signs what
/// it publishes (counters following the wall clock), drops what does not open, and records the
/// frames it sent (for the replay attacks).
class Bus {
public:
    explicit Bus(const std::string& url);
    ~Bus();
    Bus(const Bus&) = delete;
    Bus& operator=(const Bus&) = delete;

    void publish(const Sample& msg);
    void publish(const tvo_lcm::session_t& msg);
    void publish(const tvo_lcm::target_t& msg);
    /// Bytes exactly as given: neither signed nor recorded (garbage, and an attacker's frames).
    void publish_raw(const char* channel, const std::vector<std::uint8_t>& bytes);

    /// From now on sign as sender_id with key and open what arrives; clear_key: unkeyed again.
    void set_key(const std::uint8_t (&key)[TVO_AUTH_KEY_BYTES], std::uint32_t sender_id);
    void clear_key();
    bool keyed() const { return auth_.keyed != 0; }
    /// The signed frame of message bytes on channel (consumes one counter); not published.
    std::vector<std::uint8_t> sign(const char* channel, std::vector<std::uint8_t> message);
    /// Keyed: every frame publish() sent, in order.
    std::vector<Frame> sent;
    /// Keyed: the node's frames that did not open, by reason (none is expected).
    long dropped_unauthenticated{0};
    long dropped_replayed{0};

    /// Handles messages until done() holds (true) or timeout passes (false).
    bool wait_until(const std::function<bool()>& done, std::chrono::microseconds timeout);
    /// Handles messages for `duration`.
    void pump(std::chrono::microseconds duration);
    /// Forgets everything received (after draining what is in flight).
    void clear();

    /// The highest boot a node of every robot announced (0: none yet); the plant's rule 1.
    std::int64_t node_boot() const;
    /// Waits until a node of every robot announces a boot above `above`; that boot, or 0 on timeout.
    std::int64_t await_boot(std::int64_t above, std::chrono::milliseconds timeout);
    /// Waits for an announcement of `boot` after the first `after` announcements that satisfies `ok`.
    const tvo_lcm::node_status_t* await_announcement(std::size_t after, std::int64_t boot,
                                                     const std::function<bool(const tvo_lcm::node_status_t&)>& ok,
                                                     std::chrono::milliseconds timeout);

    std::vector<ReceivedCommand> commands;
    std::vector<tvo_lcm::telemetry_t> telemetry;
    std::vector<tvo_lcm::session_ack_t> acks;
    std::vector<Announcement> announcements;

private:
    void on_frame(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
    template <class M>
    void publish_message(const char* channel, const M& msg);

    lcm::LCM lcm_;
    tvo_auth_t auth_{};
};

/// tvo_firmware_node as a child: `path --lcm-url URL --exit-with-parent --boot-file FILE [--keep-running]
/// [--key-file FILE]`. Every node of the campaign counts its boots in one file (kBootFile, in the
/// working directory; the node locks it), so a restarted node announces a new boot.
class NodeProcess {
public:
    static constexpr const char* kBootFile = "fault_campaign_node.boot";
    NodeProcess(std::string path, std::string url, std::string key_file = "");
    NodeProcess(const NodeProcess&) = delete;
    NodeProcess& operator=(const NodeProcess&) = delete;
    ~NodeProcess();

    /// stderr_path non-empty: the node's stderr is appended to that file.
    void spawn(bool keep_running, const std::string& stderr_path = "");
    bool running();
    void kill_now();   // SIGKILL and reap: a crash
    /// Waits for the child to exit; its exit code (128 + signal if killed), or -1 on timeout.
    int wait_exit(std::chrono::milliseconds timeout);
    void terminate();

private:
    std::string path_;
    std::string url_;
    std::string key_file_;
    pid_t pid_{-1};
    int exit_code_{-1};
};

/// Timing of a session.
struct Timing {
    std::int32_t clock_source{tvo_lcm::session_t::CLOCK_PLANT};
    std::int64_t period_us{10000};
    std::int64_t delay_us{5000};
    std::int32_t watchdog_periods{10};
};

/// The START the simulator sends for its default run: one unicycle, gains (40, 13), the ellipse
/// (centre 0, semi-axes 3 and 1.5 m, period 10 s), its limits, stamped start_utime, naming node boot
/// node_boot (0: none yet, the run names it when it heard the node), telemetry after every command.
tvo_lcm::session_t demo_session(std::int32_t session_id, std::int64_t start_utime_us, std::int64_t epoch_utime_us,
                                const Timing& timing, std::int64_t node_boot = 0);

/// The target of demo_session at plant time utime (objective time (utime - epoch) s).
void demo_target(const tvo_lcm::session_t& session, std::int64_t utime_us, double* x_m, double* y_m);

/// Encoded bytes of any generated message.
template <class M>
std::vector<std::uint8_t> encode(const M& msg)
{
    std::vector<std::uint8_t> bytes(static_cast<std::size_t>(msg.getEncodedSize()));
    msg.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
}

/// Every command of a case passes through this: no non-finite value, no value beyond a limit,
/// a safe stop exactly zero.
struct CommandAudit {
    double omega_max_radps{0.0};
    double speed_max_mps{0.0};
    long commands{0};
    long non_finite{0};
    long beyond_limit{0};
    long safe_stop_not_zero{0};
    long safe_stops{0};
    double max_abs_omega{0.0};
    double max_abs_speed{0.0};

    void add(const Command& cmd);
    void report(Report& report) const;
};

}  // namespace campaign
