#pragma once
/// @file time.hpp
/// The one time base of the project: CLOCK_MONOTONIC. Every timestamp in the shared memory, on
/// the wire and in the cycle is a TimeNs on it; a deadline of a setup or blocking call is a
/// MonotonicClock::time_point (std::chrono's type checking for spans and moments). Both read the
/// same clock, so a TimeNs from a region and MonotonicClock::now() compare directly.
///
/// Real-time contract: now() and monotonic_now_ns() are one vDSO call (no syscall on x86-64),
/// allocate nothing; safe in the cycle.

#include <time.h>

#include <chrono>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl {

/// A moment on CLOCK_MONOTONIC, or a span, in nanoseconds: the form the regions, the protocol's
/// frames and the cycle's arithmetic carry.
using TimeNs = std::int64_t;

inline constexpr TimeNs kNsPerUs = 1'000;
inline constexpr TimeNs kNsPerMs = 1'000'000;
inline constexpr TimeNs kNsPerS = 1'000'000'000;

/// CLOCK_MONOTONIC as a std::chrono clock (a steady clock; on Linux the same clock as
/// std::chrono::steady_clock, named here so that no room picks another).
struct MonotonicClock {
  using duration = std::chrono::nanoseconds;
  using rep = duration::rep;
  using period = duration::period;
  using time_point = std::chrono::time_point<MonotonicClock>;
  static constexpr bool is_steady = true;

  HAPTICCTRL_RT static time_point now() noexcept {
    timespec ts{};
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return time_point(duration(static_cast<TimeNs>(ts.tv_sec) * kNsPerS + ts.tv_nsec));
  }
};

/// MonotonicClock::now() as a TimeNs.
HAPTICCTRL_RT inline TimeNs monotonic_now_ns() noexcept {
  return MonotonicClock::now().time_since_epoch().count();
}

}  // namespace hapticctrl
