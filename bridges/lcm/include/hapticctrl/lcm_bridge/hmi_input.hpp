#pragma once
/// @file hmi_input.hpp
/// HMI traffic from LCM into the core's `ctrl` and `force` regions: decoded here, validated and
/// applied by shm::RemoteCommands (the rule every remote transport shares).
///
/// - Commands (hmi_command_t): only the emergency stop is accepted unless remote commands are
///   enabled; unknown commands are counted and ignored.
/// - Force (hmi_force_t): needs remote commands enabled; every value finite and within the
///   device's operator limits (100 N, 10 N.m, the core's own); the applied wrench moves towards
///   the requested one at a bounded rate and decays to zero when messages stop.
/// - Malformed messages are counted and ignored.
///
/// Real-time contract: soft-RT (the LCM bridge's receive thread); no blocking, allocation only
/// in LCM's decoding of strings.
#include <cstddef>
#include <cstdint>

#include "hapticctrl/shm/remote_commands.hpp"

namespace hapticctrl::lcm_bridge {

using HmiSettings = shm::RemoteCommandSettings;

class HmiInput {
 public:
  HmiInput(const HmiSettings& settings, shm::CtrlWriter* ctrl,
           shm::SeqlockCell<shm::ForcePayload>* force) noexcept
      : remote_(settings, ctrl, force) {}

  /// One encoded hmi_command_t.
  void on_command(const void* data, std::size_t size, TimePoint now) noexcept;
  /// One encoded hmi_force_t.
  void on_force(const void* data, std::size_t size, TimePoint now) noexcept;
  /// Moves the applied wrench towards the request (or zero once stale) and publishes it.
  void tick(TimePoint now) noexcept { remote_.tick(now); }

  [[nodiscard]] const shm::RemoteCommandCounters& counters() const noexcept {
    return remote_.counters();
  }
  [[nodiscard]] const shm::Vector6& applied() const noexcept { return remote_.applied(); }

 private:
  shm::RemoteCommands remote_;
};

}  // namespace hapticctrl::lcm_bridge
