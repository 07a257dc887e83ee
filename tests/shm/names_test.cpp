// Tests of names.hpp: human-readable names of the codes carried in the regions (core state, stop
// reason, RT mode, events), shared by every process that reports them.
#include "hapticctrl/shm/names.hpp"

#include <gtest/gtest.h>

#include <string>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::shm {
namespace {

TEST(Names, EveryKnownCodeHasANameAndUnknownOnesSaySo) {
  for (std::uint32_t r = 0; r <= static_cast<std::uint32_t>(StopReason::kCoreLost); ++r) {
    EXPECT_EQ(std::string(stop_reason_name(r)).find("unknown"), std::string::npos) << r;
  }
  for (std::uint32_t s = 0; s <= static_cast<std::uint32_t>(CoreState::kStopped); ++s) {
    EXPECT_EQ(std::string(core_state_name(s)).find("unknown"), std::string::npos) << s;
  }
  for (std::uint32_t m = 0; m <= static_cast<std::uint32_t>(RtMode::kFifoLockedRt); ++m) {
    EXPECT_STRNE(rt_mode_name(m), "unknown") << m;
  }
  EXPECT_STREQ(stop_reason_name(1), "5 consecutive deadline misses");
  EXPECT_STREQ(stop_reason_name(99), "unknown reason");
  EXPECT_STREQ(core_state_name(1ULL << 40), "unknown state");
  EXPECT_STREQ(rt_mode_name(2), "SCHED_FIFO+mlockall");
}

TEST(Names, EventsDescribeThemselves) {
  Event e;
  e.kind = EventKind::kCoreState;
  e.code = static_cast<std::uint32_t>(CoreState::kFailSafe);
  e.value = static_cast<std::uint64_t>(StopReason::kConsecutiveMisses);
  EXPECT_EQ(describe_event(e), "fail-safe: 5 consecutive deadline misses");
  e.code = static_cast<std::uint32_t>(CoreState::kRunning);
  e.value = 0;
  EXPECT_EQ(describe_event(e), "running");
  e.kind = EventKind::kPower;
  e.code = 1;
  EXPECT_EQ(describe_event(e), "power on");
  e.kind = EventKind::kClientSession;
  e.value = 0;
  EXPECT_EQ(describe_event(e), "no client session");
  e.kind = EventKind::kClientStale;
  e.code = 1;
  EXPECT_EQ(describe_event(e), "client data stale (extrapolating, fading)");
  e.code = 0;
  e.value = 12;
  EXPECT_EQ(describe_event(e), "client data fresh (12 shorter lapses since the last)");
  e.kind = static_cast<EventKind>(77);
  EXPECT_EQ(describe_event(e), "unknown event");
}

}  // namespace
}  // namespace hapticctrl::shm
