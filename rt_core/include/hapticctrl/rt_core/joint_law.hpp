#pragma once
/// @file joint_law.hpp
/// The joint-space commands (J6, protocol 1.4), VirtuoseAPI's COMMAND_TYPE_ARTICULAR and
/// COMMAND_TYPE_ARTICULAR_IMPEDANCE, as the servo law renders them on top of its gravity
/// compensation, joint damping and soft joint-limit walls:
/// - ARTICULAR: each joint is held by a spring-damper at a set point that follows the client's
///   target within the joint's range (inside the soft walls) and at most `setpoint_speed`; the
///   set point starts where the joint is, so a far target is a ramp, never a step.
/// - ARTICULAR_IMPEDANCE: the client's torque per joint, through a one-port passivity guard per
///   joint (Hannaford & Ryu's observer and controller at each joint's port).
/// Both are clamped per joint to its continuous torque, scaled by the link's fade and the
/// engagement ramp, and rate limited per joint. docs/control.md explains the gains.
///
/// Real-time contract: every function is noexcept, allocates nothing and reads no clock; safe in
/// the cycle.

#include <cstdint>

#include "hapticctrl/arm_model/arm_model.hpp"
#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/client_sample.hpp"

namespace hapticctrl::rt_core {

/// True for the two joint-space commands.
[[nodiscard]] HAPTICCTRL_RT constexpr bool is_joint_command(ClientCommand c) noexcept {
  return c == ClientCommand::kArticular || c == ClientCommand::kArticularImpedance;
}

/// What the joint law carries from cycle to cycle (part of the servo law's RenderMemory, so that
/// the degraded SERVO continues from it).
struct JointMemory {
  ClientCommand command = ClientCommand::kNone;  ///< the mode of the last cycle
  bool tracking = false;                         ///< ARTICULAR: `setpoint` is in force
  Vector6d setpoint = Vector6d::Zero();          ///< rad
  Vector6d torque = Vector6d::Zero();            ///< rendered last cycle (rate limited), N·m
  /// J per joint: the hand's net input at it (ARTICULAR_IMPEDANCE with the guard on).
  Vector6d observed_energy = Vector6d::Zero();
};

/// One cycle's inputs.
struct JointLawInputs {
  const ClientSample* client = nullptr;
  Vector6d q = Vector6d::Zero();        ///< measured joint positions, rad
  Vector6d qd = Vector6d::Zero();       ///< measured joint speeds, rad/s
  Vector6d inertia = Vector6d::Zero();  ///< the mass matrix's diagonal here, kg·m²
  /// Of the command the joints get: the handle's engagement, which has the link's fade and the
  /// speed brake in it (ServoLaw::update_engagement).
  double share = 0.0;
  double rate = 0.0;  ///< rate limit as a share of each joint's peak torque per second
  double dt = 0.0;    ///< s
};

/// What the joint law did this cycle.
struct JointLawResult {
  Vector6d torque = Vector6d::Zero();  ///< added to the joints, N·m
  bool saturated = false;              ///< a joint's command was clamped to its torque
  bool guarded = false;                ///< the passivity guard damped a joint
};

struct JointLawConfig {
  /// ARTICULAR: a joint this far from its set point gets its whole continuous torque (the
  /// spring's stiffness is torque_continuous / span), unless its inertia and the period bound it.
  double span = 0.1;                 ///< rad
  double setpoint_speed = 1.0;       ///< rad/s, the fastest a set point moves
  double wall_margin = 0.05;         ///< rad: set points stay this far inside each joint's range
  double stiffness_fraction = 0.25;  ///< k <= this * I_rotor / T² (the coupling gains' rule)
  double damping_ratio = 0.7;
  bool passivity_guard = true;  ///< ARTICULAR_IMPEDANCE's guard (LawConfig::passivity_guard)
  /// The guard's damping is at most a joint's continuous torque per this speed (and I / T): a
  /// client's torque still drives a joint the hand leaves free, at most this fast at its
  /// continuous torque, as the handle's guard is bounded by the device's damping.
  double guard_speed = 1.0;  ///< rad/s
};

class JointLaw {
 public:
  JointLaw(const arm_model::ArmModel& model, const JointLawConfig& config = {}) noexcept;

  /// The joint-space command of one cycle for a client in a joint-space mode.
  [[nodiscard]] HAPTICCTRL_RT JointLawResult torque(const JointLawInputs& in,
                                                    JointMemory& memory) const noexcept;
  /// No joint-space command this cycle: the next one starts from zero and from where the joints
  /// are.
  HAPTICCTRL_RT static void release(JointMemory& memory) noexcept;
  /// The largest share of a joint's peak torque in `torque` (the link's fade is timed by it).
  [[nodiscard]] HAPTICCTRL_RT double peak_share(const Vector6d& torque) const noexcept;
  /// ARTICULAR's stiffness (N·m/rad) and damping (N·m·s/rad) per joint for inertias `inertia`.
  HAPTICCTRL_RT void gains(const Vector6d& inertia, double dt, Vector6d& stiffness,
                           Vector6d& damping) const noexcept;

 private:
  [[nodiscard]] HAPTICCTRL_RT Vector6d articular(const JointLawInputs& in,
                                                 JointMemory& memory) const noexcept;
  [[nodiscard]] HAPTICCTRL_RT Vector6d guard(const JointLawInputs& in, const Vector6d& target,
                                             JointMemory& memory, bool& guarded) const noexcept;

  const arm_model::ArmModel* model_;
  JointLawConfig config_;
};

}  // namespace hapticctrl::rt_core
