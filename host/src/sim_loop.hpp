// The closed loop on the plant side: sample, publish, receive commands, integrate exactly.
//
// Timing (plant time in whole microseconds from the session epoch, t_n = n h; on the wire
// utime = epoch_utime + plant time):
//   measurement n (sequence n, for the node's period n + 1) is sampled at s_n = t_{n+1} - tau
//   (mid-interval when tau > 0: the plant is integrated along its arc up to s_n, then on to the
//   boundary); the command answering it is applied at its utime, nominally t_{n+1} (+ any injected
//   extra delay), and held until the next one. The robots hold zero input until the first command;
//   the run ends at T = steps h.
// Commands (edge_spec, "the plant's rules"): one is applied only if it carries our session id and
//   either answers a measurement we sent that is newer than the command in force, or is a safe stop.
//   A command with status tvo_lcm::command_t::STATUS_ERR_NO_SESSION means the node lost our session (it restarted): the
//   START is sent again (repeated until acknowledged) and the run goes on.
// Lockstep (session CLOCK_PLANT): after publishing measurement n the loop blocks (wall-clock
//   timeout) until the command and the telemetry answering n arrive, so the run is deterministic
//   and as fast as the transport. Epoch = --start-utime-us.
// Realtime (session CLOCK_NODE): plant time follows the plant's monotonic clock (PlantClock), which
//   starts before the first START; the epoch is that START's utime + kNodeClockEpochLeadUs and the
//   loop waits for it. Commands take effect at their utime, or on arrival when they come late
//   (counted). A dropped measurement is never sent and nothing is awaited.
// Constraint checks: the constraint monitor sees the true positions every kCheckStepUs of plant
//   time along the exact arcs, and at every sample and command instant.
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <optional>
#include <vector>

#include "constraint_metrics.hpp"
#include "faults.hpp"
#include "metrics.hpp"
#include "noise.hpp"
#include "options.hpp"
#include "plant.hpp"
#include "plant_clock.hpp"
#include "run_recorder.hpp"
#include "scenario.hpp"
#include "session.hpp"
#include "transport.hpp"

namespace tvo_host {

/// Realtime: the epoch lies this far after the first START's stamp. It covers the START's round
/// trip with up to three repeats (after 100, 300 and 700 ms: a node that was just spawned may not be
/// subscribed yet), and the link's time to carry the repeats still in flight, so the first
/// measurements do not queue behind them (on a slow link they would arrive late by as much, and the
/// node's clock offset, which it takes from their arrival, would keep that error); a later ack only
/// costs the first periods (their measurements go out late and are refused as stale).
constexpr std::int64_t kNodeClockEpochLeadUs = 1000000;

struct LoopResult {
    std::int64_t steps{0};
    double wall_s{0.0};
    std::uint64_t drops{0};
    std::uint64_t late_commands{0};
    std::uint64_t lost_answers{0};            // lockstep, --on-missing-answer hold: no command in time
    std::uint64_t lost_telemetry{0};          // ... the command came, its telemetry did not
    std::uint64_t link_lost_measurements{0};  // not sent because of --link-loss
    std::uint64_t ignored_commands{0};        // ours by id but answering nothing we sent (newer), or malformed
    std::uint64_t other_session_commands{0};  // for another session id
    std::uint64_t session_restarts{0};        // tvo_lcm::command_t::STATUS_ERR_NO_SESSION seen: START sent again
    std::uint64_t safe_stop_commands{0};      // safe stops applied to the plant
    std::optional<double> first_safe_stop_after_loss_s;  // realtime with --link-loss, see README
    std::optional<tvo_lcm::node_counters_t> node_counters;  // from the newest telemetry of our session
    bool interrupted{false};
};

class SimLoop : public TransportListener {
public:
    SimLoop(const SimOptions& options, const Scenario& scenario, LcmTransport& transport, SessionClient& session,
            const PlantClock& clock, RunRecorder& recorder, TrackingMetrics& metrics, ConstraintMonitor& monitor,
            const volatile std::sig_atomic_t& stop_signal);

    /// Runs all periods. TransportError if, in lockstep with --on-missing-answer fail, the firmware
    /// does not answer in time, or if a re-sent START is refused or never acknowledged.
    LoopResult run();

    void on_command(const JointCommand& command) override;
    void on_session_ack(const tvo_lcm::session_ack_t& ack) override;
    void on_telemetry(const tvo_lcm::telemetry_t& telemetry) override;

private:
    struct PendingCommand {
        std::int64_t apply_us{0};
        std::int64_t sequence{0};
        std::array<UnicycleInput, kMaxRobots> input{};
        std::int32_t status{0};
        std::int32_t flags{0};
    };
    enum class Answer { Received, Lost, Interrupted };

    void advance_to(std::int64_t t_us);
    void integrate_to(std::int64_t t_us);
    void check_constraints(std::int64_t t_us);
    bool publish_sample(std::int64_t sequence, std::int64_t sample_us);  // false if not sent
    Answer await_answer(std::int64_t sequence);
    bool await_restart();                        // lockstep; false when interrupted
    void service_restart();                      // (re)sends START while a restart is pending
    bool wait_until(std::int64_t t_us);          // realtime; false when interrupted
    bool sent(std::int64_t sequence) const;
    std::int64_t sample_time_us(std::int64_t sequence) const;
    void record(std::int64_t t_us);
    std::int64_t wall_plant_us() const;
    bool stopping() const { return stop_signal_ != 0; }

    const SimOptions& options_;
    const Scenario& scenario_;
    LcmTransport& transport_;
    SessionClient& session_;
    const PlantClock& clock_;
    RunRecorder& recorder_;
    TrackingMetrics& metrics_;
    ConstraintMonitor& monitor_;
    const volatile std::sig_atomic_t& stop_signal_;
    const std::int64_t epoch_utime_;

    UnicyclePlant plant_;
    MeasurementNoise noise_;
    ProcessDisturbance disturbance_;
    FaultInjector faults_;

    std::int64_t now_us_{0};                 // plant time integrated so far
    std::vector<PendingCommand> pending_;    // by apply time; capacity reserved up front
    std::vector<bool> sent_;                 // per sequence: the measurement was published
    PendingCommand applied_{};               // command in force (as commanded, before disturbance)
    std::int64_t last_queued_sequence_{-1};
    std::int64_t answered_sequence_{-1};     // newest sent measurement a command answered
    std::int32_t answered_status_{0};        // that command's status
    std::int64_t telemetry_sequence_{-1};    // newest telemetry received
    StepTelemetry telemetry_{};              // newest received (lockstep: of the command in force)
    LoopResult counts_{};                    // the counters of the result, filled as the run goes

    // Session restart (the node answered tvo_lcm::command_t::STATUS_ERR_NO_SESSION).
    bool restart_pending_{false};
    StartRepeats restart_repeats_;              // the restart's START copies, backing off as the first session's
    std::optional<tvo_lcm::session_ack_t> restart_refused_;
    std::int64_t last_sent_sequence_{-1};
    std::int64_t restart_acked_through_sequence_{-1};  // newest sent when the last restart was acked

    // --link-loss figures (realtime): plant-clock utimes from the commands' own stamps.
    std::optional<std::int64_t> last_answer_before_loss_utime_;
    std::optional<std::int64_t> first_safe_stop_after_loss_utime_;

    bool heading_sent_{false};
    JointMeasurement measurement_{};
    tvo_lcm::target_t target_{};
};

}  // namespace tvo_host
