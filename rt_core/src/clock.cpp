// Implements clock.hpp: the clock seam: the executive reads time and sleeps only through this
// interface, so the whole cycle can run against a fake clock in unit tests (scenarios of seconds in
// microseconds).
#include "hapticctrl/rt_core/clock.hpp"

#include <cerrno>
#include <ctime>

namespace hapticctrl::rt_core {

TimeNs RealClock::now() noexcept {
  return monotonic_now_ns();
}

void RealClock::sleep_until(TimeNs deadline) noexcept {
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(deadline / kNsPerS);
  ts.tv_nsec = static_cast<long>(deadline % kNsPerS);
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

void FakeClock::sleep_until(TimeNs deadline) noexcept {
  if (deadline > now_) {
    now_ = deadline;
  }
  now_ += oversleep_;
  oversleep_ = 0;
  if (deadline == oversleep_deadline_) {
    now_ += oversleep_at_extra_;
    oversleep_deadline_ = -1;
  }
}

}  // namespace hapticctrl::rt_core
