// Implements latency_histogram.hpp: a fixed 1 µs-bin latency histogram with an overflow count: the
// binning of `cyclictest -h`, so the core's figures and cyclictest's are directly comparable.
#include "hapticctrl/rt_core/latency_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace hapticctrl::rt_core {

void LatencyHistogram::add(Duration sample_or_negative) noexcept {
  const Duration sample = std::max(sample_or_negative, Duration{0});
  const auto us = static_cast<std::size_t>(sample / std::chrono::microseconds(1));
  if (us < kBins) {
    ++bins_[us];
  } else {
    ++overflows_;
  }
  if (samples_ == 0 || sample < min_) {
    min_ = sample;
  }
  max_ = std::max(max_, sample);
  sum_ += static_cast<long double>(sample.count());
  ++samples_;
}

Duration LatencyHistogram::percentile(double fraction) const noexcept {
  if (samples_ == 0) {
    return Duration{0};
  }
  const auto wanted =
      static_cast<std::uint64_t>(std::ceil(fraction * static_cast<double>(samples_)));
  std::uint64_t seen = 0;
  for (std::size_t us = 0; us < kBins; ++us) {
    seen += bins_[us];
    if (seen >= wanted && seen > 0) {
      return std::min<Duration>(std::chrono::microseconds(us + 1), max_);
    }
  }
  return max_;  // in the overflow
}

shm::LatencySummary LatencyHistogram::summary() const noexcept {
  shm::LatencySummary s;
  s.samples = samples_;
  s.overflows = overflows_;
  if (samples_ == 0) {
    return s;
  }
  s.min_ns = to_ns(min_);
  s.max_ns = to_ns(max_);
  s.avg_ns = static_cast<std::int64_t>(sum_ / static_cast<long double>(samples_));
  s.p50_ns = to_ns(percentile(0.50));
  s.p99_ns = to_ns(percentile(0.99));
  s.p999_ns = to_ns(percentile(0.999));
  return s;
}

void LatencyHistogram::write_cyclictest_format(std::ostream& out) const {
  std::size_t last = 0;
  for (std::size_t us = 0; us < kBins; ++us) {
    if (bins_[us] != 0) {
      last = us;
    }
  }
  char line[64];
  for (std::size_t us = 0; us <= last; ++us) {
    std::snprintf(line, sizeof(line), "%06zu %06llu\n", us,
                  static_cast<unsigned long long>(bins_[us]));
    out << line;
  }
  const shm::LatencySummary s = summary();
  out << "# Total: " << samples_ << "\n";
  const auto us = [](std::int64_t ns) {  // cyclictest's unit
    return std::chrono::duration_cast<std::chrono::microseconds>(Duration(ns)).count();
  };
  out << "# Min Latencies: " << us(s.min_ns) << "\n";
  out << "# Avg Latencies: " << us(s.avg_ns) << "\n";
  out << "# Max Latencies: " << us(s.max_ns) << "\n";
  out << "# Histogram Overflows: " << overflows_ << "\n";
}

void LatencyHistogram::coarse(std::array<std::uint64_t, shm::kLatencyBuckets>& out) const noexcept {
  out.fill(0);
  std::size_t bucket = 0;
  for (std::size_t us = 0; us < kBins; ++us) {
    // Bin `us` holds [us, us+1) µs: it belongs to the first bucket whose edge is above it.
    while (bucket < shm::kLatencyBucketEdgesUs.size() &&
           static_cast<std::int64_t>(us) >= shm::kLatencyBucketEdgesUs[bucket]) {
      ++bucket;
    }
    out[bucket] += bins_[us];
  }
  out[shm::kLatencyBuckets - 1] += overflows_;  // 10 ms and beyond: the last bucket exactly
}

}  // namespace hapticctrl::rt_core
