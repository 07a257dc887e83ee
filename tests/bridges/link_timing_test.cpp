// Tests of link_timing.hpp: how the bridge measures the client link (protocol 1.1,
// HCP_FEATURE_TIMING): each ANSWER's send time is logged by cycle.
#include "hapticctrl/udp_bridge/link_timing.hpp"

#include <gtest/gtest.h>

#include <memory>

namespace hapticctrl::udp_bridge {
namespace {

constexpr TimeNs kMs = 1'000'000;

protocol::AnswerEcho echo_of(std::uint64_t cycle, TimeNs hold) {
  return protocol::unpack_answer_echo(protocol::pack_answer_echo(cycle, hold, true));
}

TEST(AnswerLog, KeepsTheRecentCyclesSendTimes) {
  auto log = std::make_unique<AnswerLog>();
  for (std::uint64_t c = 1; c <= 10'000; ++c) {
    log->record(c, static_cast<TimeNs>(c) * kMs);
  }
  TimeNs sent = 0;
  ASSERT_TRUE(log->sent_time(9'000, sent));
  EXPECT_EQ(sent, 9'000 * kMs);
  EXPECT_FALSE(log->sent_time(10'000 - AnswerLog::kSize, sent)) << "overwritten";
  EXPECT_FALSE(log->sent_time(0, sent));
  EXPECT_EQ(log->newest(), 10'000U);
}

TEST(LinkEstimator, RoundTripIsArrivalLessAnswerTimeLessTheClientsHold) {
  auto log = std::make_unique<AnswerLog>();
  log->record(100, 50 * kMs);
  log->record(101, 51 * kMs);
  // The client got answer 100 after 3 ms, held it 0.4 ms, its frame took 3 ms back.
  const SampleTiming t = LinkEstimator::time_sample(echo_of(100, 400'000), *log, 56'400'000);
  ASSERT_TRUE(t.measured);
  EXPECT_EQ(t.echo_cycle, 100U);
  EXPECT_EQ(t.round_trip, 6 * kMs);
  EXPECT_EQ(t.sample_time, 56'400'000 - 3 * kMs) << "dated half a round trip before arrival";
}

TEST(LinkEstimator, UnknownOrImpossibleEchoesAreNotMeasured) {
  auto log = std::make_unique<AnswerLog>();
  log->record(100, 50 * kMs);
  EXPECT_FALSE(LinkEstimator::time_sample(echo_of(99, 0), *log, 60 * kMs).measured);
  EXPECT_FALSE(LinkEstimator::time_sample(protocol::AnswerEcho{}, *log, 60 * kMs).measured);
  EXPECT_FALSE(LinkEstimator::time_sample(echo_of(100, 0), *log, 40 * kMs).measured)
      << "an arrival before the answer left";
  const SampleTiming lying = LinkEstimator::time_sample(echo_of(100, 500 * kMs), *log, 60 * kMs);
  ASSERT_TRUE(lying.measured);
  EXPECT_EQ(lying.round_trip, 0) << "a hold longer than the round trip never makes it negative";
}

TEST(LinkEstimator, AveragesDelayAndJitterAndCountsLoss) {
  LinkEstimator e;
  for (int i = 0; i < 400; ++i) {
    SampleTiming s;
    s.measured = true;
    s.round_trip = (i % 2 == 0 ? 18 : 22) * kMs;  // one-way 9 or 11 ms
    e.add(s);
    e.add_arrival(i % 10 == 0 ? 1 : 0);  // one frame in 11 lost
  }
  EXPECT_NEAR(static_cast<double>(e.delay()), 10.0 * kMs, 1.0 * kMs);
  EXPECT_NEAR(static_cast<double>(e.jitter()), 2.0 * kMs, 0.2 * kMs);
  EXPECT_NEAR(e.loss_ppm(), 1e6 / 11.0, 0.02e6);
  e.reset();
  EXPECT_EQ(e.delay(), 0);
  EXPECT_EQ(e.loss_ppm(), 0U);
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
