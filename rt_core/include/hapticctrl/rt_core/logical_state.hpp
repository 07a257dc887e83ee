#pragma once
/// @file logical_state.hpp
/// The controller's logical state (power, emergency stop, stop request, fault injection) and
/// the interpretation of ctrl commands. docs/rt_core.md has the state diagram.
///
///   UNPOWERED --power-on--> POWERED --power-off--> UNPOWERED
///   any --e-stop--> ESTOP (unpowered, latched) --reset--> UNPOWERED (power-on needed again)
///   power-on while ESTOP or FAIL-SAFE is rejected; stop -> orderly stop sequence.
///   A core started after one that did not stop in order awaits an operator: a client's
///   power-on is rejected until an operator's power-on (shm::kPowerOnByClient).

#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

struct LogicalState {
  bool powered = false;                      ///< motor commands enabled
  bool estop = false;                        ///< latched until an explicit reset
  bool stop_requested = false;               ///< orderly stop asked through ctrl
  bool awaiting_operator = false;            ///< a client may not power on (after a restart)
  std::uint32_t pending_overrun_cycles = 0;  ///< fault injection queued for the main SERVO

  /// state_bits for VP/position (kFailSafe/kDegraded/... are added by the caller).
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t state_word() const noexcept {
    return (powered ? shm::state_bits::kPowered : 0U) |
           (estop ? shm::state_bits::kEmergencyStop : 0U) |
           (stop_requested ? shm::state_bits::kStopping : 0U) |
           (awaiting_operator ? shm::state_bits::kAwaitingOperator : 0U);
  }
};

/// Applies ctrl commands to the logical state, validating each.
class CommandInterpreter {
 public:
  /// `allow_fault_injection`: accept kInjectOverrun (off unless the core was started with it).
  explicit CommandInterpreter(bool allow_fault_injection) noexcept
      : allow_fault_injection_(allow_fault_injection) {}

  /// Returns false to reject (unknown code, power-on while stopped or, from a client, while
  /// awaiting an operator, disallowed injection).
  /// Real-time contract: safe in the cycle.
  HAPTICCTRL_RT bool apply(const shm::CtrlCommand& command, LogicalState& state) const noexcept;

 private:
  bool allow_fault_injection_;
};

}  // namespace hapticctrl::rt_core
