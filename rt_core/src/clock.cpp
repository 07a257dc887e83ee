// Implements clock.hpp: the clock seam: the executive reads time and sleeps only through this
// interface, so the whole cycle can run against a fake clock in unit tests (scenarios of seconds in
// microseconds).
#include "hapticctrl/rt_core/clock.hpp"

#include <cerrno>
#include <chrono>
#include <ctime>

namespace hapticctrl::rt_core {

TimePoint RealClock::now() noexcept {
  return MonotonicClock::now();
}

void RealClock::sleep_until(TimePoint deadline) noexcept {
  const auto seconds = std::chrono::floor<std::chrono::seconds>(deadline.time_since_epoch());
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(seconds.count());
  ts.tv_nsec = static_cast<long>((deadline.time_since_epoch() - seconds).count());
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

void FakeClock::sleep_until(TimePoint deadline) noexcept {
  if (deadline > now_) {
    now_ = deadline;
  }
  now_ += oversleep_;
  oversleep_ = Duration{0};
  if (deadline == oversleep_deadline_) {
    now_ += oversleep_at_extra_;
    oversleep_deadline_ = kNotYet;
  }
}

}  // namespace hapticctrl::rt_core
