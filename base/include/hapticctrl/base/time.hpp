#pragma once
/// @file time.hpp
/// The one time base of the project: CLOCK_MONOTONIC. A moment on it is a TimePoint and a span a
/// Duration (std::chrono's checked types: a moment and a span do not mix, nor a span and a bare
/// number), in every room; the shared memory's fields, the wire's timestamps and the client
/// library's public API carry nanosecond counts on the same clock (to_ns, time_point_from_ns at
/// those edges only; docs/architecture.md, the vocabulary).
///
/// Real-time contract: MonotonicClock::now() is one vDSO call (no syscall on x86-64), allocates
/// nothing; safe in the cycle.

#include <time.h>

#include <chrono>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl {

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
    return time_point(std::chrono::seconds(ts.tv_sec) + duration(ts.tv_nsec));
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
/// A span given in seconds (an option's, a scene's), to the nearest nanosecond (a cast cuts an
/// option's 33.3 ms, 33.3 / 1e3 s = 33299999.999999996 ns in binary, to 33299999 ns).
[[nodiscard]] HAPTICCTRL_RT constexpr Duration from_seconds(double seconds) noexcept {
  return std::chrono::round<Duration>(std::chrono::duration<double>(seconds));
}

/// When a program run for `seconds` (its --duration) ends: that long from now, or never
/// (TimePoint::max()) for 0 or less. Reads the clock: not for the cycle.
[[nodiscard]] inline TimePoint end_after(double seconds) noexcept {
  return seconds > 0.0 ? MonotonicClock::now() + from_seconds(seconds) : TimePoint::max();
}

}  // namespace hapticctrl
