// Tests of clock.hpp: the clock seam: the executive reads time and sleeps only through this
// interface, so the whole cycle can run against a fake clock in unit tests (scenarios of seconds in
// microseconds).
#include "hapticctrl/rt_core/clock.hpp"

#include <gtest/gtest.h>

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

TEST(Clock, RealClockIsMonotonicAndSleepsToAbsoluteDeadlines) {
  RealClock clock;
  const TimePoint start = clock.now();
  clock.sleep_until(start + 2ms);
  EXPECT_GE(clock.now(), start + 2ms);
  const TimePoint before = clock.now();
  clock.sleep_until(before - 1s);  // in the past: returns at once
  EXPECT_GE(clock.now(), before);
}

TEST(Clock, FakeClockMovesOnlyWhenTold) {
  FakeClock clock(TimePoint{100ns});
  EXPECT_EQ(clock.now(), TimePoint{100ns});
  clock.sleep_until(TimePoint{50ns});
  EXPECT_EQ(clock.now(), TimePoint{100ns}) << "no travel back in time";
  clock.sleep_until(TimePoint{200ns});
  EXPECT_EQ(clock.now(), TimePoint{200ns});
  clock.advance(5ns);
  EXPECT_EQ(clock.now(), TimePoint{205ns});
}

TEST(Clock, FakeClockOversleepsOnDemand) {
  FakeClock clock(TimePoint{0ns});
  clock.oversleep_next(7ns);
  clock.sleep_until(TimePoint{10ns});
  EXPECT_EQ(clock.now(), TimePoint{17ns});
  clock.oversleep_at(TimePoint{30ns}, 3ns);
  clock.sleep_until(TimePoint{20ns});
  EXPECT_EQ(clock.now(), TimePoint{20ns});
  clock.sleep_until(TimePoint{30ns});
  EXPECT_EQ(clock.now(), TimePoint{33ns});
}

}  // namespace
}  // namespace hapticctrl::rt_core
