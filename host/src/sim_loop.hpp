// The closed loop on the plant side: sample, publish, receive commands, integrate exactly.
//
// Timing (plant time in whole microseconds from the session epoch, t_n = n h; on the wire
// utime = epoch_utime + plant time):
//   measurement n (sequence n, for the node's period n + 1) is sampled at s_n = t_{n+1} - tau
//   (mid-interval when tau > 0: the plant is integrated along its arc up to s_n, then on to the
//   boundary); the command answering it is applied at its utime, nominally t_{n+1} (+ any injected
//   extra delay), and held until the next one. The robots hold zero input until the first command;
//   the run ends at T = steps h.
// Commands (lcm_types/README.md, "Writing your own plant"): one robot's each, joined per period into the
//   joint command (CommandAssembler); it is applied only if it carries our session id and either answers a
//   sample we sent that is newer than the command in force, or is a safe stop.
// The nodes (rule 5): when a node we named announces a new boot, or says it is idle after it ran our
//   session, or the node falls silent (realtime: no command, not even the node's own safe stops, for
//   (watchdog_periods + 2) h after the newest command's apply instant; lockstep with
//   --on-missing-answer hold: watchdog_periods samples in a row unanswered), the plant stops its robots
//   and sends START again naming the nodes' current boots: of a new session (fresh id) when a node
//   restarted or lost ours, else the same START (a node that still runs it acks a repeat and changes
//   nothing); lockstep waits for every ack.
// Lockstep (session CLOCK_PLANT): after publishing the samples of period n the loop blocks (wall-clock
//   timeout) until every robot's command answering n arrives, and its telemetry when n carries some
//   (every telemetry_every-th sequence), so the run is deterministic and as fast as the transport.
//   Epoch = --start-utime-us.
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
#include <array>
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
    std::uint64_t session_restarts{0};        // rule 5: robots stopped, a new session started
    std::uint64_t safe_stop_commands{0};      // safe stops applied to the plant
    std::optional<double> first_safe_stop_after_loss_s;  // realtime with --link-loss, see README
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
    void on_node_status(const tvo_lcm::node_status_t& status) override;

private:
    struct PendingCommand {
        std::int64_t apply_us{0};
        std::int64_t sequence{0};
        std::array<UnicycleInput, kMaxRobots> input{};
        std::int32_t status{0};
        std::int32_t flags{0};
    };
    enum class Answer { Received, Lost, Restart, Interrupted };

    void advance_to(std::int64_t t_us);
    void integrate_to(std::int64_t t_us);
    void check_constraints(std::int64_t t_us);
    bool publish_sample(std::int64_t sequence, std::int64_t sample_us);  // false if not sent
    Answer await_answer(std::int64_t sequence);
    void bind_nodes();                           // the roles of the nodes the session names
    void begin_restart(bool new_session);        // rule 5: robots stopped, START again (a new session if needed)
    bool await_restart();                        // lockstep; false when interrupted
    void service_restart();                      // (re)sends START while a restart is pending
    bool telemetry_due(std::int64_t sequence) const;
    std::int64_t silence_limit_us() const;       // realtime: rule 5's silence
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
    const std::int64_t telemetry_every_;     // the periods whose answers carry telemetry
    std::array<std::int64_t, kMaxRobots> telemetry_sequence_{};  // per robot: newest telemetry received
    std::array<StepTelemetry, kMaxRobots> telemetry_{};          // per robot: newest received
    LoopResult counts_{};                    // the counters of the result, filled as the run goes

    // Rule 5: a new session when a node restarted, lost ours or fell silent.
    std::vector<std::int8_t> roles_;          // per named boot: its node's own_robot
    std::vector<std::int64_t> running_seen_;  // per named boot: node utime it last said it runs ours, -1 none
    bool restart_pending_{false};
    bool restart_begun_{false};               // the new session's START is out (its nodes were heard)
    bool restart_new_session_{false};         // a node restarted or lost ours (not just silence)
    std::optional<tvo_lcm::session_ack_t> restart_refused_;
    std::optional<std::int64_t> silent_since_us_;  // realtime: plant time of the newest command of ours, or
                                                   // when the session's first sample went out before any came
    std::int64_t unanswered_streak_{0};       // lockstep: sent samples in a row that got no answer

    // --link-loss figures (realtime): plant-clock utimes from the commands' own stamps.
    std::optional<std::int64_t> last_answer_before_loss_utime_;
    std::optional<std::int64_t> first_safe_stop_after_loss_utime_;

    bool heading_sent_{false};
    JointMeasurement measurement_{};
    tvo_lcm::target_t target_{};
};

}  // namespace tvo_host
