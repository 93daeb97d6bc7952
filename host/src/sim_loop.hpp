// The closed loop on the plant side: sample, publish, receive commands, integrate exactly.
//
// Timing (plant time in whole microseconds from the epoch, t_n = n h):
//   measurement n is sampled at s_n = t_{n+1} - tau (mid-interval when tau > 0: the plant is
//   integrated along its arc up to s_n, then on to the boundary); the command answering it is
//   applied at its utime t_{n+1} (+ any injected extra delay) and held until the next one.
//   The robots hold zero input until the first command; the run ends at T = steps h.
// Lockstep: after publishing measurement n the loop blocks (wall-clock timeout) until the command
//   and the telemetry answering n arrive, so the run is deterministic and as fast as the transport.
// Constraint checks: the constraint monitor sees the true positions every kCheckStepUs of plant
//   time along the exact arcs, and at every sample and command instant.
// Realtime: plant time follows the wall clock; commands take effect at their utime, or on arrival
//   when they come late (counted). A dropped measurement is never sent and nothing is awaited.
#pragma once

#include <chrono>
#include <csignal>
#include <cstdint>
#include <vector>

#include "constraint_metrics.hpp"
#include "faults.hpp"
#include "metrics.hpp"
#include "noise.hpp"
#include "options.hpp"
#include "plant.hpp"
#include "run_recorder.hpp"
#include "scenario.hpp"
#include "transport.hpp"

namespace tvo_host {

struct LoopResult {
    std::int64_t steps{0};
    double wall_s{0.0};
    std::uint64_t drops{0};
    std::uint64_t late_commands{0};
    bool interrupted{false};
};

class SimLoop : public TransportListener {
public:
    SimLoop(const SimOptions& options, const Scenario& scenario, LcmTransport& transport, RunRecorder& recorder,
            TrackingMetrics& metrics, ConstraintMonitor& monitor, const volatile std::sig_atomic_t& stop_signal);

    /// Runs all periods. TransportError if, in lockstep, the firmware does not answer in time.
    LoopResult run();

    void on_command(const tvo_lcm::command_t& command) override;
    void on_session_ack(const tvo_lcm::session_ack_t&) override {}
    void on_telemetry(const tvo_lcm::telemetry_t& telemetry) override;

private:
    struct PendingCommand {
        std::int64_t apply_us{0};
        std::int64_t sequence{0};
        std::array<UnicycleInput, kMaxRobots> input{};
        std::int32_t status{0};
        std::int32_t flags{0};
    };

    void advance_to(std::int64_t t_us);
    void integrate_to(std::int64_t t_us);
    void check_constraints(std::int64_t t_us);
    void publish_sample(std::int64_t sequence, std::int64_t sample_us);
    bool await_answer(std::int64_t sequence);  // false when interrupted
    bool wait_until(std::int64_t t_us);        // realtime; false when interrupted
    void record(std::int64_t t_us);
    std::int64_t wall_plant_us() const;
    bool stopping() const { return stop_signal_ != 0; }

    const SimOptions& options_;
    const Scenario& scenario_;
    LcmTransport& transport_;
    RunRecorder& recorder_;
    TrackingMetrics& metrics_;
    ConstraintMonitor& monitor_;
    const volatile std::sig_atomic_t& stop_signal_;

    UnicyclePlant plant_;
    MeasurementNoise noise_;
    ProcessDisturbance disturbance_;
    FaultInjector faults_;

    std::int64_t now_us_{0};                 // plant time integrated so far
    std::vector<PendingCommand> pending_;    // by apply time; capacity reserved up front
    PendingCommand applied_{};               // command in force (as commanded, before disturbance)
    std::int64_t last_queued_sequence_{-1};
    std::int64_t answered_sequence_{-1};
    std::int64_t telemetry_sequence_{-1};    // newest telemetry received
    StepTelemetry telemetry_{};              // newest received (lockstep: of the command in force)
    std::uint64_t late_commands_{0};
    bool heading_sent_{false};
    std::chrono::steady_clock::time_point wall_epoch_{};
    tvo_lcm::measurement_t measurement_{};
    tvo_lcm::target_t target_{};
};

}  // namespace tvo_host
