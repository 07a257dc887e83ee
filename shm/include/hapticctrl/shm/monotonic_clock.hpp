#pragma once
/// @file monotonic_clock.hpp
/// The clock of every timestamp in the shared memory: publish times, the core's heartbeat.
#include <time.h>

#include <cstdint>

namespace hapticctrl::shm {

/// CLOCK_MONOTONIC in nanoseconds. Real-time contract: one vDSO call, no syscall; safe anywhere.
[[nodiscard]] inline std::int64_t monotonic_now_ns() noexcept {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1'000'000'000 + ts.tv_nsec;
}

}  // namespace hapticctrl::shm
