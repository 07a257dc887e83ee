// Implements force_slew.hpp: the operator wrench a writer of the `force` region applies, moved
// towards a requested wrench at a bounded rate: whatever a panel, a script or a remote HMI asks
// for, the simulated hand never jumps.
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

bool hand_acceptable(const HandGrip& hand, const ForceLimits& limits) noexcept {
  const auto norm = [](const std::array<double, 3>& v) {
    return std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
  };
  const double distance = norm(hand.anchor);
  const double speed = norm(hand.anchor_velocity);
  const auto& q = hand.anchor_rotation;
  const double unit = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  // A zeroed region (no wrist, no rotation) is a valid "no hand".
  const bool wrist = hand.angular_stiffness != 0.0 || hand.angular_damping != 0.0;
  // Written so that a NaN anywhere fails a comparison and refuses the grip.
  return hand.stiffness >= 0.0 && hand.stiffness <= limits.max_hand_stiffness &&
         hand.damping >= 0.0 && hand.damping <= limits.max_hand_damping &&
         distance <= limits.max_anchor_distance && speed <= limits.max_anchor_speed &&
         hand.angular_stiffness >= 0.0 && hand.angular_stiffness <= limits.max_wrist_stiffness &&
         hand.angular_damping >= 0.0 && hand.angular_damping <= limits.max_wrist_damping &&
         (std::abs(unit - 1.0) <= 1e-6 || (unit == 0.0 && !wrist));
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
