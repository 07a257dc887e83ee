#pragma once
/// @file hmi_input.hpp
/// HMI traffic from LCM into the core's `ctrl` and `force` regions, validated.
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
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>

#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::lcm_bridge {

struct HmiSettings {
  bool allow_remote_commands = false;
  shm::ForceLimits force_limits;                ///< magnitude and rate of the applied wrench
  std::int64_t force_timeout_ns = 200'000'000;  ///< no message for that long: decay to zero
};

struct HmiCounters {
  std::atomic<std::uint64_t> commands_applied{0};
  std::atomic<std::uint64_t> commands_refused{0};  ///< remote commands disabled
  std::atomic<std::uint64_t> commands_invalid{0};  ///< unknown command code
  std::atomic<std::uint64_t> commands_queue_full{0};
  std::atomic<std::uint64_t> forces_accepted{0};
  std::atomic<std::uint64_t> forces_refused{0};  ///< remote commands disabled
  std::atomic<std::uint64_t> forces_invalid{0};  ///< non-finite or out of range
  std::atomic<std::uint64_t> force_timeouts{0};
  std::atomic<std::uint64_t> malformed{0};
};

class HmiInput {
 public:
  HmiInput(const HmiSettings& settings, shm::CtrlWriter* ctrl,
           shm::SeqlockCell<shm::ForcePayload>* force) noexcept;

  /// One encoded hmi_command_t.
  void on_command(const void* data, std::size_t size, std::int64_t now_ns) noexcept;
  /// One encoded hmi_force_t.
  void on_force(const void* data, std::size_t size, std::int64_t now_ns) noexcept;
  /// Moves the applied wrench towards the request (or zero once stale) and publishes it.
  void tick(std::int64_t now_ns) noexcept;

  [[nodiscard]] const HmiCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const shm::Vector6& applied() const noexcept { return slew_.applied(); }

 private:
  HmiSettings settings_;
  shm::CtrlWriter* ctrl_;
  shm::SeqlockCell<shm::ForcePayload>* force_;
  shm::ForceSlew slew_;
  std::int64_t last_force_ns_ = 0;
  std::int64_t last_tick_ns_ = 0;
  bool ticked_ = false;
  bool force_active_ = false;
  HmiCounters counters_;
};

}  // namespace hapticctrl::lcm_bridge
