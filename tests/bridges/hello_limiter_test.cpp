// Tests of hello_limiter.hpp: rate limit of handshake attempts (HELLO) per source address.
#include "hapticctrl/udp_bridge/hello_limiter.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::udp_bridge {
namespace {

using namespace std::chrono_literals;
using std::chrono::milliseconds;

int admitted(HelloLimiter& limiter, std::uint32_t source, int attempts, Duration at) {
  int n = 0;
  for (int i = 0; i < attempts; ++i) {
    n += limiter.admit(source, TimePoint{at}) ? 1 : 0;
  }
  return n;
}

TEST(HelloLimiter, ANewSourceGetsOneHelloThenSavesUpToItsBurstAtTheSustainedRate) {
  HelloLimiter limiter({10.0, 5.0, 1000.0, 1000.0});  // per source 10/s, burst 5
  EXPECT_EQ(admitted(limiter, 1, 100, 0ms), 2) << "kFirstHellos at once, never a burst on arrival";
  EXPECT_EQ(admitted(limiter, 1, 100, 1s), 5) << "1 s at 10/s saves up the burst of 5";
  int over_a_second = 0;
  for (std::int64_t t = 1001; t <= 2000; ++t) {  // one attempt per millisecond for a second
    over_a_second += limiter.admit(1, TimePoint{milliseconds(t)}) ? 1 : 0;
  }
  EXPECT_EQ(over_a_second, 10);
}

TEST(HelloLimiter, EachSourceHasItsOwnBudget) {
  HelloLimiter limiter({10.0, 3.0, 1000.0, 1000.0});
  EXPECT_EQ(admitted(limiter, 1, 50, 0ms), 2);
  EXPECT_EQ(admitted(limiter, 2, 50, 0ms), 2) << "a flood from 1 does not starve 2";
  EXPECT_EQ(admitted(limiter, 1, 50, 300ms), 3);
}

TEST(HelloLimiter, AnEvictedSourceComesBackWithTheFirstHellosNotAFreshBurst) {
  HelloLimiter limiter({1.0, 10.0, 1000.0, 1000.0});
  EXPECT_EQ(admitted(limiter, 100, 20, 0ms), 2);
  for (std::uint32_t s = 1; s <= HelloLimiter::kSources; ++s) {  // evicts 100, the oldest
    limiter.admit(s, TimePoint{milliseconds(s)});
  }
  EXPECT_EQ(admitted(limiter, 100, 20, 100ms), 2);
}

TEST(HelloLimiter, ManySourcesShareOneTotalBudget) {
  // H3: 40 addresses cycling through the 16 slots were answered 19 088 HELLOs of 20 000.
  HelloLimiter limiter({20.0, 20.0, 100.0, 50.0});
  int answered = 0;
  for (int i = 0; i < 20'000; ++i) {  // 20 000 HELLOs over 1 s from 40 addresses
    answered += limiter.admit(static_cast<std::uint32_t>(i % 40), TimePoint{i * 50us}) ? 1 : 0;
  }
  EXPECT_LE(answered, 50 + 100 + 1) << "the total burst plus one second at the total rate";
  EXPECT_GE(answered, 100);
}

TEST(HelloLimiter, ATimeGoingBackwardsRefillsNothing) {
  HelloLimiter limiter({10.0, 1.0});
  EXPECT_TRUE(limiter.admit(1, TimePoint{1s}));
  EXPECT_FALSE(limiter.admit(1, TimePoint{}));
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
