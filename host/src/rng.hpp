// Reproducible random streams: one std::mt19937_64 per purpose, all derived from the run's seed.
//
// Separate streams keep runs comparable: turning drops on does not change the noise sequence.
#pragma once

#include <cstdint>
#include <random>

namespace tvo_host {

enum class RngStream : std::uint32_t { MeasurementNoise = 1, Drops = 2, Disturbance = 3 };

inline std::mt19937_64 make_rng(std::uint64_t seed, RngStream stream)
{
    std::seed_seq seq{static_cast<std::uint32_t>(seed), static_cast<std::uint32_t>(seed >> 32),
                      static_cast<std::uint32_t>(stream)};
    return std::mt19937_64(seq);
}

}  // namespace tvo_host
