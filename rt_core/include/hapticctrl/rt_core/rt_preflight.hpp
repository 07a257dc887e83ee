#pragma once
/// @file rt_preflight.hpp
/// Real-time preflight: what the machine and our privileges allow, tried once at start.
/// Without privileges the core still runs (policy warn/ignore), says so once, and reports the
/// obtained mode in telemetry.

#include <string>
#include <vector>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

enum class RtPolicy : std::uint8_t {
  kEnforce,  ///< refuse to start without SCHED_FIFO and mlockall
  kWarn,     ///< try, say once what is missing, run anyway (default)
  kIgnore,   ///< try, say nothing
};

/// Parses "enforce" | "warn" | "ignore"; throws std::invalid_argument otherwise.
RtPolicy parse_rt_policy(const std::string& text);

struct RtReport {
  bool preempt_rt = false;     ///< kernel is PREEMPT_RT
  bool fifo_granted = false;   ///< SCHED_FIFO at the requested priority works here
  bool memory_locked = false;  ///< mlockall(MCL_CURRENT | MCL_FUTURE) succeeded
  long rtprio_limit = 0;       ///< RLIMIT_RTPRIO soft limit (-1: unlimited)
  long memlock_limit_kib = 0;  ///< RLIMIT_MEMLOCK soft limit (-1: unlimited)
  std::string kernel;          ///< uname -r and -v
  std::string virtualization;  ///< "none", "vm", "container", or "vm+container"
  std::vector<std::string> problems;

  [[nodiscard]] shm::RtMode mode() const noexcept;
  /// One paragraph for stderr.
  [[nodiscard]] std::string summary() const;
};

/// Probes the system and locks memory. The SCHED_FIFO probe runs on a short-lived thread, so
/// the caller's own scheduling is unchanged. Throws std::runtime_error under kEnforce when
/// something is missing. Not for the cycle.
RtReport rt_preflight(RtPolicy policy, int fifo_priority);

}  // namespace hapticctrl::rt_core
