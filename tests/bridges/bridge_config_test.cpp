// Tests of bridge_config.hpp: command line of hapticctrl-udp.
#include "hapticctrl/udp_bridge/bridge_config.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::udp_bridge {
namespace {

TEST(BridgeConfig, DefaultsAreLoopbackAndTheStandardPort) {
  const BridgeConfig c = BridgeConfig::parse({});
  EXPECT_EQ(c.bind_address, "127.0.0.1");
  EXPECT_EQ(c.port, 5125);
  EXPECT_EQ(c.watchdog_ms, 3000U);
}

TEST(BridgeConfig, ParsesEveryOption) {
  const BridgeConfig c =
      BridgeConfig::parse({"--instance", "lab", "--port", "0", "--watchdog-ms", "250", "--duration",
                           "1.5", "--json", "--priority", "70"});
  EXPECT_EQ(c.priority, 70);
  EXPECT_EQ(c.instance, "lab");
  EXPECT_EQ(c.port, 0);
  EXPECT_EQ(c.watchdog_ms, 250U);
  EXPECT_DOUBLE_EQ(c.duration_s, 1.5);
  EXPECT_TRUE(c.json);
}

TEST(BridgeConfig, AllowListAndHandshakeRate) {
  const BridgeConfig c = BridgeConfig::parse(
      {"--allow-client", "127.0.0.1", "--allow-client", "10.1.0.0/16", "--hello-rate", "5"});
  ASSERT_EQ(c.allowed_clients.size(), 2U);
  EXPECT_EQ(c.allowed_clients[1].mask, 0xFFFF0000U);
  EXPECT_DOUBLE_EQ(c.hello_rate, 5.0);
  EXPECT_TRUE(BridgeConfig::parse({}).allowed_clients.empty()) << "no list: any source";
  try {
    BridgeConfig::parse({"--allow-client", "10.1.0.0/33"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--allow-client: '10.1.0.0/33': the prefix length must be 0..32");
  }
  EXPECT_THROW(BridgeConfig::parse({"--allow-client", "lab-pc"}), std::invalid_argument);
  EXPECT_THROW(BridgeConfig::parse({"--hello-rate", "0"}), std::invalid_argument);
  EXPECT_EQ(BridgeConfig::parse({}).max_watchdog_ms, 10000U);
  EXPECT_EQ(BridgeConfig::parse({"--max-watchdog-ms", "20000"}).max_watchdog_ms, 20000U);
  EXPECT_THROW(BridgeConfig::parse({"--max-watchdog-ms", "1000"}), std::invalid_argument)
      << "below the default watchdog";
  // NaN used to pass the range check and switch the limiter off (H3).
  EXPECT_THROW(BridgeConfig::parse({"--hello-rate", "nan"}), std::invalid_argument);
  EXPECT_THROW(BridgeConfig::parse({"--duration", "nan"}), std::invalid_argument);
}

TEST(BridgeConfig, OtherInterfacesNeedAnExplicitChoice) {
  EXPECT_THROW(BridgeConfig::parse({"--bind", "0.0.0.0"}), std::invalid_argument);
  EXPECT_EQ(BridgeConfig::parse({"--bind", "0.0.0.0", "--allow-remote"}).bind_address, "0.0.0.0");
  EXPECT_NO_THROW(BridgeConfig::parse({"--bind", "127.0.0.2"}));
}

TEST(BridgeConfig, BadValuesNameTheOption) {
  try {
    BridgeConfig::parse({"--watchdog-ms", "5"});
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "--watchdog-ms: expected a number from 10 to 60000, got '5'");
  }
  EXPECT_THROW(BridgeConfig::parse({"--port", "70000"}), std::invalid_argument);
  EXPECT_THROW(BridgeConfig::parse({"--port"}), std::invalid_argument);
  EXPECT_THROW(BridgeConfig::parse({"--frobnicate"}), std::invalid_argument);
  EXPECT_THROW(BridgeConfig::parse({"--duration", "x"}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::udp_bridge
