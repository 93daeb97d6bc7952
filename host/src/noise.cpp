// Measurement noise and process disturbance; see noise.hpp.
#include "noise.hpp"

#include <cmath>

#include "rng.hpp"

namespace tvo_host {

double wrap_angle(double angle_rad)
{
    return std::atan2(std::sin(angle_rad), std::cos(angle_rad));
}

MeasurementNoise::MeasurementNoise(const MeasurementNoiseConfig& config, std::uint64_t seed)
    : config_(config), rng_(make_rng(seed, RngStream::MeasurementNoise))
{
}

double MeasurementNoise::draw(double sigma)
{
    // A noiseless run stays bit-exact and consumes no random numbers.
    return sigma > 0.0 ? sigma * unit_(rng_) : 0.0;
}

RobotSample MeasurementNoise::measure(const UnicycleState& state, const UnicycleInput& input)
{
    RobotSample sample;
    sample.position_m.x() = state.position_m.x() + draw(config_.position_sigma_m);
    sample.position_m.y() = state.position_m.y() + draw(config_.position_sigma_m);
    sample.heading_rad = wrap_angle(state.heading_rad + draw(config_.heading_sigma_rad));
    sample.speed_mps = input.speed_mps + draw(config_.speed_sigma_mps);
    return sample;
}

ProcessDisturbance::ProcessDisturbance(const DisturbanceConfig& config, std::uint64_t seed)
    : config_(config), rng_(make_rng(seed, RngStream::Disturbance))
{
}

UnicycleInput ProcessDisturbance::perturb(const UnicycleInput& commanded)
{
    UnicycleInput actual = commanded;
    if (config_.speed_sigma_mps > 0.0) {
        actual.speed_mps += config_.speed_sigma_mps * unit_(rng_);
    }
    if (config_.turn_rate_sigma_radps > 0.0) {
        actual.turn_rate_radps += config_.turn_rate_sigma_radps * unit_(rng_);
    }
    return actual;
}

}  // namespace tvo_host
