// Implements panel_keys.hpp: the operator panel's keyboard, apart from the screen so that it is
// unit-tested: a key and the panel's force state give an action and the new force state.
#include "hapticctrl/hmi/panel_keys.hpp"

#include <algorithm>

namespace hapticctrl::hmi {
namespace {

constexpr double kMinForceStep = 0.125;
constexpr double kMaxForceStep = 32.0;
constexpr double kMinTorqueStep = 0.00625;
constexpr double kMaxTorqueStep = 1.6;

KeyResult command(shm::CtrlCode code) noexcept {
  return KeyResult{PanelAction::kCommand, code};
}

KeyResult push(PanelForce& f, double sign, double max_force, double max_torque) noexcept {
  const double limit = f.axis < 3 ? max_force : max_torque;
  f.wrench[f.axis] = std::clamp(f.wrench[f.axis] + sign * f.step(), -limit, limit);
  return KeyResult{PanelAction::kForce, shm::CtrlCode::kNone};
}

void scale_steps(PanelForce& f, double factor) noexcept {
  f.force_step = std::clamp(f.force_step * factor, kMinForceStep, kMaxForceStep);
  f.torque_step = std::clamp(f.torque_step * factor, kMinTorqueStep, kMaxTorqueStep);
}

}  // namespace

const char* command_feedback(shm::CtrlCode code, std::uint32_t state_word) noexcept {
  const bool estop = (state_word & shm::state_bits::kEmergencyStop) != 0;
  const bool powered = (state_word & shm::state_bits::kPowered) != 0;
  switch (code) {
    case shm::CtrlCode::kPowerOn:
      if (estop) {
        return "power on refused: the emergency stop is latched (r resets it)";
      }
      if ((state_word & shm::state_bits::kAwaitingOperator) != 0) {
        return "power on requested (the operator's acknowledgement of the restart)";
      }
      return powered ? "already powered" : "power on requested";
    case shm::CtrlCode::kPowerOff:
      return powered ? "power off requested" : "already unpowered";
    case shm::CtrlCode::kEmergencyStop:
      return estop ? "the emergency stop is already latched" : "emergency stop latched";
    case shm::CtrlCode::kEmergencyReset:
      return estop ? "emergency stop reset requested (p powers on again)"
                   : "no emergency stop to reset";
    case shm::CtrlCode::kStop:
      return "controller stop requested";
    default:
      return "sent";
  }
}

KeyResult apply_key(int key, PanelForce& force, double max_force, double max_torque) noexcept {
  switch (key) {
    case 'p':
      return command(shm::CtrlCode::kPowerOn);
    case 'o':
      return command(shm::CtrlCode::kPowerOff);
    case ' ':
    case 'e':
      return command(shm::CtrlCode::kEmergencyStop);
    case 'r':
      return command(shm::CtrlCode::kEmergencyReset);
    case '+':
    case '=':
      return push(force, 1.0, max_force, max_torque);
    case '-':
    case '_':
      return push(force, -1.0, max_force, max_torque);
    case '[':
      scale_steps(force, 0.5);
      return {};
    case ']':
      scale_steps(force, 2.0);
      return {};
    case '0':
      force.wrench = {};
      return KeyResult{PanelAction::kForce, shm::CtrlCode::kNone};
    case 'S':
      return KeyResult{PanelAction::kAskStop, shm::CtrlCode::kNone};
    case 'q':
    case 'Q':
      return KeyResult{PanelAction::kQuit, shm::CtrlCode::kNone};
    default:
      break;
  }
  if (key >= '1' && key <= '6') {
    force.axis = static_cast<std::size_t>(key - '1');
  }
  return {};
}

}  // namespace hapticctrl::hmi
