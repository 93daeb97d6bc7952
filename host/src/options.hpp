// Command line of tvo_sim (CLI11): every numeric option has a range (shown by --help, the reasons in
// host/README.md, "Options"), checked with the cross-option rules before any work; validated into
// whole-microsecond timing.
#pragma once

#include <cstdint>
#include <ostream>
#include <string>

#include "scenario.hpp"
#include "tvo/defaults.h"

namespace tvo_host {

/// Lockstep: what a measurement whose answer does not come within --answer-timeout-s does to the run.
enum class MissingAnswer {
    Fail,  // the run ends with an error (exit code 1)
    Hold   // the answer counts as lost; the plant holds its command and the loop goes on
};

struct SimOptions {
    // Timing (seconds as given; *_us derived, whole microseconds).
    double period_s{0.01};
    double delay_s{0.005};         // default h/2
    double duration_s{20.0};
    bool delay_compensation{true};
    bool zoh_aware{false};          // evaluate the law at the middle of each held interval
    bool realtime{false};
    double answer_timeout_s{2.0};   // lockstep: longest wait for the firmware's answer
    MissingAnswer on_missing_answer{MissingAnswer::Fail};
    // Lockstep: plant time 0 on the wire (the session's epoch). Realtime: the plant clock's reading
    // when tvo_sim starts (the epoch follows the first START, see sim_loop.hpp).
    std::int64_t start_utime_us{1000000};

    // Sensing.
    double sigma{0.0};              // position (m), heading (rad) and speed (m/s) noise sigma
    bool position_only{false};
    double filter_tf_s{TVO_DEFAULT_FILTER_TF_S};
    std::uint64_t seed{1};

    // Controller (validated by the firmware, not here: the firmware is the authority).
    double gain_kp{TVO_DEFAULT_GAIN_KP};
    double gain_kd{TVO_DEFAULT_GAIN_KD};
    double omega_max_radps{TVO_DEFAULT_OMEGA_MAX_RADPS};
    double accel_max_mps2{TVO_DEFAULT_ACCEL_MAX_MPS2};
    double speed_max_mps{TVO_DEFAULT_SPEED_MAX_MPS};
    double min_speed_mps{TVO_DEFAULT_MIN_SPEED_MPS};
    std::int32_t watchdog_periods{TVO_DEFAULT_WATCHDOG_PERIODS};
    std::int32_t telemetry_every{0};  // session_t.telemetry_every: 0, the node's default (about 10 Hz)

    // Scenario (scenario.hpp). robots and the ellipse/circle choice shape the demo only.
    std::string scenario{"demo"};
    std::size_t robots{1};
    TargetKind target{TargetKind::Ellipse};
    BarrierOverrides barrier;       // --barrier-*: replace the scenario's barrier settings
    bool list_scenarios{false};

    // Faults.
    double drop_prob{0.0};
    double extra_delay_s{0.0};
    double disturbance_speed_mps{0.0};
    double disturbance_turn_radps{0.0};
    double link_loss_start_s{0.0};  // --link-loss S,D: no measurement for sample times in [S, S + D)
    double link_loss_duration_s{0.0};

    // Plumbing.
    std::string lcm_url;            // empty: LCM's default ($LCM_DEFAULT_URL or udpm)
    std::string key_file;           // empty: an unauthenticated bus; else the 32-byte key (tools/keygen)
    std::uint32_t sender_id{2};     // this plant's sender id on a keyed bus (TVO_AUTH_SENDER_PLANT)
    std::string firmware;           // tvo_firmware_node to spawn; empty: one is already running
    std::string out_dir{"runs/demo"};
    std::string summary_json;       // empty: <out-dir>/summary.json
    std::uint64_t max_output_mib{1024};  // refuse a run whose files could exceed this (MiB)
    bool dry_run{false};            // check the options, print what the run would do, run nothing

    // Derived.
    std::int64_t period_us{TVO_DEFAULT_PERIOD_US};
    std::int64_t delay_us{TVO_DEFAULT_DELAY_US};
    std::int64_t extra_delay_us{0};
    std::int64_t steps{2000};
    std::int64_t link_loss_start_us{0};
    std::int64_t link_loss_end_us{0};  // == start: no link loss

    bool has_link_loss() const { return link_loss_end_us > link_loss_start_us; }
    /// True when the measurement sampled at plant time sample_us is lost to --link-loss.
    bool link_lost_at(std::int64_t sample_us) const
    {
        return sample_us >= link_loss_start_us && sample_us < link_loss_end_us;
    }
};

/// Prints each file of the scenario folder: its name and its description, one line each. A file that
/// does not load is named on err; returns 0, or 2 if one did not load.
int print_scenario_list(std::ostream& out, std::ostream& err);

/// Parses and validates argv. Returns -1 to run, or the exit code to leave with: 0 after --help,
/// --list-scenarios or --dry-run, 2 after a one-line error naming the offending option and its range.
int parse_options(int argc, char** argv, SimOptions* options);

}  // namespace tvo_host
