#pragma once
/// @file arm_simulator.hpp
/// Rigid-body simulation of the arm: M(q) qdd + C(q, qd) qd + G(q) = tau_motor + J^T w_operator
/// + tau_friction + tau_stops, integrated with semi-implicit Euler in sub-steps. Deterministic,
/// fixed-size Eigen only; takes dt, never reads a clock.
///
/// SimulatedArm wraps it behind the ArmIo seam: motor torque saturation, brakes while the supply
/// is off (the arm is held), the operator wrench and hand read from the `force` region
/// (validated), and
/// measures quantised to the encoder resolution with a filtered finite-difference velocity.

#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::rt_core {

struct SimulatorOptions {
  /// Longest integration sub-step (s): a 1 ms period runs 8 sub-steps. Chosen so that energy
  /// drifts 0.28 % in 10 s of free swinging with elastic stops (4 sub-steps: 1.3 %), measured
  /// 2026-11-22 (tests/rt_core/arm_simulator_test.cpp).
  double max_substep = 125e-6;
  bool friction = true;            ///< viscous + Coulomb (smoothed over coulomb_velocity)
  double coulomb_velocity = 0.01;  ///< rad/s, tanh smoothing of Coulomb friction
  double stop_stiffness = 300.0;   ///< N·m/rad, joint-limit stops
  double stop_damping = 3.0;       ///< N·m·s/rad
  /// The operator's wrench on the handle (region wrench + hand) is saturated and rate-limited
  /// to these, per sub-step, whatever the `force` region says: the limits its writers promise
  /// (shm::ForceLimits), enforced again by the core (a wrench written straight into the region
  /// went 0 -> 173 N in one cycle, 2026-12-02). Real hands stay far below the rates.
  shm::ForceLimits operator_limits{};
};

/// The operator's hand on the handle: a spring-damper pulling the handle point towards a moving
/// anchor, and a wrist turning the handle towards a fixed rotation (shm::HandGrip in the `force`
/// region). All gains 0: no hand.
struct HandModel {
  Vector3d anchor = Vector3d::Zero();
  Vector3d anchor_velocity = Vector3d::Zero();
  double stiffness = 0.0;  ///< N/m
  double damping = 0.0;    ///< N.s/m
  Matrix3d anchor_rotation = Matrix3d::Identity();
  double angular_stiffness = 0.0;  ///< N.m/rad
  double angular_damping = 0.0;    ///< N.m.s/rad

  [[nodiscard]] HAPTICCTRL_RT bool holds_rotation() const noexcept {
    return angular_stiffness > 0.0 || angular_damping > 0.0;
  }
  [[nodiscard]] HAPTICCTRL_RT bool gripping() const noexcept {
    return stiffness > 0.0 || damping > 0.0 || holds_rotation();
  }
  /// Force the hand's spring-damper puts on a handle point at `position` moving at `velocity`,
  /// `elapsed` seconds after the anchor was given (it moves on at anchor_velocity); the
  /// simulator bounds it with the rest of the operator's wrench (operator_limits). Real-time
  /// contract: noexcept, no allocation.
  [[nodiscard]] HAPTICCTRL_RT Vector3d force(const Vector3d& position, const Vector3d& velocity,
                                             double elapsed) const noexcept;
  /// Torque the wrist puts on a handle turned to `rotation` (base frame) turning at
  /// `angular_velocity`. Real-time contract: noexcept, no allocation.
  [[nodiscard]] HAPTICCTRL_RT Vector3d torque(const Matrix3d& rotation,
                                              const Vector3d& angular_velocity) const noexcept;
};

/// The pure simulator. Real-time contract of every method: noexcept, no allocation.
class ArmSimulator {
 public:
  ArmSimulator(const ArmDynamics& dynamics, const SimulatorOptions& options,
               const Vector6d& start) noexcept;

  /// Advances by `dt` seconds. `motor_torque` is applied as given (saturate before); the
  /// operator wrench plus the force of `hand`, evaluated at every sub-step, act on the handle
  /// (base frame), within options' operator_limits. With `brakes` the arm does not move.
  HAPTICCTRL_RT void step(const Vector6d& motor_torque, const Vector6d& operator_wrench, double dt,
                          bool brakes, const HandModel& hand = {}) noexcept;
  /// The operator's wrench on the handle at the end of the last step (hand included, limited).
  [[nodiscard]] HAPTICCTRL_RT const Vector6d& operator_applied() const noexcept {
    return operator_applied_;
  }

  [[nodiscard]] HAPTICCTRL_RT const Vector6d& position() const noexcept { return q_; }
  [[nodiscard]] const Vector6d& velocity() const noexcept { return qd_; }
  [[nodiscard]] const ChainState& chain() const noexcept { return chain_; }
  /// Kinetic + gravitational + joint-stop elastic energy (J).
  [[nodiscard]] double energy() const noexcept;
  void set_state(const Vector6d& q, const Vector6d& qd) noexcept;

 private:
  [[nodiscard]] HAPTICCTRL_RT Vector6d passive_torques() const noexcept;
  /// Moves the applied operator wrench towards `target` over `h` within operator_limits.
  HAPTICCTRL_RT void limit_operator(const Vector6d& target, double h) noexcept;

  const ArmDynamics* dynamics_;
  SimulatorOptions options_;
  Vector6d q_;
  Vector6d qd_ = Vector6d::Zero();
  ChainState chain_;
  Vector6d operator_applied_ = Vector6d::Zero();
};

/// ArmIo over the simulator.
class SimulatedArm final : public ArmIo {
 public:
  SimulatedArm(const ArmDynamics& dynamics, const SimulatorOptions& options, const Vector6d& start,
               const shm::SeqlockCell<shm::ForcePayload>* force) noexcept;

  HAPTICCTRL_RT bool get_measures(ArmMeasures& out) noexcept override;
  HAPTICCTRL_RT void send_commands(const ArmCommands& commands, TimePoint now,
                                   Duration dt) noexcept override;
  HAPTICCTRL_RT void set_supply(bool on) noexcept override {
    supply_on_.store(on, std::memory_order_release);
  }

  [[nodiscard]] const ArmSimulator& simulator() const noexcept { return sim_; }
  [[nodiscard]] ArmSimulator& simulator() noexcept { return sim_; }
  /// The operator's wrench on the handle last cycle: the `force` region's wrench plus the hand's,
  /// as limited.
  [[nodiscard]] HAPTICCTRL_RT const Vector6d& operator_wrench() const noexcept {
    return sim_.operator_applied();
  }
  [[nodiscard]] std::uint64_t rejected_force_samples() const noexcept { return rejected_; }

 private:
  HAPTICCTRL_RT void read_operator_wrench() noexcept;
  [[nodiscard]] HAPTICCTRL_RT Vector6d quantised(const Vector6d& q) const noexcept;

  const ArmDynamics* dynamics_;
  ArmSimulator sim_;
  const shm::SeqlockCell<shm::ForcePayload>* force_;
  Vector6d operator_wrench_ = Vector6d::Zero();
  HandModel hand_;
  Vector6d applied_torque_ = Vector6d::Zero();
  Vector6d measured_position_;
  Vector6d measured_velocity_ = Vector6d::Zero();
  std::atomic<bool> supply_on_{false};  ///< also switched by the fail-safe, cycle or not
  std::uint64_t rejected_ = 0;
  std::uint64_t force_sequence_ = 0;  ///< the last operator force sample read
};

}  // namespace hapticctrl::rt_core
