// The joint-space commands, ARTICULAR and ARTICULAR_IMPEDANCE (joint_law.hpp; docs/control.md).
#include "hapticctrl/rt_core/joint_law.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::rt_core {
namespace {

/// A joint slower than this has no motion for the guard to damp (rad/s).
constexpr double kStillSpeed = 1e-6;

}  // namespace

JointLaw::JointLaw(const ArmModel& model, const JointLawConfig& config) noexcept
    : model_(&model), config_(config) {}

void JointLaw::release(JointMemory& memory) noexcept {
  memory = JointMemory{};
}

double JointLaw::peak_share(const Vector6d& torque) const noexcept {
  double share = 0.0;
  for (int i = 0; i < kJoints; ++i) {
    share = std::max(share,
                     std::abs(torque(i)) / model_->joints[static_cast<std::size_t>(i)].torque_peak);
  }
  return share;
}

void JointLaw::gains(const Vector6d& inertia, double dt, Vector6d& stiffness,
                     Vector6d& damping) const noexcept {
  // The spring gives a joint its continuous torque at `span` from its set point, within
  // stiffness_fraction * I / T² (omega T = 0.5), as the coupling's gains (servo_law_gains.cpp):
  // at I / T² (omega T = 1) a 10 ms core left the wrist 0.1 rad off its set point, swinging
  // (2026-12-06); the damper is the damping ratio's on the joint's inertia here,
  // within I / T. The inertia floor is the rotor's: the mass matrix's diagonal is never below it.
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = model_->joints[static_cast<std::size_t>(i)];
    const double m = std::max(inertia(i), j.rotor_inertia);
    stiffness(i) = std::min(j.torque_continuous / config_.span,
                            config_.stiffness_fraction * j.rotor_inertia / (dt * dt));
    damping(i) = std::min(2.0 * config_.damping_ratio * std::sqrt(stiffness(i) * m), m / dt);
  }
}

Vector6d JointLaw::articular(const JointLawInputs& in, JointMemory& memory) const noexcept {
  const ClientSample& c = *in.client;
  if (!memory.tracking) {
    memory.setpoint = in.q;  // from where the joints are: a far target is a ramp
    memory.tracking = true;
  }
  const double step = config_.setpoint_speed * in.dt;
  Vector6d reference_speed;
  for (int i = 0; i < kJoints; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const JointModel& j = model_->joints[k];
    const double target =
        std::clamp(c.joint_target[k], j.q_min + config_.wall_margin, j.q_max - config_.wall_margin);
    const double move = std::clamp(target - memory.setpoint(i), -step, step);
    memory.setpoint(i) += move;
    // Caught up, the set point moves as the client says its target does; on the way, as it goes.
    reference_speed(i) =
        std::abs(target - memory.setpoint(i)) < 1e-12
            ? std::clamp(c.joint_speed[k], -config_.setpoint_speed, config_.setpoint_speed)
            : move / in.dt;
  }
  Vector6d stiffness;
  Vector6d damping;
  gains(in.inertia, in.dt, stiffness, damping);
  return stiffness.cwiseProduct(memory.setpoint - in.q) +
         damping.cwiseProduct(reference_speed - in.qd);
}

Vector6d JointLaw::guard(const JointLawInputs& in, const Vector6d& target, JointMemory& memory,
                         bool& guarded) const noexcept {
  // At each joint the hand has given the port -tau . qd dt in total (observed_energy, counted
  // after the rate limit in torque()). Rendering `target` now at the joint's speed would take
  // target . qd dt more: where that leaves the total negative (energy the client's torque
  // delivers beyond what it received: delay, loss, an active client), a damper takes the
  // difference back in this period (Ryu & Hannaford's controller on the current step; a damper
  // sized on the last step's deficit only lagged it: the rendered torque swung around half the
  // command), at most the one the joint's inertia takes stably in one period (I / T) and the
  // joint's continuous torque per guard_speed (unbounded, it held a joint the client drove to
  // its limit where it was).
  Vector6d out = target;
  for (int i = 0; i < kJoints; ++i) {
    const double v2 = in.qd(i) * in.qd(i);
    const double after = memory.observed_energy(i) - target(i) * in.qd(i) * in.dt;
    if (after < 0.0 && v2 > kStillSpeed * kStillSpeed) {
      const JointModel& j = model_->joints[static_cast<std::size_t>(i)];
      const double bound = std::min(std::max(in.inertia(i), j.rotor_inertia) / in.dt,
                                    j.torque_continuous / config_.guard_speed);
      out(i) -= std::min(-after / (in.dt * v2), bound) * in.qd(i);
      guarded = true;
    }
  }
  return out;
}

JointLawResult JointLaw::torque(const JointLawInputs& in, JointMemory& memory) const noexcept {
  const ClientSample& c = *in.client;
  JointLawResult result;
  if (c.command != memory.command) {
    release(memory);  // a new mode starts from zero and from where the joints are
    memory.command = c.command;
  }
  if (in.share <= 0.0 || !c.joint_command) {
    memory.tracking = false;  // a lost link: the set point starts again from where the joints are
  }
  Vector6d target = Vector6d::Zero();
  if (c.command == ClientCommand::kArticular && in.share > 0.0 && c.joint_command) {
    target = articular(in, memory);
  } else if (c.command == ClientCommand::kArticularImpedance && c.joint_command) {
    for (int i = 0; i < kJoints; ++i) {
      target(i) = c.joint_torque[static_cast<std::size_t>(i)] * c.force_factor;
    }
  }
  for (int i = 0; i < kJoints; ++i) {
    const double limit = model_->joints[static_cast<std::size_t>(i)].torque_continuous;
    result.saturated = result.saturated || std::abs(target(i)) > limit;
    target(i) = std::clamp(target(i), -limit, limit) * in.share;
  }
  const bool guarded = c.command == ClientCommand::kArticularImpedance && config_.passivity_guard;
  if (guarded) {
    target = guard(in, target, memory, result.guarded);
  }
  for (int i = 0; i < kJoints; ++i) {
    const double step = model_->joints[static_cast<std::size_t>(i)].torque_peak * in.rate * in.dt;
    memory.torque(i) += std::clamp(target(i) - memory.torque(i), -step, step);
  }
  if (guarded) {
    memory.observed_energy -= memory.torque.cwiseProduct(in.qd) * in.dt;  // what the port gave
  }
  result.torque = memory.torque;
  return result;
}

}  // namespace hapticctrl::rt_core
