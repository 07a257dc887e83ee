#pragma once
/// What the machine did to the cores of a test's attempt (J5): each ControllerStack adds its
/// core's telemetry when it ends, and retry_what_the_machine_disturbed (machine_retries.hpp)
/// reads it to tell the machine's faults from the software's.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <string>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::test {

/// What the machine did to the cores of one attempt, from their own telemetry.
struct MachineDisturbance {
  /// A wake-up this many periods after the previous one is a stall of the machine: as long as
  /// the five consecutive misses on which the core fails safe (its own work takes a few percent
  /// of a period).
  static constexpr std::int64_t kStallPeriods = 5;
  /// A client starved this long in all (its samples 5 ms old or more) disturbed the attempt.
  static constexpr std::int64_t kStarvedNs = 20'000'000;

  std::uint64_t stalls_ridden = 0;  ///< benchmark mode: miss rules that would have tripped
  std::int64_t longest_period_ns = 0;
  std::int64_t nominal_period_ns = 0;
  bool failed_safe_on_misses = false;
  /// Cycles the core ran on a client sample 5 ms old or more: on a link nobody impairs, the
  /// client (a process at normal priority: the demo is the physics engine) was starved. Beside
  /// `stress-ng` the demo's sphere once rolled over the fixed one while the core's own periods
  /// were fine (2026-12-03).
  std::uint64_t client_stale_cycles = 0;
  /// Set by a test whose link drops or delays on purpose (hapticctrl-netem): stale samples are
  /// then the test's, and it judges link hold-ups itself.
  bool link_impaired = false;

  /// Adds one core's telemetry (read when its stack ends).
  void add(const shm::TelemetryPayload& t) {
    stalls_ridden += t.would_fail_safe;
    // A wake-up too late for its slot skips it and is no measured period: it counts as a
    // period of its lateness plus one.
    const std::int64_t longest = std::max(
        t.measured_period.max_ns, t.wake_latency.max_ns + static_cast<std::int64_t>(t.period_ns));
    if (longest > longest_period_ns) {
      longest_period_ns = longest;
      nominal_period_ns = static_cast<std::int64_t>(t.period_ns);
    }
    failed_safe_on_misses =
        failed_safe_on_misses ||
        t.stop_reason == static_cast<std::uint32_t>(shm::StopReason::kConsecutiveMisses) ||
        t.stop_reason == static_cast<std::uint32_t>(shm::StopReason::kChronicMisses);
    client_stale_cycles += t.vpr_stale;
  }
  [[nodiscard]] bool any() const {
    return stalls_ridden > 0 || failed_safe_on_misses ||
           (!link_impaired &&
            static_cast<std::int64_t>(client_stale_cycles) * nominal_period_ns >= kStarvedNs) ||
           (nominal_period_ns > 0 && longest_period_ns >= kStallPeriods * nominal_period_ns);
  }
  [[nodiscard]] std::string text() const {
    char line[240];
    std::snprintf(line, sizeof line,
                  "a period of up to %.1f ms for %.1f ms, %llu stall(s) ridden through, %llu "
                  "cycle(s) on a stale client sample%s",
                  static_cast<double>(longest_period_ns) / 1e6,
                  static_cast<double>(nominal_period_ns) / 1e6,
                  static_cast<unsigned long long>(stalls_ridden),
                  static_cast<unsigned long long>(client_stale_cycles),
                  failed_safe_on_misses ? ", failed safe on missed deadlines" : "");
    return line;
  }
};

/// The disturbance noted by the stacks of the attempt running on this thread.
inline MachineDisturbance& attempt_disturbance() {
  thread_local MachineDisturbance disturbance;
  return disturbance;
}

}  // namespace hapticctrl::test
