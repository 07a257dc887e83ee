#pragma once
/// @file clock.hpp
/// The clock seam: the executive reads time and sleeps only through this interface, so the
/// whole cycle can run against a fake clock in unit tests (scenarios of seconds in microseconds).
/// The control law, the simulator and the deadline monitor never read a clock: they take
/// `now`/`dt` as arguments.

#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/base/time.hpp"

namespace hapticctrl::rt_core {

/// Time source and absolute sleep.
class Clock {
 public:
  virtual ~Clock() = default;
  /// Current time. Real-time contract: safe in the cycle (vDSO, no syscall on x86-64).
  [[nodiscard]] HAPTICCTRL_RT virtual TimeNs now() noexcept = 0;
  /// Sleeps until the absolute time `deadline` (returns at once if it has passed).
  /// Real-time contract: the cycle's one allowed blocking call (clock_nanosleep TIMER_ABSTIME).
  HAPTICCTRL_RT virtual void sleep_until(TimeNs deadline) noexcept = 0;
};

/// MonotonicClock (base/time.hpp) with clock_nanosleep(TIMER_ABSTIME), retried on EINTR.
class RealClock final : public Clock {
 public:
  [[nodiscard]] HAPTICCTRL_RT TimeNs now() noexcept override;
  HAPTICCTRL_RT void sleep_until(TimeNs deadline) noexcept override;
};

/// A clock that only moves when told to. sleep_until() jumps to the deadline plus an optional
/// one-shot oversleep, which is how tests model late wake-ups.
class FakeClock final : public Clock {
 public:
  explicit FakeClock(TimeNs start = 1'000 * kNsPerS) noexcept : now_(start) {}
  [[nodiscard]] HAPTICCTRL_RT TimeNs now() noexcept override { return now_; }
  HAPTICCTRL_RT void sleep_until(TimeNs deadline) noexcept override;
  /// Moves time forward by `dt` (tests: work that takes time).
  void advance(TimeNs dt) noexcept { now_ += dt; }
  /// The next sleep_until() wakes `extra` late (tests: a preempted CLOCK).
  void oversleep_next(TimeNs extra) noexcept { oversleep_ = extra; }
  /// The sleep_until(deadline) call with exactly this deadline wakes `extra` late.
  void oversleep_at(TimeNs deadline, TimeNs extra) noexcept {
    oversleep_deadline_ = deadline;
    oversleep_at_extra_ = extra;
  }

 private:
  TimeNs now_;
  TimeNs oversleep_ = 0;
  TimeNs oversleep_deadline_ = -1;
  TimeNs oversleep_at_extra_ = 0;
};

}  // namespace hapticctrl::rt_core
