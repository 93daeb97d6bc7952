// Transport faults injected by the simulator: dropped measurements and extra command latency.
//
// A dropped measurement is never published: the firmware gets nothing that period and the plant
// keeps holding the last applied command; the node accepts the next measurement across the gap.
// Extra delay postpones when each command takes effect on the plant beyond its utime, an
// unmodelled latency the controller's delay compensation does not know about.
#pragma once

#include <cstdint>
#include <random>

namespace tvo_host {

struct FaultConfig {
    double drop_probability{0.0};   // per measurement, 0..1
    std::int64_t extra_delay_us{0};  // >= 0
};

class FaultInjector {
public:
    FaultInjector(const FaultConfig& config, std::uint64_t seed);

    /// True when this period's measurement is lost (one draw per period, only if drops are on).
    bool drop_measurement();

    std::int64_t extra_delay_us() const { return config_.extra_delay_us; }
    std::uint64_t drops() const { return drops_; }

private:
    FaultConfig config_;
    std::mt19937_64 rng_;
    std::uniform_real_distribution<double> uniform_{0.0, 1.0};
    std::uint64_t drops_{0};
};

}  // namespace tvo_host
