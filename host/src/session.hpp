// Session control with the node(s) (lcm_types/README.md, "Writing your own plant", rules 1, 2, 5, 6):
// hear each robot's node on TVO_NODE, START naming their boots (repeated, backing off, until every
// named node acked), a new session when a node restarted, lost the session or fell silent, and STOP at
// the end.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "nodes.hpp"
#include "options.hpp"
#include "scenario.hpp"
#include "transport.hpp"

namespace tvo_host {

/// START is repeated until acknowledged (LCM drops messages nobody subscribed yet), first after this
/// interval, then after twice the last, up to kStartRepeatMax: a slow link (an 11 kB START takes 1 s
/// at 115200 baud) is not flooded with repeats that delay the first samples behind them.
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

/// The periods whose answers carry telemetry: every `every`-th sequence (session_t.telemetry_every, 0:
/// the node's default, the fewest periods that span 100 ms).
std::int64_t telemetry_every_periods(std::int32_t telemetry_every, std::int64_t period_us);

/// The START message for this run: timing (CLOCK_NODE when realtime, else CLOCK_PLANT), telemetry rate,
/// controller settings, robots, tracking weights, targets and constraints, naming each robot's node by
/// its boot, stamped `utime`, with the objective's t = 0 at `epoch_utime`.
tvo_lcm::session_t make_start_session(const SimOptions& options, const Scenario& scenario, std::int32_t session_id,
                                      std::int64_t utime, std::int64_t epoch_utime, const NodeBoots& boots);

/// "the firmware rejected the session (parameter out of range): parameter gain_kp/gain_kd (--gains -1,13)";
/// a rejected part of the problem is named with the index of its entry ("obstacles, entry 3").
std::string describe_rejection(const tvo_lcm::session_ack_t& ack, const SimOptions& options);

/// Rule 1: waits until every robot of the run has a node on the bus (NodeDirectory::assignment) and
/// returns their boots. TransportError if none came within timeout (naming what was heard) or a node
/// takes fewer robots than the run has; nullopt if keep_waiting returned false.
std::optional<NodeBoots> await_nodes(LcmTransport& transport, std::size_t robots, std::chrono::milliseconds timeout,
                                     const std::function<bool()>& keep_waiting);

class SessionClient : public TransportListener {
public:
    /// `start` names its nodes' boots; `stamp` gives the utime of each START sent after the first (the
    /// plant's current time in realtime runs, so the node measures its clock offset from the newest one);
    /// the first is sent as built.
    SessionClient(LcmTransport& transport, const tvo_lcm::session_t& start, std::function<std::int64_t()> stamp);

    std::int32_t session_id() const { return session_.session_id; }
    const tvo_lcm::session_t& start_message() const { return session_; }
    /// The boots named: every robot's node.
    NodeBoots boots() const;
    /// The different boots named (one node that drives every robot, or one per robot).
    const std::vector<std::int64_t>& named() const { return named_; }

    /// Rule 2: sends START until every named node acked or timeout passes (TransportError). keep_waiting
    /// returning false aborts the wait: the result is then false.
    bool start(std::chrono::milliseconds timeout, const std::function<bool()>& keep_waiting);
    /// The START's answer: the first refusal among the nodes' acks, else the last ack.
    const tvo_lcm::session_ack_t& ack() const { return refusal_ ? *refusal_ : ack_; }
    bool refused() const { return refusal_.has_value(); }

    /// Rule 5: a new session (fresh id, the same configuration) naming `boots`, stamped utime; its START
    /// goes out on service(), repeated until every named node acked.
    void restart(std::int32_t session_id, const NodeBoots& boots, std::int64_t utime);
    /// Sends the restart's START when a copy is due; true once every named node acked (see ack()).
    bool service(std::optional<std::int64_t> utime);
    bool acked() const { return exchange_done(); }

    /// Rule 6: STOP (at plant utime `utime`) naming the boots; waits briefly for every node's ack; false
    /// if not all came.
    bool stop(std::int64_t utime, std::chrono::milliseconds timeout);

    void on_command(const JointCommand&) override {}
    void on_session_ack(const tvo_lcm::session_ack_t& ack) override;

private:
    void begin_exchange(std::int8_t action);
    bool exchange_done() const;
    void publish_start(std::optional<std::int64_t> utime);
    bool await_exchange(std::chrono::steady_clock::time_point deadline);

    LcmTransport& transport_;
    tvo_lcm::session_t session_;
    std::function<std::int64_t()> stamp_;
    std::vector<std::int64_t> named_;      // the different boots of session_.node_boot_id
    std::vector<bool> acked_;              // per named boot: its ack of the exchange came
    std::int8_t awaited_action_{0};
    tvo_lcm::session_ack_t ack_{};
    std::optional<tvo_lcm::session_ack_t> refusal_;
    StartRepeats repeats_;
    bool first_copy_{true};
};

}  // namespace tvo_host
