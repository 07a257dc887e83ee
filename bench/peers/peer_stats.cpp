// Implements peer_stats.hpp: the figures of one case and their JSON.
#include "peers/peer_stats.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace hapticctrl::bench {
namespace {

/// The q-quantile (0..1) of `values` (nearest rank); 0 for none.
double quantile(std::vector<std::int64_t> values, double q) {
  if (values.empty()) {
    return 0.0;
  }
  const auto rank = static_cast<std::size_t>(std::ceil(q * static_cast<double>(values.size())) -
                                             (q > 0.0 ? 1.0 : 0.0));
  const std::size_t k = std::min(rank, values.size() - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return static_cast<double>(values[k]);
}

/// The median of `values`; 0 for none.
double median_of(std::vector<double> values) {
  if (values.empty()) {
    return 0.0;
  }
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

struct Latency {
  double p50 = 0;
  double p99 = 0;
  double p999 = 0;
  double max = 0;
  double delivered = 0;  ///< share of the messages the reader saw
};

Latency latency_of(const RunResult& r, std::uint32_t messages) {
  const auto us = [&](double q) { return quantile(r.latency_ns, q) * 1e-3; };
  return {us(0.5), us(0.99), us(0.999), us(1.0),
          static_cast<double>(r.latency_ns.size()) / std::max<std::uint32_t>(1, messages)};
}

void print_latency(std::FILE* out, const Latency& l) {
  std::fprintf(out, "{\"p50\":%.2f,\"p99\":%.2f,\"p999\":%.2f,\"max\":%.2f,\"delivered\":%.4f}",
               l.p50, l.p99, l.p999, l.max, l.delivered);
}

/// CPU microseconds per 1000 messages, writer and reader.
void print_cpu(std::FILE* out, const RunResult& r) {
  const double per = 1e9 / std::max<double>(1.0, static_cast<double>(r.publish_ns.size()));
  std::fprintf(out, "{\"writer\":%.1f,\"reader\":%.1f,\"messages\":%zu}", r.writer_cpu_s * per,
               r.reader_cpu_s * per, r.publish_ns.size());
}

void print_stall(std::FILE* out, const RunResult& r) {
  static constexpr std::array<const char*, kPhases> kNames{"running", "stopped", "resumed",
                                                           "killed"};
  std::fprintf(out, "{");
  for (std::size_t p = 0; p < kPhases; ++p) {
    std::vector<std::int64_t> costs;
    for (std::size_t i = 0; i < r.publish_ns.size(); ++i) {
      if (static_cast<std::size_t>(r.publish_phase[i]) == p) {
        costs.push_back(r.publish_ns[i]);
      }
    }
    std::fprintf(out,
                 "\"%s\":{\"publish_p50_us\":%.3f,\"publish_p99_us\":%.3f,"
                 "\"publish_max_us\":%.3f,\"publishes\":%zu},",
                 kNames[p], quantile(costs, 0.5) * 1e-3, quantile(costs, 0.99) * 1e-3,
                 quantile(costs, 1.0) * 1e-3, costs.size());
  }
  std::fprintf(out, "\"failed_publishes\":%llu}",
               static_cast<unsigned long long>(r.failed_publishes));
}

std::string first_error(const std::vector<RunResult>& latency, const RunResult& a,
                        const RunResult& b, const RunResult& c) {
  for (const RunResult& r : latency) {
    if (!r.error.empty()) {
      return r.error;
    }
  }
  for (const RunResult* r : {&a, &b, &c}) {
    if (!r->error.empty()) {
      return r->error;
    }
  }
  return {};
}

}  // namespace

void print_case_json(std::FILE* out, const std::string& transport, const char* mode,
                     std::uint32_t messages, const std::vector<RunResult>& latency,
                     const RunResult& cpu_1k, const RunResult& cpu_10k, const RunResult& stall) {
  std::vector<Latency> runs;
  std::vector<std::int64_t> pooled;
  std::vector<std::int64_t> reads;
  std::vector<std::int64_t> publishes;
  for (const RunResult& r : latency) {
    runs.push_back(latency_of(r, messages));
    pooled.insert(pooled.end(), r.latency_ns.begin(), r.latency_ns.end());
    reads.insert(reads.end(), r.read_ns.begin(), r.read_ns.end());
    publishes.insert(publishes.end(), r.publish_ns.begin(), r.publish_ns.end());
  }
  const auto median = [&](double Latency::*field) {
    std::vector<double> v;
    v.reserve(runs.size());
    for (const Latency& l : runs) {
      v.push_back(l.*field);
    }
    return median_of(v);
  };
  const Latency m{median(&Latency::p50), median(&Latency::p99), median(&Latency::p999),
                  median(&Latency::max), median(&Latency::delivered)};
  std::fprintf(out, "{\"transport\":\"%s\",\"mode\":\"%s\",\"latency_us\":", transport.c_str(),
               mode);
  print_latency(out, m);
  std::fprintf(out, ",\"latency_runs\":[");
  for (std::size_t i = 0; i < runs.size(); ++i) {
    std::fprintf(out, "%s", i == 0 ? "" : ",");
    print_latency(out, runs[i]);
  }
  // The distribution, for the plot: the pooled runs' latency at these quantiles.
  static constexpr std::array<double, 17> kCdf{0.001, 0.01, 0.05,  0.1,   0.2, 0.3,
                                               0.4,   0.5,  0.6,   0.7,   0.8, 0.9,
                                               0.95,  0.99, 0.995, 0.999, 1.0};
  std::fprintf(out, "],\"cdf_us\":[");
  for (std::size_t i = 0; i < kCdf.size(); ++i) {
    std::fprintf(out, "%s[%g,%.2f]", i == 0 ? "" : ",", kCdf[i], quantile(pooled, kCdf[i]) * 1e-3);
  }
  std::fprintf(out, "],\"read_ns\":{\"p50\":%.0f,\"p99\":%.0f},", quantile(reads, 0.5),
               quantile(reads, 0.99));
  std::fprintf(out, "\"publish_ns\":{\"p50\":%.0f,\"p99\":%.0f},", quantile(publishes, 0.5),
               quantile(publishes, 0.99));
  std::fprintf(out, "\"cpu_us_per_1000\":{\"1000\":");
  print_cpu(out, cpu_1k);
  std::fprintf(out, ",\"10000\":");
  print_cpu(out, cpu_10k);
  std::fprintf(out, "},\"stall\":");
  print_stall(out, stall);
  const std::string error = first_error(latency, cpu_1k, cpu_10k, stall);
  std::fprintf(out, ",\"error\":\"%s\"}", error.c_str());
}

}  // namespace hapticctrl::bench
