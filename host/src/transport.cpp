// LCM transport and in-process log; see transport.hpp.
#include "transport.hpp"

#include <sys/select.h>

#include <algorithm>
#include <cerrno>

#include "auth_key_file.h"

namespace tvo_host {

namespace {
// Larger than any of the protocol's fixed-size messages (session_t is the biggest, ~2 kB with the
// problem's constraints); the constructor checks it against the encoded sizes.
constexpr std::size_t kBufferBytes = 4096;
}  // namespace

LcmTransport::LcmTransport(const std::string& url, const std::string& log_path, const std::string& key_file,
                           std::uint32_t sender_id, std::size_t fleet_robots)
    : lcm_(url), buffer_(kBufferBytes + TVO_AUTH_TRAILER_BYTES), fleet_robots_(fleet_robots), rows_(fleet_robots)
{
    if (fleet_robots > kMaxRobots) {
        throw TransportError("the per-robot leg carries at most " + std::to_string(kMaxRobots) + " robots, got " +
                             std::to_string(fleet_robots));
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
            status = tvo_auth_follow_clock(&auth_, tvo_auth_wall_clock_counter, TVO_AUTH_NEW_SENDER_WINDOW_US);
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
    const int largest = std::max({tvo_lcm::session_t{}.getEncodedSize(), tvo_lcm::measurement_t{}.getEncodedSize(),
                                  tvo_lcm::fleet_sample_t{}.getEncodedSize(), tvo_lcm::target_t{}.getEncodedSize()});
    if (largest < 0 || static_cast<std::size_t>(largest) > kBufferBytes) {
        throw TransportError("the encode buffer (" + std::to_string(buffer_.size()) + " bytes) is smaller than a " +
                             std::to_string(largest) + "-byte message");
    }
    lcm_.subscribe(fleet_robots_ > 0 ? TVO_CHANNEL_FLEET_COMMAND : TVO_CHANNEL_COMMAND, &LcmTransport::on_raw, this);
    lcm_.subscribe(TVO_CHANNEL_SESSION_ACK, &LcmTransport::on_raw, this);
    lcm_.subscribe(TVO_CHANNEL_TELEMETRY, &LcmTransport::on_raw, this);
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
void LcmTransport::publish_encoded(const std::string& channel, const Msg& msg)
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
    log(channel, buffer_.data(), size, msg.utime);
}

void LcmTransport::publish(const tvo_lcm::session_t& msg)
{
    publish_encoded(session_channel_, msg);
}

void LcmTransport::publish(const JointMeasurement& msg)
{
    if (fleet_robots_ == 0) {
        to_wire(msg, &measurement_);
        publish_encoded(measurement_channel_, measurement_);
        return;
    }
    for (std::size_t r = 0; r < fleet_robots_; ++r) {  // back to back: the hub gathers a period's samples
        to_wire(msg, r, &sample_);
        publish_encoded(fleet_sample_channel_, sample_);
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
    log(channel, rbuf->data, size, log_utime_);
    if (listener_ == nullptr) {
        return;
    }
    // Decoding fixed-size messages into members allocates nothing.
    if (channel == TVO_CHANNEL_COMMAND) {
        if (command_.decode(rbuf->data, 0, size) >= 0) {
            listener_->on_command(from_wire(command_));
        }
    } else if (channel == TVO_CHANNEL_FLEET_COMMAND) {
        const JointCommand* joint = row_.decode(rbuf->data, 0, size) >= 0 ? rows_.add(row_) : nullptr;
        if (joint != nullptr) {
            listener_->on_command(*joint);
        }
    } else if (channel == TVO_CHANNEL_SESSION_ACK) {
        if (ack_.decode(rbuf->data, 0, size) >= 0) {
            listener_->on_session_ack(ack_);
        }
    } else if (channel == TVO_CHANNEL_TELEMETRY) {
        if (telemetry_.decode(rbuf->data, 0, size) >= 0) {
            listener_->on_telemetry(telemetry_);
        }
    }
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
