#pragma once
/// @file deadline_monitor.hpp
/// Deadline monitor: a pure state machine fed with each cycle's times. No clock inside.
///
/// A cycle is a *miss* when the main SERVO did not commit that cycle's outputs by the check at
/// 3/4 of the period: it was still busy (overrun), its output came too late and was discarded,
/// the degraded SERVO ran the cycle instead, or the CLOCK skipped the slot after a late wake-up.
/// Exactly kFailSafeConsecutiveMisses consecutive misses trip the fail-safe; any good cycle
/// resets the run. Chronic intermittent misses are *reported* through a windowed miss rate and a
/// leaky bucket, and trip only when their thresholds are configured (> 0).

#include <array>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/clock.hpp"

namespace hapticctrl::rt_core {

/// The seed specification's number: this many consecutive misses trip the fail-safe.
inline constexpr std::uint32_t kFailSafeConsecutiveMisses = 5;

/// What CLOCK observed for one cycle.
struct CycleTimes {
  TimePoint scheduled;           ///< the slot's deadline
  TimePoint woke;                ///< CLOCK's actual wake-up
  TimePoint released;            ///< when CLOCK released the SERVO task
  TimePoint started = kNotYet;   ///< main SERVO start (kNotYet: it did not start this cycle)
  TimePoint finished = kNotYet;  ///< main SERVO commit of this cycle (kNotYet: none by the check)
  TimePoint checked;             ///< the 3/4-period check
  bool degraded = false;         ///< the degraded SERVO ran this cycle
};

/// Thresholds for the chronic-miss detectors (0 disables tripping; they are always reported).
struct ChronicMissConfig {
  std::uint32_t window_cycles = 1000;  ///< window of the miss rate (<= kMaxWindow)
  std::uint32_t trip_window_ppm = 0;   ///< trip when the window rate exceeds this (0: report)
  std::uint32_t bucket_cost = 100;     ///< leaky bucket: added per miss
  std::uint32_t bucket_leak = 1;       ///< leaky bucket: removed per cycle
  std::uint32_t trip_bucket = 0;       ///< trip when the score exceeds this (0: report)
};

/// The verdict for one cycle.
enum class MonitorVerdict : std::uint8_t {
  kGood,
  kMiss,
  kFailSafe,       ///< exactly kFailSafeConsecutiveMisses consecutive misses
  kChronicMisses,  ///< a configured chronic-miss threshold was exceeded
};

/// Real-time contract of every method: noexcept, no allocation, no syscall; safe in the cycle.
class DeadlineMonitor {
 public:
  static constexpr std::uint32_t kMaxWindow = 65536;

  explicit DeadlineMonitor(const ChronicMissConfig& config = {}) noexcept;

  /// Judges one executed cycle.
  HAPTICCTRL_RT MonitorVerdict on_cycle(const CycleTimes& times) noexcept;
  /// Judges `count` slots the CLOCK skipped after a late wake-up: each is a miss.
  MonitorVerdict on_skipped(std::uint32_t count) noexcept;

  [[nodiscard]] HAPTICCTRL_RT std::uint32_t consecutive_misses() const noexcept {
    return consecutive_;
  }
  [[nodiscard]] HAPTICCTRL_RT std::uint64_t total_misses() const noexcept { return total_misses_; }
  [[nodiscard]] std::uint64_t cycles() const noexcept { return cycles_; }
  /// Misses per million over the last window_cycles cycles (or fewer, at start).
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t window_miss_ppm() const noexcept;
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t leaky_bucket_score() const noexcept { return bucket_; }

 private:
  HAPTICCTRL_RT MonitorVerdict record(bool miss) noexcept;

  ChronicMissConfig config_;
  std::uint32_t consecutive_ = 0;
  std::uint64_t total_misses_ = 0;
  std::uint64_t cycles_ = 0;
  std::uint32_t bucket_ = 0;
  std::uint32_t window_misses_ = 0;
  std::array<std::uint64_t, kMaxWindow / 64> window_bits_{};
};

}  // namespace hapticctrl::rt_core
