// Tests of link_monitor.hpp: per-session network statistics from the answer stream (internal to the
// client library).
#include "link_monitor.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::client {
namespace {

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin (the origin itself: no echo).
TimePoint at(Duration t) {
  return TimePoint{t};
}

TEST(LinkMonitor, CountsLossFromSequenceGapsAndDropsLateAnswers) {
  LinkMonitor m;
  m.set_period(1ms);
  EXPECT_TRUE(m.on_answer(1, at(1ms), 0, at(0ms), 0));
  EXPECT_TRUE(m.on_answer(2, at(2ms), 0, at(0ms), 0));
  EXPECT_TRUE(m.on_answer(5, at(5ms), 0, at(0ms), 0));   // 3 and 4 lost
  EXPECT_FALSE(m.on_answer(4, at(5ms), 0, at(0ms), 0));  // arrives late: dropped
  const LinkStatistics s = m.statistics(7);
  EXPECT_EQ(s.answers_received, 3U);
  EXPECT_EQ(s.answers_lost, 2U);
  EXPECT_EQ(s.answers_late, 1U);
  EXPECT_EQ(s.control_sent, 7U);
  EXPECT_DOUBLE_EQ(s.interarrival_max_us, 3000.0);
}

TEST(LinkMonitor, RoundTripFromTheFirstEchoOfEachControlFrame) {
  LinkMonitor m;
  m.on_answer(1, at(10ms), 7, at(9ms), 1);  // control 7 sent at 9 ms: 1 ms round trip
  m.on_answer(2, at(11ms), 7, at(9ms), 1);  // the same echo again: not a new sample
  m.on_answer(3, at(12ms), 8, at(11500us), 2);
  const LinkStatistics s = m.statistics(0);
  EXPECT_EQ(s.rtt_samples, 2U);
  EXPECT_DOUBLE_EQ(s.rtt_last_us, 500.0);
  EXPECT_DOUBLE_EQ(s.rtt_mean_us, 750.0);
  EXPECT_DOUBLE_EQ(s.rtt_max_us, 1000.0);
  EXPECT_EQ(s.control_received_by_controller, 2U);
}

TEST(LinkMonitor, JitterFollowsRfc3550) {
  LinkMonitor m;
  m.set_period(1ms);
  m.on_answer(1, at(0ms), 0, at(0ms), 0);
  m.on_answer(2, at(2ms), 0, at(0ms), 0);  // 1 ms late: J = 1000/16
  EXPECT_DOUBLE_EQ(m.statistics(0).jitter_us, 62.5);
  m.on_answer(3, at(3ms), 0, at(0ms), 0);  // on time: J -= J/16
  EXPECT_DOUBLE_EQ(m.statistics(0).jitter_us, 62.5 - 62.5 / 16.0);
  EXPECT_DOUBLE_EQ(m.statistics(0).interarrival_mean_us, 1500.0);
}

TEST(LinkMonitor, SequenceWrapIsNotLoss) {
  LinkMonitor m;
  m.on_answer(0xFFFFFFFFU, at(0ms), 0, at(0ms), 0);
  EXPECT_TRUE(m.on_answer(0, at(1ms), 0, at(0ms), 0));
  EXPECT_EQ(m.statistics(0).answers_lost, 0U);
}

}  // namespace
}  // namespace hapticctrl::client
