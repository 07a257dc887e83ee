#pragma once
/// @file servo_law.hpp
/// The control law seam: inputs of one cycle in, motor commands and coupling wrench out.
/// Pure computation: no clock, no I/O, no allocation; `dt` and `now` come in the inputs.
///
/// F2 law (until F3's Cartesian control lands): joint damping when powered, nothing otherwise;
/// no coupling. The degraded SERVO runs the same code with `degraded = true`.

#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

/// Everything the law may use for one cycle.
struct ServoInputs {
  std::uint64_t cycle = 0;
  TimeNs now = 0;
  TimeNs dt = 0;
  ArmMeasures measures;
  LogicalState logical;
  shm::VprPayload client;     ///< last valid client sample
  bool client_valid = false;  ///< a valid client sample exists
  TimeNs client_age = 0;      ///< now - arrival of that sample
};

struct ServoOutputs {
  ArmCommands commands;
  Vector6d coupling_wrench = Vector6d::Zero();
};

class ServoLaw {
 public:
  /// Joint damping gains of the safe behaviour, N·m·s/rad.
  explicit ServoLaw(const Vector6d& damping = Vector6d::Constant(0.02)) noexcept
      : damping_(damping) {}

  /// Real-time contract: noexcept, no allocation; safe in the cycle.
  void compute(const ServoInputs& in, bool degraded, ServoOutputs& out) noexcept;

 private:
  Vector6d damping_;
};

}  // namespace hapticctrl::rt_core
