// Implements real_time_steps.hpp: real-time stepping with a bounded catch-up.
#include "hapticctrl/mujoco/real_time_steps.hpp"

#include <algorithm>

namespace hapticctrl::mujoco {

RealTimeSteps::RealTimeSteps(std::int64_t step_ns, std::int64_t max_catch_up_ns) noexcept
    : step_ns_(std::max<std::int64_t>(1, step_ns)),
      max_catch_up_(
          static_cast<std::uint64_t>(std::max<std::int64_t>(1, max_catch_up_ns / step_ns_))) {}

void RealTimeSteps::start(std::int64_t now_ns) noexcept {
  origin_ns_ = now_ns;
  accounted_ = 0;
}

std::uint64_t RealTimeSteps::owed(std::int64_t now_ns) const noexcept {
  if (now_ns <= origin_ns_) {
    return 0;
  }
  const auto made_due = static_cast<std::uint64_t>((now_ns - origin_ns_) / step_ns_);
  return made_due > accounted_ ? made_due - accounted_ : 0;
}

std::uint64_t RealTimeSteps::due(std::int64_t now_ns) noexcept {
  const std::uint64_t owed_now = owed(now_ns);
  const std::uint64_t steps = std::min(owed_now, max_catch_up_);
  dropped_ += owed_now - steps;
  catch_ups_ += steps > 1 ? 1 : 0;
  run_ += steps;
  accounted_ += owed_now;
  return steps;
}

void RealTimeSteps::pause(std::int64_t now_ns) noexcept {
  const std::uint64_t owed_now = owed(now_ns);
  paused_ += owed_now;
  accounted_ += owed_now;
}

std::int64_t RealTimeSteps::next_due_ns() const noexcept {
  return origin_ns_ + static_cast<std::int64_t>(accounted_ + 1) * step_ns_;
}

}  // namespace hapticctrl::mujoco
