// The ranges of tvo_sim's settings, written once: the command line (options.cpp) checks its options
// against them and a scenario file (scenario_file.cpp) the same settings under their YAML names.
// Why each range is what it is: host/README.md, "Options".
#pragma once

#include <cstdint>

#include "option_ranges.hpp"

extern "C" {
#include "tvo/config.h"        // TVO_BARRIER_MAX_DEGREE
#include "tvo/sample_clock.h"  // TVO_MAX_TICK_SPAN
}

namespace tvo_host::sim_ranges {

using tvo_options::End;
using tvo_options::Interval;

constexpr double kUsPerS = 1e6;
constexpr double kMinPeriodS = 1e-6;                                                // the node's tick
constexpr double kMaxPeriodS = static_cast<double>(TVO_MAX_TICK_SPAN) / kUsPerS;  // the node's tick span
constexpr double kMaxDurationS = 86400.0;                                          // a day: the soak of issue 11
constexpr double kMaxSigma = 1.0;            // m, rad, m/s
constexpr double kMaxFilterTfS = 10.0;
constexpr double kMaxGain = 1e6;             // |KP| (1/s^2), |KD| (1/s)
constexpr double kMaxTurnRateRadps = 100.0;
constexpr double kMaxAccelMps2 = 100.0;
constexpr double kMaxSpeedMps = 100.0;
constexpr double kMaxBarrierScale = 1e6;     // c0, c_max
constexpr double kMaxBarrierRatePerS = 1e3;  // alpha_c, alpha_s
constexpr double kMaxBarrierLength = 100.0;  // delta0, slack margin (units of the constraint functions)
constexpr double kMaxExtraDelayS = 10.0;
constexpr double kMaxDisturbance = 10.0;     // m/s, rad/s

// Timing.
constexpr Interval kPeriod{kMinPeriodS, kMaxPeriodS, "s"};
constexpr Interval kDelay{0.0, kMaxPeriodS, "s"};
constexpr Interval kDuration{0.0, kMaxDurationS, "s", End::Open};
// Sensing.
constexpr Interval kSigma{0.0, kMaxSigma, ""};
constexpr Interval kFilterTf{0.0, kMaxFilterTfS, "s", End::Open};
// Controller.
constexpr Interval kGainKp{-kMaxGain, kMaxGain, "1/s^2"};
constexpr Interval kGainKd{-kMaxGain, kMaxGain, "1/s"};
constexpr Interval kOmegaMax{0.0, kMaxTurnRateRadps, "rad/s", End::Open};
constexpr Interval kAccelMax{0.0, kMaxAccelMps2, "m/s^2", End::Open};
constexpr Interval kSpeedMax{0.0, kMaxSpeedMps, "m/s", End::Open};
constexpr Interval kMinSpeed{0.0, kMaxSpeedMps, "m/s", End::Open};
constexpr std::int32_t kMinWatchdogPeriods = 1;
constexpr auto kMaxWatchdogPeriods = static_cast<std::int32_t>(TVO_MAX_TICK_SPAN);
// Barrier (the finer rules, c_max >= c0 and m_r >= k + 1, are the firmware's).
constexpr Interval kBarrierC0{0.0, kMaxBarrierScale, "", End::Open};
constexpr Interval kBarrierAlphaC{0.0, kMaxBarrierRatePerS, "1/s"};
constexpr Interval kBarrierCMax{0.0, kMaxBarrierScale, "", End::Open};
constexpr Interval kBarrierDelta0{0.0, kMaxBarrierLength, "", End::Open};
constexpr Interval kBarrierAlphaS{0.0, kMaxBarrierRatePerS, "1/s", End::Open};
constexpr Interval kBarrierSlackMargin{0.0, kMaxBarrierLength, "", End::Open};
constexpr int kMinBarrierDegree = 1;
constexpr int kMaxBarrierDegree = TVO_BARRIER_MAX_DEGREE;
// Faults.
constexpr Interval kDropProb{0.0, 1.0, "", End::Closed, End::Open};
constexpr Interval kExtraDelay{0.0, kMaxExtraDelayS, "s"};
constexpr Interval kLinkLossStart{0.0, kMaxDurationS, "s"};
constexpr Interval kLinkLossDuration{0.0, kMaxDurationS, "s", End::Open};
constexpr Interval kDisturbanceSpeed{0.0, kMaxDisturbance, "m/s"};
constexpr Interval kDisturbanceTurn{0.0, kMaxDisturbance, "rad/s"};

}  // namespace tvo_host::sim_ranges
