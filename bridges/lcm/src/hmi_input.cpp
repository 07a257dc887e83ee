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

HmiInput::HmiInput(const HmiSettings& settings, shm::CtrlWriter* ctrl,
                   shm::SeqlockCell<shm::ForcePayload>* force) noexcept
    : settings_(settings), ctrl_(ctrl), force_(force), slew_(settings.force_limits) {}

void HmiInput::on_command(const void* data, std::size_t size, std::int64_t now_ns) noexcept {
  Command m{};
  try {
    if (!last_string_is_sound<Command>(data, size) ||
        m.decode(data, 0, static_cast<int>(size)) < 0) {
      counters_.malformed.fetch_add(1, std::memory_order_relaxed);
      return;
    }
  } catch (...) {  // LCM's string decoding may throw bad_alloc on absurd lengths
    counters_.malformed.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  const shm::CtrlCode code = ctrl_code_of(m.command);
  if (code == shm::CtrlCode::kNone) {
    counters_.commands_invalid.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (code != shm::CtrlCode::kEmergencyStop && !settings_.allow_remote_commands) {
    counters_.commands_refused.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (ctrl_ == nullptr || ctrl_->send(code, 0, now_ns) != shm::CtrlSendStatus::kQueued) {
    counters_.commands_queue_full.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  counters_.commands_applied.fetch_add(1, std::memory_order_relaxed);
}

void HmiInput::on_force(const void* data, std::size_t size, std::int64_t now_ns) noexcept {
  hapticctrl_lcm::hmi_force_t m{};
  try {
    if (!last_string_is_sound<hapticctrl_lcm::hmi_force_t>(data, size) ||
        m.decode(data, 0, static_cast<int>(size)) < 0) {
      counters_.malformed.fetch_add(1, std::memory_order_relaxed);
      return;
    }
  } catch (...) {
    counters_.malformed.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  if (!settings_.allow_remote_commands) {
    counters_.forces_refused.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  shm::Vector6 requested{};
  std::copy_n(m.wrench, 6, requested.begin());
  if (!slew_.set_target(requested)) {
    counters_.forces_invalid.fetch_add(1, std::memory_order_relaxed);
    return;
  }
  last_force_ns_ = now_ns;
  force_active_ = true;
  counters_.forces_accepted.fetch_add(1, std::memory_order_relaxed);
}

void HmiInput::tick(std::int64_t now_ns) noexcept {
  const double dt = ticked_ ? static_cast<double>(now_ns - last_tick_ns_) / 1e9 : 0.0;
  last_tick_ns_ = now_ns;
  ticked_ = true;
  if (force_active_ && now_ns - last_force_ns_ > settings_.force_timeout_ns) {
    slew_.set_target({});  // the HMI went quiet: let go, at the same bounded rate
    force_active_ = false;
    counters_.force_timeouts.fetch_add(1, std::memory_order_relaxed);
  }
  if (slew_.step(dt) && force_ != nullptr) {
    force_->publish_quietly(shm::ForcePayload{slew_.applied()}, now_ns);
  }
}

}  // namespace hapticctrl::lcm_bridge
