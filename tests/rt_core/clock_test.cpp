// Tests of clock.hpp: the clock seam: the executive reads time and sleeps only through this
// interface, so the whole cycle can run against a fake clock in unit tests (scenarios of seconds in
// microseconds).
#include "hapticctrl/rt_core/clock.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(Clock, RealClockIsMonotonicAndSleepsToAbsoluteDeadlines) {
  RealClock clock;
  const TimeNs start = clock.now();
  clock.sleep_until(start + 2 * kNsPerMs);
  EXPECT_GE(clock.now(), start + 2 * kNsPerMs);
  const TimeNs before = clock.now();
  clock.sleep_until(before - kNsPerS);  // in the past: returns at once
  EXPECT_GE(clock.now(), before);
}

TEST(Clock, FakeClockMovesOnlyWhenTold) {
  FakeClock clock(100);
  EXPECT_EQ(clock.now(), 100);
  clock.sleep_until(50);
  EXPECT_EQ(clock.now(), 100) << "no travel back in time";
  clock.sleep_until(200);
  EXPECT_EQ(clock.now(), 200);
  clock.advance(5);
  EXPECT_EQ(clock.now(), 205);
}

TEST(Clock, FakeClockOversleepsOnDemand) {
  FakeClock clock(0);
  clock.oversleep_next(7);
  clock.sleep_until(10);
  EXPECT_EQ(clock.now(), 17);
  clock.oversleep_at(30, 3);
  clock.sleep_until(20);
  EXPECT_EQ(clock.now(), 20);
  clock.sleep_until(30);
  EXPECT_EQ(clock.now(), 33);
}

}  // namespace
}  // namespace hapticctrl::rt_core
