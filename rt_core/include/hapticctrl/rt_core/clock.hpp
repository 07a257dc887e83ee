#pragma once
/// @file clock.hpp
/// The clock seam: the executive reads time and sleeps only through this interface, so the
/// whole cycle can run against a fake clock in unit tests (scenarios of seconds in microseconds).
/// The control law, the simulator and the deadline monitor never read a clock: they take
/// `now`/`dt` as arguments.

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/base/time.hpp"

namespace hapticctrl::rt_core {

/// Time source and absolute sleep.
class Clock {
 public:
  virtual ~Clock() = default;
  /// Current time. Real-time contract: safe in the cycle (vDSO, no syscall on x86-64).
  [[nodiscard]] HAPTICCTRL_RT virtual TimePoint now() noexcept = 0;
  /// Sleeps until the absolute time `deadline` (returns at once if it has passed).
  /// Real-time contract: the cycle's one allowed blocking call (clock_nanosleep TIMER_ABSTIME).
  HAPTICCTRL_RT virtual void sleep_until(TimePoint deadline) noexcept = 0;
};

/// MonotonicClock (base/time.hpp) with clock_nanosleep(TIMER_ABSTIME), retried on EINTR.
class RealClock final : public Clock {
 public:
  [[nodiscard]] HAPTICCTRL_RT TimePoint now() noexcept override;
  HAPTICCTRL_RT void sleep_until(TimePoint deadline) noexcept override;
};

/// A clock that only moves when told to. sleep_until() jumps to the deadline plus an optional
/// one-shot oversleep, which is how tests model late wake-ups.
class FakeClock final : public Clock {
 public:
  explicit FakeClock(TimePoint start = TimePoint(std::chrono::seconds(1'000))) noexcept
      : now_(start) {}
  [[nodiscard]] HAPTICCTRL_RT TimePoint now() noexcept override { return now_; }
  HAPTICCTRL_RT void sleep_until(TimePoint deadline) noexcept override;
  /// Moves time forward by `dt` (tests: work that takes time).
  void advance(Duration dt) noexcept { now_ += dt; }
  /// The next sleep_until() wakes `extra` late (tests: a preempted CLOCK).
  void oversleep_next(Duration extra) noexcept { oversleep_ = extra; }
  /// The sleep_until(deadline) call with exactly this deadline wakes `extra` late.
  void oversleep_at(TimePoint deadline, Duration extra) noexcept {
    oversleep_deadline_ = deadline;
    oversleep_at_extra_ = extra;
  }

 private:
  TimePoint now_;
  Duration oversleep_{0};
  TimePoint oversleep_deadline_ = kNotYet;
  Duration oversleep_at_extra_{0};
};

}  // namespace hapticctrl::rt_core
