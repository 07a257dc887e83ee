#pragma once
/// @file latency_histogram.hpp
/// A fixed 1 µs-bin latency histogram with an overflow count: the binning of `cyclictest -h`,
/// so the core's figures and cyclictest's are directly comparable.

#include <array>
#include <cstdint>
#include <ostream>
#include <string>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

class LatencyHistogram {
 public:
  /// 10 ms of 1 µs bins; later samples are counted as overflows (and in max).
  static constexpr std::size_t kBins = 10'000;

  /// Adds one sample. Negative samples count as 0. Real-time contract: safe in the cycle.
  HAPTICCTRL_RT void add(Duration sample) noexcept;

  /// min/avg/max/p50/p99/p99.9 (percentiles at 1 µs resolution, upper bin edge).
  /// Real-time contract: bounded (one pass over kBins); call at telemetry rate, not per cycle.
  [[nodiscard]] HAPTICCTRL_RT shm::LatencySummary summary() const noexcept;

  /// Sums the 1 µs bins (and the overflows) into the coarse telemetry bins.
  /// Real-time contract: bounded (one pass over kBins); at telemetry rate.
  HAPTICCTRL_RT void coarse(std::array<std::uint64_t, shm::kLatencyBuckets>& out) const noexcept;

  /// The value under which `fraction` of the samples lie (upper edge of its bin).
  [[nodiscard]] HAPTICCTRL_RT Duration percentile(double fraction) const noexcept;

  [[nodiscard]] std::uint64_t samples() const noexcept { return samples_; }
  [[nodiscard]] std::uint64_t overflows() const noexcept { return overflows_; }
  [[nodiscard]] std::uint64_t bin(std::size_t us) const noexcept { return bins_[us]; }

  /// Writes the histogram in cyclictest's `-h` format (one column). Not for the cycle.
  void write_cyclictest_format(std::ostream& out) const;

 private:
  std::array<std::uint64_t, kBins> bins_{};
  std::uint64_t samples_ = 0;
  std::uint64_t overflows_ = 0;
  Duration min_{0};
  Duration max_{0};
  long double sum_ = 0;
};

}  // namespace hapticctrl::rt_core
