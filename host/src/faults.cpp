// Dropped measurements and extra latency; see faults.hpp.
#include "faults.hpp"

#include "rng.hpp"

namespace tvo_host {

FaultInjector::FaultInjector(const FaultConfig& config, std::uint64_t seed)
    : config_(config), rng_(make_rng(seed, RngStream::Drops))
{
}

bool FaultInjector::drop_measurement()
{
    if (!(config_.drop_probability > 0.0)) {
        return false;
    }
    const bool drop = uniform_(rng_) < config_.drop_probability;
    drops_ += drop ? 1u : 0u;
    return drop;
}

}  // namespace tvo_host
