// The simulator's LCM side: publishes without per-message allocation, dispatches what the
// firmware sends, and logs every message both ways in LCM's own log format (lcm-logplayer replays it).
#pragma once

#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <lcm/lcm-cpp.hpp>

#include "auth.h"
#include "lcm_messages.hpp"
#include "plant_wire.hpp"

namespace tvo_host {

class TransportError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Receives the firmware's messages (called from LcmTransport::wait).
class TransportListener {
public:
    virtual ~TransportListener() = default;
    /// A joint command: a command_t, or (per-robot leg) every robot's fleet_command_t row of one period.
    virtual void on_command(const JointCommand& command) = 0;
    virtual void on_session_ack(const tvo_lcm::session_ack_t& ack) = 0;
    virtual void on_telemetry(const tvo_lcm::telemetry_t& /*telemetry*/) {}
};

enum class WaitResult { Timeout, Handled, Interrupted };

class LcmTransport {
public:
    /// Opens LCM on url (empty: LCM's default) and the log at log_path. TransportError with a fix on failure.
    /// With a key_file every message is signed as sender_id and every received one must open (auth.h);
    /// the log holds the messages without their trailers. Without one the bus is unauthenticated.
    /// fleet_robots > 0: the per-robot leg for that many robots (fleet_sample_t out, fleet_command_t in,
    /// plant_wire.hpp); 0: the joint leg (measurement_t, command_t).
    LcmTransport(const std::string& url, const std::string& log_path, const std::string& key_file = "",
                 std::uint32_t sender_id = TVO_AUTH_SENDER_PLANT, std::size_t fleet_robots = 0);
    ~LcmTransport();
    LcmTransport(const LcmTransport&) = delete;
    LcmTransport& operator=(const LcmTransport&) = delete;

    void set_listener(TransportListener* listener) { listener_ = listener; }
    /// Plant-clock utime stamped on received messages in the log (the sim's notion of "now").
    void set_log_utime(std::int64_t utime) { log_utime_ = utime; }

    void publish(const tvo_lcm::session_t& msg);
    /// The period's sample on the run's leg: one measurement_t, or one fleet_sample_t per robot.
    void publish(const JointMeasurement& msg);
    void publish(const tvo_lcm::target_t& msg);

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
    void publish_encoded(const std::string& channel, const Msg& msg);
    void on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel);
    void log(const std::string& channel, const void* data, std::int32_t size, std::int64_t utime);

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
    std::size_t fleet_robots_;
    CommandAssembler rows_;
    tvo_lcm::measurement_t measurement_{};
    tvo_lcm::fleet_sample_t sample_{};
    tvo_lcm::command_t command_{};
    tvo_lcm::fleet_command_t row_{};
    tvo_lcm::session_ack_t ack_{};
    tvo_lcm::telemetry_t telemetry_{};
    // Channel names as std::string once, so publishing builds no temporaries.
    const std::string session_channel_{TVO_CHANNEL_SESSION};
    const std::string measurement_channel_{TVO_CHANNEL_MEASUREMENT};
    const std::string target_channel_{TVO_CHANNEL_TARGET};
    const std::string fleet_sample_channel_{TVO_CHANNEL_FLEET_SAMPLE};
};

}  // namespace tvo_host
