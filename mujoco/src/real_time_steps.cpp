// Implements real_time_steps.hpp: real-time stepping with a bounded catch-up.
#include "hapticctrl/mujoco/real_time_steps.hpp"

#include <algorithm>

namespace hapticctrl::mujoco {

RealTimeSteps::RealTimeSteps(Duration step, Duration max_catch_up) noexcept
    : step_(std::max(Duration(1), step)),
      max_catch_up_(static_cast<std::uint64_t>(std::max<Duration::rep>(1, max_catch_up / step_))) {}

void RealTimeSteps::start(TimePoint now) noexcept {
  origin_ = now;
  accounted_ = 0;
}

std::uint64_t RealTimeSteps::owed(TimePoint now) const noexcept {
  if (now <= origin_) {
    return 0;
  }
  const auto made_due = static_cast<std::uint64_t>((now - origin_) / step_);
  return made_due > accounted_ ? made_due - accounted_ : 0;
}

std::uint64_t RealTimeSteps::due(TimePoint now) noexcept {
  const std::uint64_t owed_now = owed(now);
  const std::uint64_t steps = std::min(owed_now, max_catch_up_);
  dropped_ += owed_now - steps;
  catch_ups_ += steps > 1 ? 1 : 0;
  run_ += steps;
  accounted_ += owed_now;
  return steps;
}

void RealTimeSteps::pause(TimePoint now) noexcept {
  const std::uint64_t owed_now = owed(now);
  paused_ += owed_now;
  accounted_ += owed_now;
}

TimePoint RealTimeSteps::next_due() const noexcept {
  return origin_ + static_cast<Duration::rep>(accounted_ + 1) * step_;
}

}  // namespace hapticctrl::mujoco
