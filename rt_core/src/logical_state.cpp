// Implements logical_state.hpp: the controller's logical state (power, emergency stop, stop
// request, fault injection) and the interpretation of ctrl commands.
#include "hapticctrl/rt_core/logical_state.hpp"

#include <algorithm>

namespace hapticctrl::rt_core {

namespace {
constexpr std::uint32_t kMaxInjectedOverrun = 1000;
}  // namespace

bool CommandInterpreter::apply(const shm::CtrlCommand& command,
                               LogicalState& state) const noexcept {
  switch (command.code) {
    case shm::CtrlCode::kPowerOn: {
      const bool by_client = command.arg == shm::kPowerOnByClient;
      if (state.estop || state.stop_requested || (by_client && state.awaiting_operator) ||
          (!by_client && command.arg != shm::kPowerOnByOperator)) {
        return false;
      }
      state.awaiting_operator = false;  // an operator's power-on is the acknowledgement
      state.powered = true;
      return true;
    }
    case shm::CtrlCode::kPowerOff:
      state.powered = false;
      return true;
    case shm::CtrlCode::kEmergencyStop:
      state.estop = true;
      state.powered = false;
      return true;
    case shm::CtrlCode::kEmergencyReset:
      state.estop = false;  // stays unpowered: power-on is a separate, explicit request
      return true;
    case shm::CtrlCode::kStop:
      state.stop_requested = true;
      return true;
    case shm::CtrlCode::kInjectOverrun:
      if (!allow_fault_injection_ || command.arg == 0 || command.arg > kMaxInjectedOverrun) {
        return false;
      }
      state.pending_overrun_cycles = command.arg;
      return true;
    case shm::CtrlCode::kNone:
      break;
  }
  return false;
}

}  // namespace hapticctrl::rt_core
