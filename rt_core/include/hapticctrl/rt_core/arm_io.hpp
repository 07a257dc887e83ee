#pragma once
/// @file arm_io.hpp
/// The arm I/O seam: the only way the servo talks to an arm. The simulator implements it now; a
/// hardware backend implements the same three calls without touching the servo law.

#include <Eigen/Core>

#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/clock.hpp"

namespace hapticctrl::rt_core {

using Vector6d = Eigen::Matrix<double, 6, 1>;

/// One sample of the arm's sensors (SI units, joint space).
struct ArmMeasures {
  Vector6d position = Vector6d::Zero();  ///< rad
  Vector6d velocity = Vector6d::Zero();  ///< rad/s
  Vector6d torque = Vector6d::Zero();    ///< torque actually applied by the motors, N·m
  bool supply_on = false;                ///< motor power supply state
  /// Wrench the operator applies at the handle (base frame), when the arm senses it (the
  /// simulator does; hardware without a force sensor reports zero).
  Vector6d operator_wrench = Vector6d::Zero();
  /// Operator wrench samples refused so far (non-finite or beyond the limits); 0 without one.
  std::uint64_t operator_wrench_rejected = 0;
};

/// What the servo asks of the motors for the next period.
struct ArmCommands {
  Vector6d torque = Vector6d::Zero();  ///< N·m, before the arm's own saturation
  bool enable = false;                 ///< false: motors inhibited (zero torque), brakes engaged
};

/// Real-time contract of every method: noexcept, no allocation, no blocking; safe in the cycle.
/// get_measures and send_commands are serialised by the servo (one cycle owner at a time);
/// set_supply may come from another thread meanwhile (see there).
class ArmIo {
 public:
  virtual ~ArmIo() = default;
  /// Reads the sensors. Returns false on an I/O fault (the servo then latches a fault).
  HAPTICCTRL_RT virtual bool get_measures(ArmMeasures& out) noexcept = 0;
  /// Applies `commands` for the period `dt` that starts at `now`.
  HAPTICCTRL_RT virtual void send_commands(const ArmCommands& commands, TimePoint now,
                                           Duration dt) noexcept = 0;
  /// Switches the motor power supply (fail-safe and power requests). Safe to call while a cycle
  /// runs on another thread: the fail-safe cuts the supply even when it could not take the cycle
  /// from a SERVO that hangs in it, as a hardware supply relay is cut independently of the bus.
  /// Implementations make the switch atomic; the next send_commands sees it.
  HAPTICCTRL_RT virtual void set_supply(bool on) noexcept = 0;
};

}  // namespace hapticctrl::rt_core
