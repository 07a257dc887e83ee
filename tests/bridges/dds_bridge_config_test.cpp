// Tests of dds_bridge_config.hpp: command line of hapticctrl-dds.
#include "hapticctrl/dds_bridge/dds_bridge_config.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <stdexcept>
#include <string>

namespace hapticctrl::dds_bridge {
namespace {

/// Sets or clears $ROS_DOMAIN_ID for one test and restores it after.
struct DomainEnv {
  explicit DomainEnv(const char* value) {
    const char* old = std::getenv("ROS_DOMAIN_ID");
    had_ = old != nullptr;
    old_ = had_ ? old : "";
    value != nullptr ? setenv("ROS_DOMAIN_ID", value, 1) : unsetenv("ROS_DOMAIN_ID");
  }
  ~DomainEnv() { had_ ? setenv("ROS_DOMAIN_ID", old_.c_str(), 1) : unsetenv("ROS_DOMAIN_ID"); }
  DomainEnv(const DomainEnv&) = delete;
  DomainEnv& operator=(const DomainEnv&) = delete;
  DomainEnv(DomainEnv&&) = delete;
  DomainEnv& operator=(DomainEnv&&) = delete;

 private:
  bool had_ = false;
  std::string old_;
};

TEST(DdsBridgeConfig, DefaultsNameTheInstanceAndRefuseRemoteCommands) {
  const DdsBridgeConfig c = DdsBridgeConfig::parse({"--instance", "arm-1"});
  EXPECT_EQ(c.ros_namespace, "/hapticctrl/arm_1");
  EXPECT_FALSE(c.allow_remote_commands);
  EXPECT_DOUBLE_EQ(c.rate_hz, 100.0);
  EXPECT_DOUBLE_EQ(c.diagnostics_rate_hz, 1.0);
}

TEST(DdsBridgeConfig, ParsesEveryOption) {
  const DdsBridgeConfig c = DdsBridgeConfig::parse(
      {"--instance", "x", "--namespace", "/lab/arm1", "--domain-id", "42", "--rate-hz", "0",
       "--diagnostics-rate-hz", "5", "--allow-remote-commands", "--duration", "2", "--json"});
  EXPECT_EQ(c.instance, "x");
  EXPECT_EQ(c.ros_namespace, "/lab/arm1");
  EXPECT_EQ(c.domain(), 42U);
  EXPECT_DOUBLE_EQ(c.rate_hz, 0.0);
  EXPECT_DOUBLE_EQ(c.diagnostics_rate_hz, 5.0);
  EXPECT_TRUE(c.allow_remote_commands);
  EXPECT_DOUBLE_EQ(c.duration_s, 2.0);
  EXPECT_TRUE(c.json);
}

TEST(DdsBridgeConfig, TheDomainComesFromRosDomainIdUnlessGiven) {
  {
    const DomainEnv env("17");
    EXPECT_EQ(DdsBridgeConfig::parse({}).domain(), 17U);
    EXPECT_EQ(DdsBridgeConfig::parse({"--domain-id", "3"}).domain(), 3U);
  }
  {
    const DomainEnv env(nullptr);
    EXPECT_EQ(DdsBridgeConfig::parse({}).domain(), 0U);
  }
  for (const char* bad : {"233", "-1", "x", "1.5"}) {
    const DomainEnv env(bad);
    EXPECT_THROW((void)DdsBridgeConfig::parse({}).domain(), std::invalid_argument) << bad;
  }
}

TEST(DdsBridgeConfig, BadValuesNameTheOption) {
  for (const auto& args :
       std::initializer_list<std::vector<std::string>>{{"--namespace", "lab"},
                                                       {"--namespace", "/lab/"},
                                                       {"--namespace", "/1arm"},
                                                       {"--domain-id", "233"},
                                                       {"--rate-hz", "-1"},
                                                       {"--diagnostics-rate-hz", "0"},
                                                       {"--bogus"}}) {
    try {
      (void)DdsBridgeConfig::parse(args);
      ADD_FAILURE() << args.front() << " accepted";
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), testing::HasSubstr(args.front())) << e.what();
    }
  }
}

}  // namespace
}  // namespace hapticctrl::dds_bridge
