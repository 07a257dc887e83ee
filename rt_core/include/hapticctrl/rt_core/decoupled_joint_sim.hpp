#pragma once
/// @file decoupled_joint_sim.hpp
/// The F2 simulated arm: six independent joints (inertia, viscous friction, torque limits,
/// position limits, brakes), behind the ArmIo seam. It exercises the whole cycle (measures,
/// commands, power gating, operator force) until the full rigid-body model of F3 replaces it.
/// Until then the operator wrench maps component-wise onto the joints (fx -> J1, ..., tz -> J6).

#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::rt_core {

/// Parameters of the decoupled model (SI).
struct DecoupledJointParams {
  Vector6d inertia = (Vector6d() << 0.01, 0.01, 0.01, 0.001, 0.001, 0.001).finished();
  Vector6d viscous = (Vector6d() << 0.05, 0.05, 0.05, 0.005, 0.005, 0.005).finished();
  Vector6d torque_limit = (Vector6d() << 30, 30, 15, 3, 3, 3).finished();
  Vector6d position_min = (Vector6d() << -2.4, -1.6, 0.2, -2.6, -1.4, -2.6).finished();
  Vector6d position_max = (Vector6d() << 2.4, 0.6, 2.6, 2.6, 1.4, 2.6).finished();
  Vector6d start = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();  ///< ready pose
  double max_operator_force = 100.0;  ///< N; larger (or non-finite) samples are rejected
  double max_operator_torque = 10.0;  ///< N·m
};

class DecoupledJointSim final : public ArmIo {
 public:
  /// `force` is the shared-memory force region (operator wrench), read every period.
  DecoupledJointSim(const DecoupledJointParams& params,
                    const shm::SeqlockCell<shm::ForcePayload>* force) noexcept;

  bool get_measures(ArmMeasures& out) noexcept override;
  void send_commands(const ArmCommands& commands, TimeNs now, TimeNs dt) noexcept override;
  void set_supply(bool on) noexcept override { supply_on_ = on; }

  /// Operator wrench samples rejected (non-finite or out of range). Safe in the cycle.
  [[nodiscard]] std::uint64_t rejected_force_samples() const noexcept { return rejected_; }
  /// The operator wrench applied during the last period (after validation).
  [[nodiscard]] const Vector6d& operator_wrench() const noexcept { return operator_wrench_; }

 private:
  void read_operator_wrench() noexcept;

  DecoupledJointParams params_;
  const shm::SeqlockCell<shm::ForcePayload>* force_;
  Vector6d position_;
  Vector6d velocity_ = Vector6d::Zero();
  Vector6d applied_torque_ = Vector6d::Zero();
  Vector6d operator_wrench_ = Vector6d::Zero();
  bool supply_on_ = false;
  std::uint64_t rejected_ = 0;
};

}  // namespace hapticctrl::rt_core
