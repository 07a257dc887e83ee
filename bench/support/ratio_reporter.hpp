#pragma once
/// Google Benchmark reporter that also remembers each result, so a benchmark binary can print
/// ratios against a baseline measured in the same run (timing claims are always relative here).

#include <benchmark/benchmark.h>

#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace hapticctrl::bench {

class RatioReporter : public benchmark::ConsoleReporter {
 public:
  void ReportRuns(const std::vector<Run>& runs) override {
    for (const Run& run : runs) {
      if (run.iterations > 0 && run.run_type == Run::RT_Iteration) {
        ns_per_iteration_[run.benchmark_name()] = run.GetAdjustedRealTime() * to_ns(run.time_unit);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  /// Nanoseconds per iteration of a benchmark that ran, 0 otherwise.
  [[nodiscard]] double ns(const std::string& name) const {
    const auto it = ns_per_iteration_.find(name);
    return it == ns_per_iteration_.end() ? 0.0 : it->second;
  }

  /// Prints "numerator / denominator = ratio" for each pair whose results exist.
  void print_ratios(const std::vector<std::pair<std::string, std::string>>& pairs) const {
    std::printf("\n%-58s %-40s %10s\n", "measured", "same-run baseline", "ratio");
    for (const auto& [numerator, denominator] : pairs) {
      const auto n = ns_per_iteration_.find(numerator);
      const auto d = ns_per_iteration_.find(denominator);
      if (n == ns_per_iteration_.end() || d == ns_per_iteration_.end() || d->second <= 0) {
        continue;
      }
      std::printf("%-45s %10.0f ns  %-28s %10.0f ns  %8.2fx\n", numerator.c_str(), n->second,
                  denominator.c_str(), d->second, n->second / d->second);
    }
  }

 private:
  static double to_ns(benchmark::TimeUnit unit) {
    switch (unit) {
      case benchmark::kNanosecond:
        return 1.0;
      case benchmark::kMicrosecond:
        return 1e3;
      case benchmark::kMillisecond:
        return 1e6;
      case benchmark::kSecond:
        return 1e9;
    }
    return 1.0;
  }

  std::map<std::string, double> ns_per_iteration_;
};

/// The common main(): runs the selected benchmarks, prints the ratio table for `pairs`, then
/// calls `epilogue(reporter)` for anything else the binary reports.
template <typename Epilogue>
int run_with_ratios(int argc, char** argv,
                    const std::vector<std::pair<std::string, std::string>>& pairs,
                    Epilogue epilogue) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  RatioReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  reporter.print_ratios(pairs);
  epilogue(reporter);
  benchmark::Shutdown();
  return 0;
}

}  // namespace hapticctrl::bench
