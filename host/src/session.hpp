// Session control with the firmware node: START with the run's configuration (repeated until
// acknowledged, since the node may still be starting up) and STOP at the end.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <string>

#include "options.hpp"
#include "scenario.hpp"
#include "transport.hpp"

namespace tvo_host {

/// The START message for this run: controller settings, robots, tracking weights, targets.
tvo_lcm::session_t make_start_session(const SimOptions& options, const Scenario& scenario, std::int64_t session_id);

/// "the firmware rejected the session (parameter out of range): parameter gain_kp/gain_kd (--gains -1,13)".
std::string describe_rejection(const tvo_lcm::session_ack_t& ack, const SimOptions& options);

class SessionClient : public TransportListener {
public:
    SessionClient(LcmTransport& transport, const tvo_lcm::session_t& start);

    /// Sends START until an ack arrives or timeout passes (TransportError). `keep_waiting` returning
    /// false aborts the wait (interrupt, child died): the result then has acked() == false.
    bool start(std::chrono::milliseconds timeout, const std::function<bool()>& keep_waiting);
    const tvo_lcm::session_ack_t& ack() const { return ack_; }

    /// Sends STOP (at plant utime `utime`) and waits briefly for its ack; false if none came.
    bool stop(std::int64_t utime, std::chrono::milliseconds timeout);

    void on_command(const tvo_lcm::command_t&) override {}
    void on_session_ack(const tvo_lcm::session_ack_t& ack) override;

private:
    bool await_ack(std::int8_t action, std::chrono::steady_clock::time_point deadline);

    LcmTransport& transport_;
    tvo_lcm::session_t session_;
    tvo_lcm::session_ack_t ack_{};
    std::int8_t awaited_action_{0};
    bool acked_{false};
};

}  // namespace tvo_host
