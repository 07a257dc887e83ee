// Tests of channels.hpp: the channel names of one controller instance and LCM's local-only default
// URL, shared by every process that publishes or subscribes (LCM bridge, web bridge, demo client,
// tests).
#include "hapticctrl/lcmtypes/channels.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace hapticctrl::lcmtypes {
namespace {

TEST(Channels, CarryTheInstance) {
  const Channels c = Channels::of("lab2");
  EXPECT_EQ(c.arm_state, "hapticctrl.lab2.arm_state");
  EXPECT_EQ(c.events, "hapticctrl.lab2.events");
  EXPECT_EQ(c.hmi_command, "hapticctrl.lab2.hmi_command");
  EXPECT_EQ(c.scene, "hapticctrl.lab2.scene");
}

TEST(Channels, AreDistinct) {
  const Channels c = Channels::of("x");
  const std::set<std::string> names{c.arm_state, c.coupling,    c.cycle_stats, c.bridge_stats,
                                    c.events,    c.hmi_command, c.hmi_force,   c.scene};
  EXPECT_EQ(names.size(), 8U);
}

TEST(Channels, DefaultUrlStaysOnThisHost) {
  EXPECT_NE(std::string(kDefaultLcmUrl).find("ttl=0"), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::lcmtypes
