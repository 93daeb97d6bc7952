// LCM transport and in-process log; see transport.hpp.
#include "transport.hpp"

#include <sys/select.h>

#include <algorithm>
#include <cerrno>
#include <limits>

#include "auth_key_file.h"

namespace tvo_host {

namespace {
// Larger than any of the protocol's fixed-size messages (session_t is the biggest, 11.4 kB with 32
// robots); the constructor checks it against the encoded sizes.
constexpr std::size_t kBufferBytes = 16384;

// The plant time a published message is logged at: its own stamp.
std::int64_t utime_of(const tvo_lcm::session_t& msg) { return msg.utime; }
template <class Msg>
std::int64_t utime_of(const Msg& msg)
{
    return msg.header.utime;
}
}  // namespace

LcmTransport::LcmTransport(const std::string& url, const std::string& log_path, std::size_t robots,
                           const std::string& key_file, std::uint32_t sender_id)
    : lcm_(url), buffer_(kBufferBytes + TVO_AUTH_TRAILER_BYTES), robots_(robots), commands_(robots)
{
    if (robots < 1 || robots > kMaxRobots) {
        throw TransportError("a run has 1 .. " + std::to_string(kMaxRobots) + " robots, got " + std::to_string(robots));
    }
    if (!key_file.empty()) {
        std::uint8_t key[TVO_AUTH_KEY_BYTES];
        char why[300];
        if (tvo_auth_key_file_read(key_file.c_str(), key, why, sizeof(why)) != 0) {
            throw TransportError(why);
        }
        tvo_auth_status_t status = tvo_auth_init(&auth_, key, sender_id, 1u);
        std::fill(std::begin(key), std::end(key), std::uint8_t{0});
        if (status == TVO_AUTH_OK) {
            // Counters follow the wall clock (MAVLink's rule): a restarted plant starts above its old ones.
            status = tvo_auth_follow_clock(&auth_, tvo_auth_wall_clock_counter);
        }
        if (status != TVO_AUTH_OK) {
            throw TransportError(std::string("authentication set-up failed: ") + tvo_auth_status_str(status));
        }
        keyed_ = true;
    }
    if (!lcm_.good()) {
        throw TransportError(
            "cannot create LCM on '" + (url.empty() ? std::string("LCM default") : url) +
            "'. UDP multicast on loopback may be disabled; fix (as root): `ip link set lo multicast on` and "
            "`ip route add 224.0.0.0/4 dev lo`, or choose another provider with --lcm-url or LCM_DEFAULT_URL");
    }
    log_ = std::make_unique<lcm::LogFile>(log_path, "w");
    if (!log_->good()) {
        throw TransportError("cannot write the LCM log " + log_path);
    }
    event_.channel.reserve(32);
    // Fixed-size messages: their encoded sizes are constants, so one check covers every publish.
    const int largest = std::max({tvo_lcm::session_t{}.getEncodedSize(), tvo_lcm::unicycle_sample_t{}.getEncodedSize(),
                                  tvo_lcm::target_t{}.getEncodedSize()});
    if (largest < 0 || static_cast<std::size_t>(largest) > kBufferBytes) {
        throw TransportError("the encode buffer (" + std::to_string(buffer_.size()) + " bytes) is smaller than a " +
                             std::to_string(largest) + "-byte message");
    }
    // Unbounded queues: LCM drops past 30 queued messages per subscription, silently, and one period of a
    // 32-robot session brings 32 commands (and as many telemetry frames) at once.
    for (const char* channel : {TVO_CHANNEL_NODE, TVO_CHANNEL_COMMAND, TVO_CHANNEL_SESSION_ACK, TVO_CHANNEL_TELEMETRY}) {
        lcm_.subscribe(channel, &LcmTransport::on_raw, this)->setQueueCapacity(0);
    }
}

LcmTransport::~LcmTransport()
{
    tvo_auth_clear(&auth_);
}

void LcmTransport::log(const std::string& channel, const void* data, std::int32_t size, std::int64_t utime)
{
    event_.timestamp = utime;
    event_.channel = channel;
    event_.datalen = size;
    event_.data = const_cast<void*>(data);  // LogEvent's field is non-const; writeEvent only reads it
    if (log_->writeEvent(&event_) != 0) {
        log_ok_ = false;
    }
    ++logged_events_;
}

template <class Msg>
void LcmTransport::publish_encoded(const std::string& channel, const Msg& msg, bool logged)
{
    const int size = msg.encode(buffer_.data(), 0, static_cast<int>(buffer_.size()));
    if (size < 0) {
        throw TransportError("cannot encode a message for " + channel);
    }
    std::size_t frame_size = static_cast<std::size_t>(size);
    if (keyed_) {
        const tvo_auth_status_t status = tvo_auth_sign(&auth_, channel.c_str(), buffer_.data(), frame_size,
                                                       buffer_.size(), &frame_size);
        if (status != TVO_AUTH_OK) {
            throw TransportError("cannot sign a message for " + channel + ": " + tvo_auth_status_str(status));
        }
    }
    if (lcm_.publish(channel, buffer_.data(), static_cast<unsigned>(frame_size)) != 0) {
        throw TransportError("LCM publish on " + channel + " failed");
    }
    if (logged) {
        log(channel, buffer_.data(), size, utime_of(msg));
    }
}

void LcmTransport::publish(const tvo_lcm::session_t& msg)
{
    publish_encoded(session_channel_, msg, logged_session_messages_ < kLoggedSessionMessages);
    ++logged_session_messages_;
}

void LcmTransport::publish(const JointMeasurement& msg)
{
    // In robot order: a node that drives every robot steps on the last one's.
    for (std::size_t r = 0; r < robots_; ++r) {
        to_wire(msg, r, &sample_);
        publish_encoded(sample_channel_, sample_);
    }
}

void LcmTransport::publish(const tvo_lcm::target_t& msg)
{
    publish_encoded(target_channel_, msg);
}

void LcmTransport::on_raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel)
{
    auto size = static_cast<int>(rbuf->data_size);
    if (keyed_) {
        std::size_t message_size = 0;
        const tvo_auth_status_t status = tvo_auth_open(&auth_, channel.c_str(), static_cast<const std::uint8_t*>(rbuf->data),
                                                       rbuf->data_size, &message_size);
        if (status != TVO_AUTH_OK) {
            ++(status == TVO_AUTH_ERR_REPLAY ? replayed_ : unauthenticated_);
            return;  // dropped: neither logged nor dispatched
        }
        size = static_cast<int>(message_size);
    }
    if (channel == TVO_CHANNEL_SESSION_ACK) {
        if (logged_acks_ < kLoggedSessionMessages * robots_) {
            log(channel, rbuf->data, size, log_utime_);
        }
        ++logged_acks_;
    } else if (channel != TVO_CHANNEL_NODE) {
        log(channel, rbuf->data, size, log_utime_);
    }
    // Decoding fixed-size messages into members allocates nothing. A frame of another length than its
    // message's is no message of that channel (a keyed frame's trailer is gone by now).
    if (channel == TVO_CHANNEL_NODE) {
        if (status_.decode(rbuf->data, 0, size) == size) {
            log_announcement(channel, rbuf->data, size);
            nodes_.heard(status_, std::chrono::steady_clock::now());
            if (listener_ != nullptr) {
                listener_->on_node_status(status_);
            }
        }
        return;
    }
    if (listener_ == nullptr) {
        return;
    }
    if (channel == TVO_CHANNEL_COMMAND) {
        const JointCommand* joint = command_.decode(rbuf->data, 0, size) == size ? commands_.add(command_) : nullptr;
        if (joint != nullptr) {
            listener_->on_command(*joint);
        }
    } else if (channel == TVO_CHANNEL_SESSION_ACK) {
        if (ack_.decode(rbuf->data, 0, size) == size) {
            listener_->on_session_ack(ack_);
        }
    } else if (channel == TVO_CHANNEL_TELEMETRY) {
        if (telemetry_.decode(rbuf->data, 0, size) == size) {
            listener_->on_telemetry(telemetry_);
        }
    }
}

void LcmTransport::log_announcement(const std::string& channel, const void* data, std::int32_t size)
{
    // The run's nodes' (each robot's, the every-robot one): a change at once, else one per interval.
    const int role = status_.own_robot;
    if (role < -1 || role >= static_cast<int>(robots_)) {
        return;
    }
    LoggedAnnouncement& last = logged_announcement_[static_cast<std::size_t>(role + 1)];
    const bool changed = !last.any || last.boot_id != status_.boot_id || last.state != status_.state ||
                         last.session_id != status_.session_id;
    if (!changed && log_utime_ - last.log_utime < kLoggedAnnouncementIntervalUs) {
        return;
    }
    if (changed && last.any && logged_changes_ >= 2 * kLoggedSessionMessages) {
        return;  // more changes than the session messages logged can make: not logged (bound_outputs)
    }
    logged_changes_ += changed && last.any ? 1u : 0u;
    last = LoggedAnnouncement{true, log_utime_, status_.boot_id, status_.state, status_.session_id};
    log(channel, data, size, log_utime_);
}

WaitResult LcmTransport::wait(std::chrono::microseconds timeout)
{
    const int fd = lcm_.getFileno();
    fd_set readable;
    FD_ZERO(&readable);
    FD_SET(fd, &readable);
    const auto us = std::max<std::int64_t>(0, timeout.count());
    timeval tv{};
    tv.tv_sec = static_cast<time_t>(us / 1000000);
    tv.tv_usec = static_cast<suseconds_t>(us % 1000000);
    const int ready = select(fd + 1, &readable, nullptr, nullptr, &tv);
    if (ready < 0) {
        if (errno == EINTR) {
            return WaitResult::Interrupted;
        }
        throw TransportError("select on the LCM socket failed");
    }
    if (ready == 0) {
        return WaitResult::Timeout;
    }
    if (lcm_.handle() != 0) {
        throw TransportError("LCM receive failed");
    }
    return WaitResult::Handled;
}

}  // namespace tvo_host
