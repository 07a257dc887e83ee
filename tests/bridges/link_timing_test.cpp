// Tests of link_timing.hpp: how the bridge measures the client link (protocol 1.1,
// HCP_FEATURE_TIMING): each ANSWER's send time is logged by cycle.
#include "hapticctrl/udp_bridge/link_timing.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace hapticctrl::udp_bridge {
namespace {

using namespace std::chrono_literals;

protocol::AnswerEcho echo_of(std::uint64_t cycle, Duration hold) {
  return protocol::unpack_answer_echo(protocol::pack_answer_echo(cycle, to_ns(hold), true));
}

TEST(AnswerLog, KeepsTheRecentCyclesSendTimes) {
  auto log = std::make_unique<AnswerLog>();
  for (std::uint64_t c = 1; c <= 10'000; ++c) {
    log->record(c, TimePoint{std::chrono::milliseconds(c)});
  }
  TimePoint sent;
  ASSERT_TRUE(log->sent_time(9'000, sent));
  EXPECT_EQ(sent, TimePoint{9s});
  EXPECT_FALSE(log->sent_time(10'000 - AnswerLog::kSize, sent)) << "overwritten";
  EXPECT_FALSE(log->sent_time(0, sent));
  EXPECT_EQ(log->newest(), 10'000U);
}

TEST(LinkEstimator, RoundTripIsArrivalLessAnswerTimeLessTheClientsHold) {
  auto log = std::make_unique<AnswerLog>();
  log->record(100, TimePoint{50ms});
  log->record(101, TimePoint{51ms});
  // The client got answer 100 after 3 ms, held it 0.4 ms, its frame took 3 ms back.
  const SampleTiming t = LinkEstimator::time_sample(echo_of(100, 400us), *log, TimePoint{56400us});
  ASSERT_TRUE(t.measured);
  EXPECT_EQ(t.echo_cycle, 100U);
  EXPECT_EQ(t.round_trip, 6ms);
  EXPECT_EQ(t.sample_time, TimePoint{56400us - 3ms}) << "dated half a round trip before arrival";
}

TEST(LinkEstimator, UnknownOrImpossibleEchoesAreNotMeasured) {
  auto log = std::make_unique<AnswerLog>();
  log->record(100, TimePoint{50ms});
  EXPECT_FALSE(LinkEstimator::time_sample(echo_of(99, 0ns), *log, TimePoint{60ms}).measured);
  EXPECT_FALSE(LinkEstimator::time_sample(protocol::AnswerEcho{}, *log, TimePoint{60ms}).measured);
  EXPECT_FALSE(LinkEstimator::time_sample(echo_of(100, 0ns), *log, TimePoint{40ms}).measured)
      << "an arrival before the answer left";
  const SampleTiming lying = LinkEstimator::time_sample(echo_of(100, 500ms), *log, TimePoint{60ms});
  ASSERT_TRUE(lying.measured);
  EXPECT_EQ(lying.round_trip, 0ns) << "a hold longer than the round trip never makes it negative";
}

TEST(LinkEstimator, AveragesDelayAndJitterAndCountsLoss) {
  LinkEstimator e;
  for (int i = 0; i < 400; ++i) {
    SampleTiming s;
    s.measured = true;
    s.round_trip = i % 2 == 0 ? 18ms : 22ms;  // one-way 9 or 11 ms
    e.add(s);
    e.add_arrival(i % 10 == 0 ? 1 : 0);  // one frame in 11 lost
  }
  EXPECT_NEAR(to_seconds(e.delay()), 10e-3, 1e-3);
  EXPECT_NEAR(to_seconds(e.jitter()), 2e-3, 0.2e-3);
  EXPECT_NEAR(e.loss_ppm(), 1e6 / 11.0, 0.02e6);
  e.reset();
  EXPECT_EQ(e.delay(), 0ns);
  EXPECT_EQ(e.loss_ppm(), 0U);
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
