#pragma once
/// @file force_slew.hpp
/// The operator wrench a writer of the `force` region applies, moved towards a requested wrench
/// at a bounded rate: whatever a panel, a script or a remote HMI asks for, the simulated hand
/// never jumps. Both writers of `force` (hapticctrl-hmi, hapticctrl-lcm) use it.
#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::shm {

/// Bounds of the operator wrench. The magnitudes are the core's own acceptance limits.
struct ForceLimits {
  double max_force = 100.0;   ///< N per axis
  double max_torque = 10.0;   ///< N.m per axis
  double force_rate = 500.0;  ///< N/s: how fast the applied force may change
  double torque_rate = 50.0;  ///< N.m/s
  /// A simulated hand: stiffer than any grip (~1000 N/m) or than the sub-step keeps stable
  /// on the handle's ~0.3 kg, and no anchor beyond the arm's reach or faster than a hand moves.
  double max_hand_stiffness = 3000.0;  ///< N/m
  double max_hand_damping = 100.0;     ///< N.s/m
  double max_anchor_distance = 2.0;    ///< m from the base
  double max_anchor_speed = 5.0;       ///< m/s
  /// A simulated wrist: a firm one (a grip on a stylus is far softer); the handle's rotors
  /// (0.001 kg.m^2 each, ../shared/ARM_REFERENCE.md) keep both stable at the 125 us sub-step.
  double max_wrist_stiffness = 30.0;  ///< N.m/rad
  double max_wrist_damping = 1.0;     ///< N.m.s/rad
};

/// Whether every component of an operator wrench is finite and within `limits`' magnitudes:
/// the one acceptance test of the `force` region, applied by its writers and by the core.
/// Real-time contract: noexcept, allocation-free; safe in the cycle.
[[nodiscard]] HAPTICCTRL_RT bool wrench_acceptable(const Vector6& wrench,
                                                   const ForceLimits& limits = {}) noexcept;

/// Whether a hand grip is finite and within `limits` (stiffness, damping, anchor distance and
/// speed, the wrist's stiffness and damping, its rotation a unit quaternion within 1e-6, or all
/// zero without a wrist); the acceptance test of the hand in the `force` region, applied by its
/// writer and the core. Real-time contract: noexcept, allocation-free; safe in the cycle.
[[nodiscard]] HAPTICCTRL_RT bool hand_acceptable(const HandGrip& hand,
                                                 const ForceLimits& limits = {}) noexcept;

/// Rate-limited operator wrench. Real-time contract: every member is noexcept, allocation-free
/// and constant-time; safe anywhere.
class ForceSlew {
 public:
  explicit ForceSlew(const ForceLimits& limits = {}, const Vector6& start = {}) noexcept
      : limits_(limits), target_(start), applied_(start) {}

  /// Whether every component is finite and within the magnitude limits.
  [[nodiscard]] bool acceptable(const Vector6& wrench) const noexcept {
    return wrench_acceptable(wrench, limits_);
  }
  /// Sets the wrench to move towards. Refuses (false, target unchanged) what is not acceptable.
  bool set_target(const Vector6& wrench) noexcept;
  /// Advances the applied wrench by `dt` seconds (negative or non-finite: no move). Returns
  /// whether it changed.
  bool step(double dt) noexcept;

  [[nodiscard]] const Vector6& target() const noexcept { return target_; }
  [[nodiscard]] const Vector6& applied() const noexcept { return applied_; }
  [[nodiscard]] bool settled() const noexcept { return applied_ == target_; }
  /// Seconds the applied wrench still needs to reach the target.
  [[nodiscard]] double time_to_settle() const noexcept;
  [[nodiscard]] const ForceLimits& limits() const noexcept { return limits_; }

 private:
  [[nodiscard]] double rate_of(std::size_t axis) const noexcept {
    return axis < 3 ? limits_.force_rate : limits_.torque_rate;
  }

  ForceLimits limits_;
  Vector6 target_{};
  Vector6 applied_{};
};

}  // namespace hapticctrl::shm
