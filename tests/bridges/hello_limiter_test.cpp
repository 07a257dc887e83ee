#include "hapticctrl/udp_bridge/hello_limiter.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::udp_bridge {
namespace {

constexpr std::int64_t kMs = 1'000'000;

int admitted(HelloLimiter& limiter, std::uint32_t source, int attempts, std::int64_t at) {
  int n = 0;
  for (int i = 0; i < attempts; ++i) {
    n += limiter.admit(source, at) ? 1 : 0;
  }
  return n;
}

TEST(HelloLimiter, ABurstIsAdmittedThenTheSustainedRate) {
  HelloLimiter limiter({10.0, 5.0});
  EXPECT_EQ(admitted(limiter, 1, 100, 0), 5) << "the burst, at once";
  EXPECT_EQ(admitted(limiter, 1, 100, 500 * kMs), 5) << "0.5 s at 10/s refills 5";
  int over_a_second = 0;
  for (std::int64_t t = 501; t <= 1500; ++t) {  // one attempt per millisecond for a second
    over_a_second += limiter.admit(1, t * kMs) ? 1 : 0;
  }
  EXPECT_EQ(over_a_second, 10);
}

TEST(HelloLimiter, EachSourceHasItsOwnBudget) {
  HelloLimiter limiter({10.0, 3.0});
  EXPECT_EQ(admitted(limiter, 1, 50, 0), 3);
  EXPECT_EQ(admitted(limiter, 2, 50, 0), 3) << "a flood from 1 does not starve 2";
}

TEST(HelloLimiter, TheLeastRecentSourceMakesRoomAndStartsAgainWithAFullBurst) {
  HelloLimiter limiter({1.0, 2.0});
  EXPECT_EQ(admitted(limiter, 100, 5, 0), 2);
  for (std::uint32_t s = 1; s <= HelloLimiter::kSources; ++s) {  // evicts 100, the oldest
    limiter.admit(s, static_cast<std::int64_t>(s) * kMs);
  }
  EXPECT_EQ(admitted(limiter, 100, 5, 100 * kMs), 2);
}

TEST(HelloLimiter, ATimeGoingBackwardsRefillsNothing) {
  HelloLimiter limiter({10.0, 1.0});
  EXPECT_TRUE(limiter.admit(1, 1000 * kMs));
  EXPECT_FALSE(limiter.admit(1, 0));
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
