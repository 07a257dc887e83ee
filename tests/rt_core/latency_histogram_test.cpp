// Tests of latency_histogram.hpp: a fixed 1 µs-bin latency histogram with an overflow count: the
// binning of `cyclictest -h`, so the core's figures and cyclictest's are directly comparable.
#include "hapticctrl/rt_core/latency_histogram.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <sstream>

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

TEST(LatencyHistogram, SummaryOfKnownSamples) {
  auto h = std::make_unique<LatencyHistogram>();
  for (int us = 1; us <= 1000; ++us) {
    h->add(us * 1us - 500ns);  // lands in bin us-1
  }
  const shm::LatencySummary s = h->summary();
  EXPECT_EQ(s.samples, 1000U);
  EXPECT_EQ(s.min_ns, 500);
  EXPECT_EQ(s.max_ns, 999'500);
  EXPECT_EQ(s.p50_ns, to_ns(500us));
  EXPECT_EQ(s.p99_ns, to_ns(990us));
  EXPECT_EQ(s.p999_ns, to_ns(999us));
  EXPECT_NEAR(static_cast<double>(s.avg_ns), 500'000.0, 1.0);
}

TEST(LatencyHistogram, OverflowsAreCountedAndKeepTheMax) {
  auto h = std::make_unique<LatencyHistogram>();
  h->add(5us);
  h->add(20ms);
  EXPECT_EQ(h->overflows(), 1U);
  EXPECT_EQ(h->summary().max_ns, to_ns(20ms));
  EXPECT_EQ(h->percentile(1.0), 20ms);
}

TEST(LatencyHistogram, NegativeSamplesCountAsZero) {
  auto h = std::make_unique<LatencyHistogram>();
  h->add(-100ns);
  EXPECT_EQ(h->bin(0), 1U);
  EXPECT_EQ(h->summary().min_ns, 0);
}

TEST(LatencyHistogram, EmptyHistogramSummarisesToZero) {
  auto h = std::make_unique<LatencyHistogram>();
  EXPECT_EQ(h->summary().samples, 0U);
  EXPECT_EQ(h->percentile(0.99), 0ns);
}

TEST(LatencyHistogram, WritesCyclictestFormat) {
  auto h = std::make_unique<LatencyHistogram>();
  h->add(0ns);
  h->add(2us + 10ns);
  h->add(2us + 20ns);
  std::ostringstream out;
  h->write_cyclictest_format(out);
  EXPECT_EQ(out.str(),
            "000000 000001\n000001 000000\n000002 000002\n# Total: 3\n# Min Latencies: 0\n"
            "# Avg Latencies: 1\n# Max Latencies: 2\n# Histogram Overflows: 0\n");
}

}  // namespace
}  // namespace hapticctrl::rt_core
