// The plant's clock in realtime runs: whole microseconds of the monotonic clock (steady_clock is
// CLOCK_MONOTONIC on Linux), reading `origin_utime` when constructed. Wall-clock jumps cannot move it.
#pragma once

#include <chrono>
#include <cstdint>

namespace tvo_host {

class PlantClock {
public:
    explicit PlantClock(std::int64_t origin_utime)
        : origin_utime_(origin_utime), origin_(std::chrono::steady_clock::now())
    {
    }

    std::int64_t now_utime() const
    {
        return origin_utime_ + std::chrono::duration_cast<std::chrono::microseconds>(
                                   std::chrono::steady_clock::now() - origin_)
                                   .count();
    }

private:
    std::int64_t origin_utime_;
    std::chrono::steady_clock::time_point origin_;
};

}  // namespace tvo_host
