// Tests of lcm_bridge_config.hpp: command line of hapticctrl-lcm.
#include "hapticctrl/lcm_bridge/lcm_bridge_config.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::lcm_bridge {
namespace {

TEST(LcmBridgeConfig, DefaultsStayOnTheHostAndRefuseRemoteCommands) {
  const LcmBridgeConfig c = LcmBridgeConfig::parse({});
  EXPECT_EQ(c.lcm_url, "udpm://239.255.76.67:7667?ttl=0");
  EXPECT_FALSE(c.allow_remote_commands);
  EXPECT_DOUBLE_EQ(c.stats_rate_hz, 10.0);
}

TEST(LcmBridgeConfig, ParsesEveryOption) {
  const LcmBridgeConfig c = LcmBridgeConfig::parse(
      {"--instance", "x", "--lcm-url", "memq://", "--arm-rate-hz", "0", "--stats-rate-hz", "5",
       "--allow-remote-commands", "--duration", "2", "--json"});
  EXPECT_EQ(c.instance, "x");
  EXPECT_EQ(c.lcm_url, "memq://");
  EXPECT_DOUBLE_EQ(c.arm_rate_hz, 0.0);
  EXPECT_DOUBLE_EQ(c.stats_rate_hz, 5.0);
  EXPECT_TRUE(c.allow_remote_commands);
  EXPECT_DOUBLE_EQ(c.duration_s, 2.0);
  EXPECT_TRUE(c.json);
}

TEST(LcmBridgeConfig, BadValuesNameTheOption) {
  EXPECT_THROW(LcmBridgeConfig::parse({"--arm-rate-hz", "-1"}), std::invalid_argument);
  EXPECT_THROW(LcmBridgeConfig::parse({"--stats-rate-hz", "0"}), std::invalid_argument);
  EXPECT_THROW(LcmBridgeConfig::parse({"--lcm-url"}), std::invalid_argument);
  EXPECT_THROW(LcmBridgeConfig::parse({"--bogus"}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::lcm_bridge
