// Tests of deadline_monitor.hpp: deadline monitor: a pure state machine fed with each cycle's
// times.
#include "hapticctrl/rt_core/deadline_monitor.hpp"

#include <gtest/gtest.h>

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

constexpr Duration kP = 1ms;

CycleTimes good(Duration since_start) {
  const TimePoint t{since_start};
  return {t, t, t + 1us, t + 2us, t + 50us, t + 3 * kP / 4, false};
}
CycleTimes late(Duration since_start) {
  const TimePoint t{since_start};
  return {t, t, t + 1us, t + 2us, kNotYet, t + 3 * kP / 4, false};
}
CycleTimes degraded(Duration since_start) {
  const TimePoint t{since_start};
  return {t, t, t + 1us, kNotYet, kNotYet, t + 3 * kP / 4, true};
}

TEST(DeadlineMonitor, FourMissesThenGoodIsNoFailSafe) {
  DeadlineMonitor m;
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(m.on_cycle(late(i * kP)), MonitorVerdict::kMiss);
  }
  EXPECT_EQ(m.on_cycle(good(4 * kP)), MonitorVerdict::kGood);
  EXPECT_EQ(m.consecutive_misses(), 0U);
  EXPECT_EQ(m.total_misses(), 4U);
}

TEST(DeadlineMonitor, ExactlyTheFifthConsecutiveMissTrips) {
  DeadlineMonitor m;
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(m.on_cycle(late(i * kP)), MonitorVerdict::kMiss);
  }
  EXPECT_EQ(m.on_cycle(late(4 * kP)), MonitorVerdict::kFailSafe);
}

TEST(DeadlineMonitor, CommitAfterTheCheckIsAMiss) {
  DeadlineMonitor m;
  CycleTimes t = good(0ns);
  t.finished = t.checked + 1ns;
  EXPECT_EQ(m.on_cycle(t), MonitorVerdict::kMiss);
}

TEST(DeadlineMonitor, DegradedCyclesCountAsMisses) {
  DeadlineMonitor m;
  for (int i = 0; i < 4; ++i) {
    ASSERT_EQ(m.on_cycle(degraded(i * kP)), MonitorVerdict::kMiss);
  }
  EXPECT_EQ(m.on_cycle(degraded(4 * kP)), MonitorVerdict::kFailSafe);
}

TEST(DeadlineMonitor, SkippedSlotsAreMissesAndCanTrip) {
  DeadlineMonitor m;
  EXPECT_EQ(m.on_skipped(3), MonitorVerdict::kMiss);
  EXPECT_EQ(m.consecutive_misses(), 3U);
  EXPECT_EQ(m.on_skipped(2), MonitorVerdict::kFailSafe);
}

TEST(DeadlineMonitor, OneInThreeIsReportedInWindowAndBucketWithoutTripping) {
  DeadlineMonitor m(ChronicMissConfig{.window_cycles = 300});
  for (int i = 0; i < 3000; ++i) {
    const MonitorVerdict v = m.on_cycle(i % 3 == 0 ? late(i * kP) : good(i * kP));
    ASSERT_NE(v, MonitorVerdict::kFailSafe);
    ASSERT_NE(v, MonitorVerdict::kChronicMisses);
  }
  EXPECT_EQ(m.window_miss_ppm(), 333'333U);
  EXPECT_GT(m.leaky_bucket_score(), 0U);
}

TEST(DeadlineMonitor, LeakyBucketTripsWhenConfigured) {
  DeadlineMonitor m(ChronicMissConfig{.bucket_cost = 100, .bucket_leak = 1, .trip_bucket = 500});
  MonitorVerdict v = MonitorVerdict::kGood;
  int cycles = 0;
  while (v != MonitorVerdict::kChronicMisses && cycles < 1000) {
    v = m.on_cycle(cycles % 3 == 0 ? late(cycles * kP) : good(cycles * kP));
    ++cycles;
  }
  EXPECT_EQ(v, MonitorVerdict::kChronicMisses);
  EXPECT_LT(cycles, 30);
}

TEST(DeadlineMonitor, WindowForgetsOldMisses) {
  DeadlineMonitor m(ChronicMissConfig{.window_cycles = 10});
  for (int i = 0; i < 5; ++i) {
    m.on_cycle(late(i * kP));
    m.on_cycle(good(i * kP));
  }
  EXPECT_EQ(m.window_miss_ppm(), 500'000U);
  for (int i = 0; i < 10; ++i) {
    m.on_cycle(good(i * kP));
  }
  EXPECT_EQ(m.window_miss_ppm(), 0U);
}

}  // namespace
}  // namespace hapticctrl::rt_core
