// Implements commands.hpp: DDS commands and operator wrenches decoded for shm::RemoteCommands.
#include "hapticctrl/dds_bridge/commands.hpp"

#include <array>
#include <cstring>
#include <utility>

namespace hapticctrl::dds_bridge {

shm::CtrlCode command_of(const std_msgs_msg_dds__String_& message) noexcept {
  static constexpr std::array<std::pair<const char*, shm::CtrlCode>, 5> kCommands{{
      {"power_on", shm::CtrlCode::kPowerOn},
      {"power_off", shm::CtrlCode::kPowerOff},
      {"emergency_stop", shm::CtrlCode::kEmergencyStop},
      {"emergency_reset", shm::CtrlCode::kEmergencyReset},
      {"stop", shm::CtrlCode::kStop},
  }};
  if (message.data_ == nullptr) {
    return shm::CtrlCode::kNone;
  }
  for (const auto& [name, code] : kCommands) {
    if (std::strcmp(message.data_, name) == 0) {
      return code;
    }
  }
  return shm::CtrlCode::kNone;
}

shm::Vector6 wrench_of(const geometry_msgs_msg_dds__WrenchStamped_& message) noexcept {
  const auto& w = message.wrench_;
  return {w.force_.x_, w.force_.y_, w.force_.z_, w.torque_.x_, w.torque_.y_, w.torque_.z_};
}

}  // namespace hapticctrl::dds_bridge
