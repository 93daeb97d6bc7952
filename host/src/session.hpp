// Session control with the firmware node: START with the run's configuration (repeated until
// acknowledged, since the node may still be starting up; sent again when the node reports that it
// lost the session) and STOP at the end.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "options.hpp"
#include "scenario.hpp"
#include "transport.hpp"

namespace tvo_host {

/// START is repeated until acknowledged (LCM drops messages nobody subscribed yet), first after this
/// interval, then after twice the last, up to kStartRepeatMax: a slow link (a 2 kB START takes 184 ms
/// at 115200 baud) is not flooded with repeats that delay the first measurements behind them.
constexpr std::chrono::milliseconds kStartRepeat{100};
constexpr std::chrono::milliseconds kStartRepeatMax{800};

/// When to repeat an unacknowledged START, for the first session and a restart alike: `sent` after
/// each copy, `due` when the next one is; reset for a new handshake.
class StartRepeats {
public:
    using Clock = std::chrono::steady_clock;
    void sent(Clock::time_point now)
    {
        interval_ = next_ ? std::min(2 * interval_, kStartRepeatMax) : kStartRepeat;
        next_ = now + interval_;
    }
    bool due(Clock::time_point now) const { return !next_ || now >= *next_; }
    /// When the next copy is due (the first at once).
    Clock::time_point next(Clock::time_point now) const { return next_ ? *next_ : now; }
    void reset() { next_.reset(); }

private:
    std::optional<Clock::time_point> next_;
    std::chrono::milliseconds interval_{kStartRepeat};
};

/// The START message for this run: timing (CLOCK_NODE when realtime, else CLOCK_PLANT), controller
/// settings, robots, tracking weights, targets and constraints, stamped `utime`, with the
/// objective's t = 0 at `epoch_utime`.
tvo_lcm::session_t make_start_session(const SimOptions& options, const Scenario& scenario, std::int64_t session_id,
                                      std::int64_t utime, std::int64_t epoch_utime);

/// "the firmware rejected the session (parameter out of range): parameter gain_kp/gain_kd (--gains -1,13)";
/// a rejected part of the problem is named with the index of its entry ("obstacles, entry 3").
std::string describe_rejection(const tvo_lcm::session_ack_t& ack, const SimOptions& options);

class SessionClient : public TransportListener {
public:
    /// `stamp` gives the utime of each START sent after the first (the plant's current time in
    /// realtime runs, so the node measures its clock offset from the newest one); the first is sent
    /// as built.
    SessionClient(LcmTransport& transport, const tvo_lcm::session_t& start, std::function<std::int64_t()> stamp);

    std::int64_t session_id() const { return session_.session_id; }
    const tvo_lcm::session_t& start_message() const { return session_; }

    /// Sends START until an ack arrives or timeout passes (TransportError). `keep_waiting` returning
    /// false aborts the wait (interrupt, child died): the result then has acked() == false.
    bool start(std::chrono::milliseconds timeout, const std::function<bool()>& keep_waiting);
    const tvo_lcm::session_ack_t& ack() const { return ack_; }

    /// Publishes START once more, stamped now (same id and content: the node accepts it as new
    /// after a restart, or repeats its ack if it still runs the session). Does not wait.
    void send_start_again(std::optional<std::int64_t> utime = std::nullopt);
    /// True if `ack` answers our START.
    bool is_start_ack(const tvo_lcm::session_ack_t& ack) const;

    /// Sends STOP (at plant utime `utime`) and waits briefly for its ack; false if none came.
    bool stop(std::int64_t utime, std::chrono::milliseconds timeout);

    void on_command(const JointCommand&) override {}
    void on_session_ack(const tvo_lcm::session_ack_t& ack) override;

private:
    bool await_ack(std::int8_t action, std::chrono::steady_clock::time_point deadline);

    LcmTransport& transport_;
    tvo_lcm::session_t session_;
    std::function<std::int64_t()> stamp_;
    tvo_lcm::session_ack_t ack_{};
    std::int8_t awaited_action_{0};
    bool acked_{false};
};

}  // namespace tvo_host
