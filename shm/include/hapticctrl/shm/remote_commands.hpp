#pragma once
/// @file remote_commands.hpp
/// Commands and an operator wrench that arrive from another host (LCM's HMI messages, DDS
/// topics), validated and applied to the core's `ctrl` and `force` regions by one rule, whatever
/// the transport:
///
/// - Commands: only the emergency stop is applied unless remote commands are enabled;
///   kNone (an unknown command) is counted and ignored.
/// - Force: needs remote commands enabled; every value finite and within the device's operator
///   limits (the core's own); the applied wrench moves towards the request at a bounded rate and
///   decays to zero when requests stop coming.
///
/// The transports decode; this class decides. Real-time contract: soft-RT (a bridge's receive
/// thread); every member is noexcept and allocation-free.
#include <atomic>
#include <cstdint>
#include <string>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::shm {

struct RemoteCommandSettings {
  bool allow_remote_commands = false;
  ForceLimits force_limits;  ///< magnitude and rate of the applied wrench
  Duration force_timeout = std::chrono::milliseconds(200);  ///< no request: decay to zero
};

struct RemoteCommandCounters {
  std::atomic<std::uint64_t> commands_applied{0};
  std::atomic<std::uint64_t> commands_refused{0};  ///< remote commands disabled
  std::atomic<std::uint64_t> commands_invalid{0};  ///< unknown command
  std::atomic<std::uint64_t> commands_queue_full{0};
  std::atomic<std::uint64_t> forces_accepted{0};
  std::atomic<std::uint64_t> forces_refused{0};  ///< remote commands disabled
  std::atomic<std::uint64_t> forces_invalid{0};  ///< non-finite or out of range
  std::atomic<std::uint64_t> force_timeouts{0};
  std::atomic<std::uint64_t> malformed{0};  ///< messages the transport could not decode
};

/// The counters as JSON members without braces ("\"commands_applied\":3,..."), for a bridge's
/// --json summary. Setup code: allocates.
[[nodiscard]] std::string counters_json(const RemoteCommandCounters& c);

class RemoteCommands {
 public:
  /// What a bridge taking remote input attaches with: a ctrl slot always (the emergency stop is
  /// always accepted), the `force` region only with remote commands allowed; otherwise the local
  /// HMI (hapticctrl-hmi) stays the force region's writer. Setup code: allocates.
  static AttachOptions attach_options(bool allow_remote_commands);

  /// `ctrl` or `force` may be null (that region is not this process's to write): a command is
  /// then counted as queue-full, a force is still validated but never published.
  RemoteCommands(const RemoteCommandSettings& settings, CtrlWriter* ctrl,
                 SeqlockCell<ForcePayload>* force) noexcept;

  /// One command; kNone stands for a command the transport did not recognise.
  void command(CtrlCode code, TimePoint now) noexcept;
  /// One requested operator wrench (base frame, N and N.m).
  void force(const Vector6& requested, TimePoint now) noexcept;
  /// A message the transport could not decode.
  void malformed() noexcept { counters_.malformed.fetch_add(1, std::memory_order_relaxed); }
  /// Moves the applied wrench towards the request (or zero once stale) and publishes it; call
  /// every few milliseconds.
  void tick(TimePoint now) noexcept;

  [[nodiscard]] const RemoteCommandCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const Vector6& applied() const noexcept { return slew_.applied(); }

 private:
  RemoteCommandSettings settings_;
  CtrlWriter* ctrl_;
  SeqlockCell<ForcePayload>* force_;
  ForceSlew slew_;
  TimePoint last_force_;
  TimePoint last_tick_;
  bool ticked_ = false;
  bool force_active_ = false;
  RemoteCommandCounters counters_;
};

}  // namespace hapticctrl::shm
