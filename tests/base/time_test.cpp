// Tests of time.hpp: the one time base (MonotonicClock, TimePoint, Duration) and its edges.
#include "hapticctrl/base/time.hpp"

#include <gtest/gtest.h>

#include <time.h>

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;

TEST(MonotonicClock, IsClockMonotonicAndNeverGoesBack) {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  const TimePoint before = time_point_from_ns(ts.tv_sec * 1'000'000'000LL + ts.tv_nsec);
  const TimePoint a = MonotonicClock::now();
  const TimePoint b = MonotonicClock::now();
  EXPECT_GE(a, before);
  EXPECT_GE(b, a);
  EXPECT_LT(a - before, 1s) << "the same clock, read a moment apart";
}

TEST(TimeEdges, NanosecondCountsRoundTripAndNotYetComesBeforeEveryMoment) {
  const TimePoint t = time_point_from_ns(1'234'567'890'123);
  EXPECT_EQ(to_ns(t), 1'234'567'890'123);
  EXPECT_EQ(to_ns(t - TimePoint{}), 1'234'567'890'123);
  EXPECT_DOUBLE_EQ(to_seconds(1500us), 1.5e-3);
  EXPECT_LT(kNotYet, TimePoint{});
  EXPECT_LT(kNotYet, MonotonicClock::now());
}

TEST(TimeEdges, SecondsBecomeTheNearestNanosecond) {
  EXPECT_EQ(from_seconds(33.3 / 1e3), 33'300'000ns) << "a cast would give 33299999 ns";
  EXPECT_EQ(from_seconds(1e-3), 1ms);
  EXPECT_EQ(from_seconds(0.0), 0ns);
  EXPECT_EQ(from_seconds(-2.5e-9), -2ns) << "a half: to the even nanosecond";
}

TEST(TimeEdges, AProgramsDurationEndsThatLongFromNowOrNever) {
  const TimePoint before = MonotonicClock::now();
  const TimePoint end = end_after(2.0);
  EXPECT_GE(end - before, 2s);
  EXPECT_LT(end - before, 3s);
  EXPECT_EQ(end_after(0.0), TimePoint::max()) << "0: run until told to stop";
  EXPECT_EQ(end_after(-1.0), TimePoint::max());
}

}  // namespace
}  // namespace hapticctrl
