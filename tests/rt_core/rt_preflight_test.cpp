// Tests of rt_preflight.hpp: real-time preflight: what the machine and our privileges allow, tried
// once at start.
#include "hapticctrl/rt_core/rt_preflight.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(RtPreflight, ParsesPolicies) {
  EXPECT_EQ(parse_rt_policy("enforce"), RtPolicy::kEnforce);
  EXPECT_EQ(parse_rt_policy("warn"), RtPolicy::kWarn);
  EXPECT_EQ(parse_rt_policy("ignore"), RtPolicy::kIgnore);
  EXPECT_THROW(parse_rt_policy("always"), std::invalid_argument);
}

TEST(RtPreflight, ModeFollowsWhatWasGranted) {
  RtReport r;
  EXPECT_EQ(r.mode(), shm::RtMode::kNone);
  r.fifo_granted = true;
  EXPECT_EQ(r.mode(), shm::RtMode::kFifo);
  r.memory_locked = true;
  EXPECT_EQ(r.mode(), shm::RtMode::kFifoLocked);
  r.preempt_rt = true;
  EXPECT_EQ(r.mode(), shm::RtMode::kFifoLockedRt);
}

TEST(RtPreflight, ReportsThisMachineAndNeverThrowsUnderWarn) {
  const RtReport r = rt_preflight(RtPolicy::kWarn, 10);
  EXPECT_FALSE(r.kernel.empty());
  EXPECT_FALSE(r.virtualization.empty());
  EXPECT_NE(r.summary().find("real-time: kernel"), std::string::npos);
  // Whatever was granted, the report says so consistently.
  EXPECT_EQ(r.fifo_granted, r.summary().find("SCHED_FIFO granted") != std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::rt_core
