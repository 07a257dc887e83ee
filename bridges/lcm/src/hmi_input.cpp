// Implements hmi_input.hpp: HMI traffic from LCM into the core's `ctrl` and `force` regions,
// validated.
#include "hapticctrl/lcm_bridge/hmi_input.hpp"

#include <lcm/lcm_coretypes.h>

#include <algorithm>
#include <cstdint>

#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

using Command = hapticctrl_lcm::hmi_command_t;

shm::CtrlCode ctrl_code_of(std::int32_t command) noexcept {
  switch (command) {
    case Command::POWER_ON:
      return shm::CtrlCode::kPowerOn;
    case Command::POWER_OFF:
      return shm::CtrlCode::kPowerOff;
    case Command::EMERGENCY_STOP:
      return shm::CtrlCode::kEmergencyStop;
    case Command::EMERGENCY_RESET:
      return shm::CtrlCode::kEmergencyReset;
    case Command::STOP:
      return shm::CtrlCode::kStop;
    default:
      return shm::CtrlCode::kNone;
  }
}

/// Whether the one string of an HMI message, its last field, declares exactly the bytes that are
/// left (NUL included). Debian's lcm-gen 1.3.1 decodes string lengths without checking that they
/// are positive: a length of INT32_MIN overflows and the decoder copies 2 GB from past the
/// message (found by fuzzing, 2026-12-01). So the length is checked before LCM decodes.
template <typename Message>
bool last_string_is_sound(const void* data, std::size_t size) noexcept {
  // Fingerprint and fixed fields, then the length: an empty string encodes as length 1 + NUL.
  static const auto length_at = static_cast<std::size_t>(Message{}.getEncodedSize()) - 5;
  if (size < length_at + 5) {
    return false;
  }
  std::int32_t length = 0;  // decoded as LCM encodes it (big-endian)
  __int32_t_decode_array(data, static_cast<int>(length_at), 4, &length, 1);
  return length > 0 && static_cast<std::size_t>(length) == size - length_at - 4 &&
         static_cast<const std::uint8_t*>(data)[size - 1] == 0;
}

}  // namespace

void HmiInput::on_command(const void* data, std::size_t size, TimePoint now) noexcept {
  Command m{};
  try {
    if (!last_string_is_sound<Command>(data, size) ||
        m.decode(data, 0, static_cast<int>(size)) < 0) {
      remote_.malformed();
      return;
    }
  } catch (...) {  // LCM's string decoding may throw bad_alloc on absurd lengths
    remote_.malformed();
    return;
  }
  remote_.command(ctrl_code_of(m.command), now);
}

void HmiInput::on_force(const void* data, std::size_t size, TimePoint now) noexcept {
  hapticctrl_lcm::hmi_force_t m{};
  try {
    if (!last_string_is_sound<hapticctrl_lcm::hmi_force_t>(data, size) ||
        m.decode(data, 0, static_cast<int>(size)) < 0) {
      remote_.malformed();
      return;
    }
  } catch (...) {
    remote_.malformed();
    return;
  }
  shm::Vector6 requested{};
  std::copy_n(m.wrench, 6, requested.begin());
  remote_.force(requested, now);
}

}  // namespace hapticctrl::lcm_bridge
