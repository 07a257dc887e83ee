// When the engine steps (real_time_steps.hpp): one step per time step of the wall clock it is
// given, a bounded catch-up after a stall with the rest dropped, pauses while the link is silent;
// every step of the wall clock is counted once, as run, dropped or paused.
#include "hapticctrl/mujoco/real_time_steps.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::mujoco {
namespace {

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
TimePoint at(Duration t) {
  return TimePoint{t};
}

TEST(RealTimeSteps, OneStepPerTimeStepOfTheClock) {
  RealTimeSteps s(1ms, 50ms);
  s.start(at(0ns));
  EXPECT_EQ(s.due(at(500us)), 0U);
  EXPECT_EQ(s.next_due(), at(1ms));
  std::uint64_t total = 0;
  for (Duration t = 1ms; t <= 1s; t += 1ms) {
    total += s.due(at(t));
  }
  EXPECT_EQ(total, 1000U);
  EXPECT_EQ(s.run(), 1000U);
  EXPECT_EQ(s.catch_ups(), 0U);
  EXPECT_EQ(s.dropped(), 0U);
}

TEST(RealTimeSteps, ALateWakeUpRunsTheMissedStepsAtOnce) {
  RealTimeSteps s(1ms, 50ms);
  s.start(at(0ns));
  EXPECT_EQ(s.due(at(7ms + 10ns)), 7U);
  EXPECT_EQ(s.catch_ups(), 1U);
  EXPECT_EQ(s.next_due(), at(8ms));
}

TEST(RealTimeSteps, AStallBeyondTheCatchUpBoundIsDroppedAndCounted) {
  RealTimeSteps s(1ms, 50ms);
  s.start(at(0ns));
  EXPECT_EQ(s.due(at(200ms)), 50U);
  EXPECT_EQ(s.dropped(), 150U);
  EXPECT_EQ(s.due(at(201ms)), 1U) << "the clock goes on from the stall, not behind it";
  EXPECT_EQ(s.run() + s.dropped() + s.paused(), 201U);
}

TEST(RealTimeSteps, ASilentLinkPausesTheWorld) {
  RealTimeSteps s(1ms, 50ms);
  s.start(at(0ns));
  (void)s.due(at(10ms));
  s.pause(at(100ms));
  EXPECT_EQ(s.paused(), 90U);
  EXPECT_EQ(s.due(at(101ms)), 1U);
  EXPECT_EQ(s.run() + s.dropped() + s.paused(), 101U);
}

TEST(RealTimeSteps, ARestartBeginsAtTheNewStartAndAClockGoingBackOwesNothing) {
  RealTimeSteps s(1ms, 50ms);
  s.start(at(1000ms));
  EXPECT_EQ(s.due(at(999ms)), 0U);
  EXPECT_EQ(s.due(at(1003ms)), 3U);
  s.start(at(5000ms));
  EXPECT_EQ(s.due(at(5002ms)), 2U);
  EXPECT_EQ(s.run(), 5U);
}

TEST(RealTimeSteps, DegenerateArgumentsStillStepOneAtATime) {
  RealTimeSteps s(0ns, 0ns);
  s.start(at(0ns));
  EXPECT_EQ(s.due(at(10ns)), 1U);
  EXPECT_EQ(s.dropped(), 9U);
}

}  // namespace
}  // namespace hapticctrl::mujoco
