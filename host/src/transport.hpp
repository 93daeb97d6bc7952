// The simulator's LCM side: publishes without per-message allocation, dispatches what the
// firmware sends, and logs every message both ways in LCM's own log format (lcm-logplayer replays it).
#pragma once

#include <array>
#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "auth.h"
#include "lcm_messages.hpp"
#include "nodes.hpp"
#include "plant_wire.hpp"
#include "run_recorder.hpp"

namespace tvo_host {

class TransportError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Receives the firmware's messages (called from LcmTransport::wait).
class TransportListener {
public:
    virtual ~TransportListener() = default;
    /// A joint command: every robot's unicycle_command_t of one period (CommandAssembler).
    virtual void on_command(const JointCommand& command) = 0;
    virtual void on_session_ack(const tvo_lcm::session_ack_t& ack) = 0;
    /// One robot's telemetry.
    virtual void on_telemetry(const tvo_lcm::telemetry_t& /*telemetry*/) {}
    /// A node's announcement, after the transport's NodeDirectory took it.
    virtual void on_node_status(const tvo_lcm::node_status_t& /*status*/) {}
};

enum class WaitResult { Timeout, Handled, Interrupted };

class LcmTransport {
public:
    /// Opens LCM on url (empty: LCM's default) and the log at log_path. TransportError with a fix on failure.
    /// With a key_file every message is signed as sender_id and every received one must open (auth.h);
    /// the log holds the messages without their trailers. Without one the bus is unauthenticated.
    /// robots: the run's, whose commands are joined (CommandAssembler). It subscribes at once, so the
    /// first announcement of a node spawned after it is heard (nodes()).
    LcmTransport(const std::string& url, const std::string& log_path, std::size_t robots, const std::string& key_file = "",
                 std::uint32_t sender_id = TVO_AUTH_SENDER_PLANT);
    ~LcmTransport();
    LcmTransport(const LcmTransport&) = delete;
    LcmTransport& operator=(const LcmTransport&) = delete;

    void set_listener(TransportListener* listener) { listener_ = listener; }
    /// Plant-clock utime stamped on received messages in the log (the sim's notion of "now").
    void set_log_utime(std::int64_t utime) { log_utime_ = utime; }

    void publish(const tvo_lcm::session_t& msg);
    /// The period's samples: one unicycle_sample_t per robot, in robot order, back to back.
    void publish(const JointMeasurement& msg);
    /// One robot's streamed target sample.
    void publish(const tvo_lcm::target_t& msg);

    /// The nodes heard so far (every TVO_NODE announcement, whoever listens).
    const NodeDirectory& nodes() const { return nodes_; }

    /// Waits up to timeout for one message and dispatches it.
    WaitResult wait(std::chrono::microseconds timeout);

    std::uint64_t logged_events() const { return logged_events_; }
    /// Keyed: received frames dropped for a missing or wrong tag, and for a used counter.
    std::uint64_t unauthenticated() const { return unauthenticated_; }
    std::uint64_t replayed() const { return replayed_; }
    bool keyed() const { return keyed_; }
    bool log_ok() const { return log_ok_; }

private:
    template <class Msg>
    void publish_encoded(const std::string& channel, const Msg& msg, bool logged = true);
    void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
    void log(const std::string& channel, const void* data, std::int32_t size, std::int64_t utime);
    void log_announcement(const std::string& channel, const void* data, std::int32_t size);

    lcm::LCM lcm_;
    std::unique_ptr<lcm::LogFile> log_;
    TransportListener* listener_{nullptr};
    std::vector<std::uint8_t> buffer_;     // sized once for the largest message
    lcm::LogEvent event_{};                 // reused: its channel string stays within SSO capacity
    std::int64_t log_utime_{0};
    std::uint64_t logged_events_{0};
    bool log_ok_{true};
    bool keyed_{false};
    tvo_auth_t auth_{};
    std::uint64_t unauthenticated_{0};
    std::uint64_t replayed_{0};
    std::size_t robots_;
    CommandAssembler commands_;
    NodeDirectory nodes_;
    tvo_lcm::unicycle_sample_t sample_{};
    tvo_lcm::unicycle_command_t command_{};
    tvo_lcm::session_ack_t ack_{};
    tvo_lcm::telemetry_t telemetry_{};
    tvo_lcm::node_status_t status_{};
    // What the log took, so that it stays within bound_outputs (run_recorder.hpp).
    struct LoggedAnnouncement {
        bool any{false};
        std::int64_t log_utime{0};
        std::int64_t boot_id{0};
        std::int8_t state{0};
        std::int32_t session_id{0};
    };
    std::array<LoggedAnnouncement, kMaxRobots + 1> logged_announcement_{};  // per role (own_robot + 1)
    std::uint64_t logged_session_messages_{0};
    std::uint64_t logged_acks_{0};
    std::uint64_t logged_changes_{0};  // announcements logged for a change of boot, state or session
    // Channel names as std::string once, so publishing builds no temporaries.
    const std::string session_channel_{TVO_CHANNEL_SESSION};
    const std::string sample_channel_{TVO_CHANNEL_SAMPLE};
    const std::string target_channel_{TVO_CHANNEL_TARGET};
};

}  // namespace tvo_host
