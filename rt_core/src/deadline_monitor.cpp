// Implements deadline_monitor.hpp: deadline monitor: a pure state machine fed with each cycle's
// times.
#include "hapticctrl/rt_core/deadline_monitor.hpp"

#include <algorithm>

namespace hapticctrl::rt_core {

DeadlineMonitor::DeadlineMonitor(const ChronicMissConfig& config) noexcept : config_(config) {
  config_.window_cycles = std::clamp<std::uint32_t>(config_.window_cycles, 1, kMaxWindow);
}

MonitorVerdict DeadlineMonitor::on_cycle(const CycleTimes& times) noexcept {
  const bool committed_in_time =
      !times.degraded && times.finished != kNotYet && times.finished <= times.checked;
  return record(!committed_in_time);
}

MonitorVerdict DeadlineMonitor::on_skipped(std::uint32_t count) noexcept {
  MonitorVerdict verdict = MonitorVerdict::kMiss;
  for (std::uint32_t i = 0; i < count; ++i) {
    const MonitorVerdict v = record(true);
    if (v == MonitorVerdict::kFailSafe || v == MonitorVerdict::kChronicMisses) {
      verdict = v;
    }
  }
  return verdict;
}

std::uint32_t DeadlineMonitor::window_miss_ppm() const noexcept {
  const std::uint64_t span = std::min<std::uint64_t>(cycles_, config_.window_cycles);
  return span == 0 ? 0U : static_cast<std::uint32_t>(window_misses_ * 1'000'000ULL / span);
}

MonitorVerdict DeadlineMonitor::record(bool miss) noexcept {
  // Sliding window of miss bits: drop the bit leaving the window, add the new one.
  const std::uint64_t slot = cycles_ % config_.window_cycles;
  auto& word = window_bits_[slot / 64];
  const std::uint64_t mask = std::uint64_t{1} << (slot % 64);
  if ((word & mask) != 0) {
    --window_misses_;
  }
  word = miss ? (word | mask) : (word & ~mask);
  ++cycles_;

  bucket_ = bucket_ > config_.bucket_leak ? bucket_ - config_.bucket_leak : 0;
  if (!miss) {
    consecutive_ = 0;
    return MonitorVerdict::kGood;
  }
  ++window_misses_;
  ++total_misses_;
  ++consecutive_;
  bucket_ = std::min<std::uint32_t>(bucket_ + config_.bucket_cost, 1U << 30);
  if (consecutive_ == kFailSafeConsecutiveMisses) {
    return MonitorVerdict::kFailSafe;
  }
  const bool window_full = cycles_ >= config_.window_cycles;
  if ((config_.trip_window_ppm > 0 && window_full && window_miss_ppm() > config_.trip_window_ppm) ||
      (config_.trip_bucket > 0 && bucket_ > config_.trip_bucket)) {
    return MonitorVerdict::kChronicMisses;
  }
  return MonitorVerdict::kMiss;
}

}  // namespace hapticctrl::rt_core
