// Tests of dds_bridge/commands.hpp: DDS commands and operator wrenches decoded.
#include "hapticctrl/dds_bridge/commands.hpp"

#include <gtest/gtest.h>

#include <string>

namespace hapticctrl::dds_bridge {
namespace {

shm::CtrlCode code(std::string text) {
  std_msgs_msg_dds__String_ m{text.data()};
  return command_of(m);
}

TEST(DdsCommands, EachCommandIsNamedExactly) {
  EXPECT_EQ(code("power_on"), shm::CtrlCode::kPowerOn);
  EXPECT_EQ(code("power_off"), shm::CtrlCode::kPowerOff);
  EXPECT_EQ(code("emergency_stop"), shm::CtrlCode::kEmergencyStop);
  EXPECT_EQ(code("emergency_reset"), shm::CtrlCode::kEmergencyReset);
  EXPECT_EQ(code("stop"), shm::CtrlCode::kStop);
  for (const char* other : {"", "POWER_ON", "power_on ", "stop\n", "estop", "power"}) {
    EXPECT_EQ(code(other), shm::CtrlCode::kNone) << other;
  }
  std_msgs_msg_dds__String_ null_text{nullptr};
  EXPECT_EQ(command_of(null_text), shm::CtrlCode::kNone);
}

TEST(DdsCommands, TheWrenchIsForceThenTorque) {
  geometry_msgs_msg_dds__WrenchStamped_ m{};
  m.wrench_ = {{1, 2, 3}, {4, 5, 6}};
  EXPECT_EQ(wrench_of(m), (shm::Vector6{1, 2, 3, 4, 5, 6}));
}

}  // namespace
}  // namespace hapticctrl::dds_bridge
