// Tests of hmi_input.hpp: HMI traffic from LCM into the core's `ctrl` and `force` regions,
// validated.
#include "hapticctrl/lcm_bridge/hmi_input.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "support/in_memory_controller.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

using namespace std::chrono_literals;
using Command = hapticctrl_lcm::hmi_command_t;

template <typename M>
std::vector<std::uint8_t> encoded(const M& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  m.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

std::vector<std::uint8_t> command(std::int32_t code) {
  Command m{};
  m.command = code;
  m.origin = "test";
  return encoded(m);
}

std::vector<std::uint8_t> force(double fx, double tz = 0.0) {
  hapticctrl_lcm::hmi_force_t m{};
  m.wrench[0] = fx;
  m.wrench[5] = tz;
  m.origin = "test";
  return encoded(m);
}

struct HmiTest : ::testing::Test {
  test::InMemoryController controller;
  std::unique_ptr<shm::SeqlockCell<shm::ForcePayload>> force_cell =
      std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();

  HmiInput make(bool remote) {
    HmiSettings s;
    s.allow_remote_commands = remote;
    return HmiInput(s, &controller.writer, force_cell.get());
  }
  shm::Vector6 applied_force() const {
    shm::ForcePayload f;
    force_cell->read(f);
    return f.wrench;
  }
};

TEST_F(HmiTest, WithoutRemoteCommandsOnlyTheEmergencyStopActs) {
  HmiInput hmi = make(false);
  for (const std::int32_t c : std::initializer_list<std::int32_t>{
           Command::POWER_ON, Command::POWER_OFF, Command::EMERGENCY_RESET, Command::STOP,
           Command::EMERGENCY_STOP}) {
    const auto b = command(c);
    hmi.on_command(b.data(), b.size(), TimePoint{});
  }
  EXPECT_EQ(controller.drain(), std::vector<shm::CtrlCode>{shm::CtrlCode::kEmergencyStop});
  EXPECT_EQ(hmi.counters().commands_refused.load(), 4U);
  EXPECT_EQ(hmi.counters().commands_applied.load(), 1U);
  const auto f = force(5.0);
  hmi.on_force(f.data(), f.size(), TimePoint{});
  EXPECT_EQ(hmi.counters().forces_refused.load(), 1U);
}

TEST_F(HmiTest, RemoteCommandsReachCtrlInOrder) {
  HmiInput hmi = make(true);
  for (const std::int32_t c : std::initializer_list<std::int32_t>{
           Command::POWER_ON, Command::EMERGENCY_STOP, Command::EMERGENCY_RESET, Command::POWER_OFF,
           Command::STOP}) {
    const auto b = command(c);
    hmi.on_command(b.data(), b.size(), TimePoint{});
  }
  EXPECT_EQ(controller.drain(),
            (std::vector<shm::CtrlCode>{shm::CtrlCode::kPowerOn, shm::CtrlCode::kEmergencyStop,
                                        shm::CtrlCode::kEmergencyReset, shm::CtrlCode::kPowerOff,
                                        shm::CtrlCode::kStop}));
}

TEST_F(HmiTest, MalformedAndUnknownMessagesAreCountedAndIgnored) {
  HmiInput hmi = make(true);
  const std::vector<std::uint8_t> junk{1, 2, 3, 4, 5, 6, 7, 8, 9};
  hmi.on_command(junk.data(), junk.size(), TimePoint{});
  hmi.on_force(junk.data(), junk.size(), TimePoint{});
  auto truncated = command(Command::POWER_ON);
  truncated.resize(truncated.size() - 2);
  hmi.on_command(truncated.data(), truncated.size(), TimePoint{});
  const auto unknown = command(42);
  hmi.on_command(unknown.data(), unknown.size(), TimePoint{});
  EXPECT_EQ(hmi.counters().malformed.load(), 3U);
  EXPECT_EQ(hmi.counters().commands_invalid.load(), 1U);
  EXPECT_TRUE(controller.drain().empty());
}

TEST_F(HmiTest, StringLengthsThatLcmWouldMisreadAreMalformed) {
  // The origin's length is the last 4-byte field before its bytes ("test" + NUL: 5).
  HmiInput hmi = make(true);
  auto bad = force(5.0);
  const std::size_t length_at = bad.size() - 5 - 4;
  for (const std::uint32_t length : {0x80000000U, 0xFFFFFFFFU, 0U, 4U, 6U}) {
    for (std::size_t i = 0; i < 4; ++i) {
      bad[length_at + i] = static_cast<std::uint8_t>(length >> (24 - 8 * i));
    }
    hmi.on_force(bad.data(), bad.size(), TimePoint{});
  }
  auto unterminated = command(Command::EMERGENCY_STOP);
  unterminated.back() = 'x';
  hmi.on_command(unterminated.data(), unterminated.size(), TimePoint{});
  EXPECT_EQ(hmi.counters().malformed.load(), 6U);
  EXPECT_TRUE(controller.drain().empty());
  EXPECT_EQ(applied_force(), shm::Vector6{});
}

TEST_F(HmiTest, AForceMessageReachesTheForceRegionThroughTheSharedRule) {
  // The rule itself (limits, rate, decay) is shm::RemoteCommands' and tested there.
  HmiInput hmi = make(true);
  const auto f = force(2.0);
  hmi.tick(TimePoint{});
  hmi.on_force(f.data(), f.size(), TimePoint{});
  hmi.tick(TimePoint{100ms});
  EXPECT_NEAR(applied_force()[0], 2.0, 1e-9);
  EXPECT_EQ(hmi.counters().forces_accepted.load(), 1U);
}

}  // namespace
}  // namespace hapticctrl::lcm_bridge
