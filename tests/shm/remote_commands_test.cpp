// Tests of remote_commands.hpp: the one rule for commands and an operator wrench from another
// host, whatever the transport.
#include "hapticctrl/shm/remote_commands.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <vector>

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
TimePoint at(Duration t) {
  return TimePoint{t};
}

struct RemoteCommandsTest : ::testing::Test {
  std::unique_ptr<CtrlRegion> ctrl = std::make_unique<CtrlRegion>();
  std::unique_ptr<CtrlAckRegion> acks = std::make_unique<CtrlAckRegion>();
  CtrlWriter writer{ctrl->slots[0], acks->slots[0], 0};
  std::unique_ptr<SeqlockCell<ForcePayload>> force_cell =
      std::make_unique<SeqlockCell<ForcePayload>>();

  RemoteCommands make(bool allow) {
    RemoteCommandSettings s;
    s.allow_remote_commands = allow;
    return RemoteCommands(s, &writer, force_cell.get());
  }
  std::vector<CtrlCode> drain() {
    std::vector<CtrlCode> codes;
    CtrlReader(*ctrl, *acks).drain([&](const CtrlCommand& c) {
      codes.push_back(c.code);
      return true;
    });
    return codes;
  }
  Vector6 applied_force() const {
    ForcePayload f;
    (void)force_cell->read(f);
    return f.wrench;
  }
};

TEST_F(RemoteCommandsTest, WithoutRemoteCommandsOnlyTheEmergencyStopIsApplied) {
  RemoteCommands remote = make(false);
  for (const CtrlCode c : {CtrlCode::kPowerOn, CtrlCode::kPowerOff, CtrlCode::kEmergencyReset,
                           CtrlCode::kStop, CtrlCode::kEmergencyStop}) {
    remote.command(c, at(0ms));
  }
  remote.force({5, 0, 0, 0, 0, 0}, at(0ms));
  remote.tick(at(0ms));
  remote.tick(at(100ms));
  EXPECT_EQ(drain(), std::vector<CtrlCode>{CtrlCode::kEmergencyStop});
  EXPECT_EQ(remote.counters().commands_refused.load(), 4U);
  EXPECT_EQ(remote.counters().commands_applied.load(), 1U);
  EXPECT_EQ(remote.counters().forces_refused.load(), 1U);
  EXPECT_EQ(applied_force(), Vector6{});
}

TEST(RemoteCommandsAttach, TheForceRegionIsClaimedOnlyWithRemoteCommands) {
  const AttachOptions local = RemoteCommands::attach_options(false);
  EXPECT_TRUE(local.ctrl_writer);
  EXPECT_TRUE(local.write.empty());
  const AttachOptions remote = RemoteCommands::attach_options(true);
  EXPECT_TRUE(remote.ctrl_writer);
  EXPECT_EQ(remote.write, std::vector<RegionId>{RegionId::kForce});
}

TEST_F(RemoteCommandsTest, UnknownCommandsAndMissingRegionsAreCounted) {
  RemoteCommands remote = make(true);
  remote.command(CtrlCode::kNone, at(0ms));
  remote.malformed();
  EXPECT_EQ(remote.counters().commands_invalid.load(), 1U);
  EXPECT_EQ(remote.counters().malformed.load(), 1U);
  RemoteCommands without_regions(RemoteCommandSettings{true}, nullptr, nullptr);
  without_regions.command(CtrlCode::kEmergencyStop, at(0ms));
  without_regions.force({1, 0, 0, 0, 0, 0}, at(0ms));
  without_regions.tick(at(10ms));  // nowhere to publish: nothing breaks
  EXPECT_EQ(without_regions.counters().commands_queue_full.load(), 1U);
  EXPECT_TRUE(drain().empty());
}

TEST_F(RemoteCommandsTest, TheCountersReadAsJsonMembers) {
  RemoteCommands remote = make(false);
  remote.command(CtrlCode::kPowerOn, at(0ms));
  remote.command(CtrlCode::kEmergencyStop, at(0ms));
  remote.malformed();
  EXPECT_EQ(counters_json(remote.counters()),
            "\"commands_applied\":1,\"commands_refused\":1,\"commands_invalid\":0,"
            "\"commands_queue_full\":0,\"forces_accepted\":0,\"forces_refused\":0,"
            "\"forces_invalid\":0,\"force_timeouts\":0,\"malformed\":1");
}

TEST_F(RemoteCommandsTest, OutOfRangeOrNonFiniteForcesAreRefused) {
  RemoteCommands remote = make(true);
  for (const double bad :
       {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), 100.5}) {
    remote.force({bad, 0, 0, 0, 0, 0}, at(0ms));
  }
  remote.force({1, 0, 0, 0, 0, 10.5}, at(0ms));
  EXPECT_EQ(remote.counters().forces_invalid.load(), 4U);
  remote.tick(at(1ms));
  remote.tick(at(100ms));
  EXPECT_EQ(applied_force(), Vector6{});
}

TEST_F(RemoteCommandsTest, ForceIsRateLimitedAndDecaysWhenRequestsStop) {
  RemoteCommands remote = make(true);
  const Vector6 f{20, 0, 0, 0, 0, 0};
  remote.tick(at(0ms));
  remote.force(f, at(0ms));
  remote.tick(at(10ms));  // 500 N/s: at most 5 N after 10 ms
  EXPECT_NEAR(applied_force()[0], 5.0, 1e-9);
  for (std::int64_t t = 20; t <= 100; t += 10) {
    remote.force(f, at(std::chrono::milliseconds(t)));
    remote.tick(at(std::chrono::milliseconds(t)));
  }
  EXPECT_NEAR(applied_force()[0], 20.0, 1e-9);
  remote.tick(at(301ms));  // silent for more than 200 ms: let go at the same rate
  EXPECT_EQ(remote.counters().force_timeouts.load(), 1U);
  EXPECT_GE(applied_force()[0], 0.0);
  remote.tick(at(400ms));
  EXPECT_EQ(applied_force()[0], 0.0);
}

}  // namespace
}  // namespace hapticctrl::shm
