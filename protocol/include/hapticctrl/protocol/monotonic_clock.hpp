#pragma once
/// @file monotonic_clock.hpp
/// CLOCK_MONOTONIC in nanoseconds: the time base of every protocol timestamp (sender times,
/// round trips, the bridge's receive times written into VPr).
#include <time.h>

#include <cstdint>

namespace hapticctrl::protocol {

/// Real-time contract: one vDSO call, no allocation; safe in a cycle.
[[nodiscard]] inline std::int64_t monotonic_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace hapticctrl::protocol
