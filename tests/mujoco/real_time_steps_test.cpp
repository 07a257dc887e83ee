// When the engine steps (real_time_steps.hpp): one step per time step of the wall clock it is
// given, a bounded catch-up after a stall with the rest dropped, pauses while the link is silent;
// every step of the wall clock is counted once, as run, dropped or paused.
#include "hapticctrl/mujoco/real_time_steps.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::mujoco {
namespace {

constexpr std::int64_t kMs = 1'000'000;

TEST(RealTimeSteps, OneStepPerTimeStepOfTheClock) {
  RealTimeSteps s(kMs, 50 * kMs);
  s.start(0);
  EXPECT_EQ(s.due(kMs / 2), 0U);
  EXPECT_EQ(s.next_due_ns(), kMs);
  std::uint64_t total = 0;
  for (std::int64_t t = kMs; t <= 1000 * kMs; t += kMs) {
    total += s.due(t);
  }
  EXPECT_EQ(total, 1000U);
  EXPECT_EQ(s.run(), 1000U);
  EXPECT_EQ(s.catch_ups(), 0U);
  EXPECT_EQ(s.dropped(), 0U);
}

TEST(RealTimeSteps, ALateWakeUpRunsTheMissedStepsAtOnce) {
  RealTimeSteps s(kMs, 50 * kMs);
  s.start(0);
  EXPECT_EQ(s.due(7 * kMs + 10), 7U);
  EXPECT_EQ(s.catch_ups(), 1U);
  EXPECT_EQ(s.next_due_ns(), 8 * kMs);
}

TEST(RealTimeSteps, AStallBeyondTheCatchUpBoundIsDroppedAndCounted) {
  RealTimeSteps s(kMs, 50 * kMs);
  s.start(0);
  EXPECT_EQ(s.due(200 * kMs), 50U);
  EXPECT_EQ(s.dropped(), 150U);
  EXPECT_EQ(s.due(201 * kMs), 1U) << "the clock goes on from the stall, not behind it";
  EXPECT_EQ(s.run() + s.dropped() + s.paused(), 201U);
}

TEST(RealTimeSteps, ASilentLinkPausesTheWorld) {
  RealTimeSteps s(kMs, 50 * kMs);
  s.start(0);
  (void)s.due(10 * kMs);
  s.pause(100 * kMs);
  EXPECT_EQ(s.paused(), 90U);
  EXPECT_EQ(s.due(101 * kMs), 1U);
  EXPECT_EQ(s.run() + s.dropped() + s.paused(), 101U);
}

TEST(RealTimeSteps, ARestartBeginsAtTheNewStartAndAClockGoingBackOwesNothing) {
  RealTimeSteps s(kMs, 50 * kMs);
  s.start(1000 * kMs);
  EXPECT_EQ(s.due(999 * kMs), 0U);
  EXPECT_EQ(s.due(1003 * kMs), 3U);
  s.start(5000 * kMs);
  EXPECT_EQ(s.due(5002 * kMs), 2U);
  EXPECT_EQ(s.run(), 5U);
}

TEST(RealTimeSteps, DegenerateArgumentsStillStepOneAtATime) {
  RealTimeSteps s(0, 0);
  s.start(0);
  EXPECT_EQ(s.due(10), 1U);
  EXPECT_EQ(s.dropped(), 9U);
}

}  // namespace
}  // namespace hapticctrl::mujoco
