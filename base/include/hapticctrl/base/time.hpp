#pragma once
/// @file time.hpp
/// The one time base of the project: CLOCK_MONOTONIC. A moment on it is a TimePoint and a span a
/// Duration (std::chrono's checked types: a moment and a span do not mix, nor a span and a bare
/// number); the shared memory's and the wire's timestamps are nanosecond counts on the same
/// clock (to_ns, time_point_from_ns). The rooms that have not moved to the checked types yet
/// carry TimeNs, that count (docs/architecture.md, the vocabulary).
///
/// Real-time contract: now() and monotonic_now_ns() are one vDSO call (no syscall on x86-64),
/// allocate nothing; safe in the cycle.

#include <time.h>

#include <chrono>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl {

/// A moment on CLOCK_MONOTONIC, or a span, in nanoseconds: the regions' and the frames' form, and
/// the rooms' that have not moved to TimePoint and Duration yet.
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

/// A span of time (std::chrono's checked arithmetic; the cycle, the law, the clock seam).
using Duration = std::chrono::nanoseconds;
/// A moment on CLOCK_MONOTONIC.
using TimePoint = MonotonicClock::time_point;
/// "Not yet": a moment that has not happened (a task not started, a release not judged).
inline constexpr TimePoint kNotYet = TimePoint::min();

/// The edges (the regions' and frames' nanosecond fields) and the physics (seconds): the only
/// places a moment or a span leaves its type. Real-time contract: constexpr arithmetic; safe in
/// the cycle.
[[nodiscard]] HAPTICCTRL_RT constexpr std::int64_t to_ns(Duration span) noexcept {
  return span.count();
}
[[nodiscard]] HAPTICCTRL_RT constexpr std::int64_t to_ns(TimePoint moment) noexcept {
  return moment.time_since_epoch().count();
}
[[nodiscard]] HAPTICCTRL_RT constexpr TimePoint time_point_from_ns(std::int64_t ns) noexcept {
  return TimePoint(Duration(ns));
}
[[nodiscard]] HAPTICCTRL_RT constexpr double to_seconds(Duration span) noexcept {
  return std::chrono::duration<double>(span).count();
}

/// MonotonicClock::now() as a TimeNs.
HAPTICCTRL_RT inline TimeNs monotonic_now_ns() noexcept {
  return MonotonicClock::now().time_since_epoch().count();
}

}  // namespace hapticctrl
