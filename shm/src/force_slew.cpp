#include "hapticctrl/shm/force_slew.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::shm {

bool wrench_acceptable(const Vector6& wrench, const ForceLimits& limits) noexcept {
  for (std::size_t i = 0; i < wrench.size(); ++i) {
    const double limit = i < 3 ? limits.max_force : limits.max_torque;
    if (!std::isfinite(wrench[i]) || std::abs(wrench[i]) > limit) {
      return false;
    }
  }
  return true;
}

bool ForceSlew::set_target(const Vector6& wrench) noexcept {
  if (!acceptable(wrench)) {
    return false;
  }
  target_ = wrench;
  return true;
}

bool ForceSlew::step(double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return false;
  }
  bool changed = false;
  for (std::size_t i = 0; i < applied_.size(); ++i) {
    const double max_step = rate_of(i) * dt;
    const double next = applied_[i] + std::clamp(target_[i] - applied_[i], -max_step, max_step);
    changed = changed || next != applied_[i];
    applied_[i] = next;
  }
  return changed;
}

double ForceSlew::time_to_settle() const noexcept {
  double longest = 0.0;
  for (std::size_t i = 0; i < applied_.size(); ++i) {
    longest = std::max(longest, std::abs(target_[i] - applied_[i]) / rate_of(i));
  }
  return longest;
}

}  // namespace hapticctrl::shm
