// hapticctrl-mujoco's command line (mujoco_options.hpp).
#include "hapticctrl/mujoco/mujoco_options.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::mujoco {
namespace {

TEST(MujocoOptions, DefaultsAreTheDemosHabits) {
  const MujocoOptions o = MujocoOptions::parse({"--model", "scene.xml"});
  EXPECT_EQ(o.model_path, "scene.xml");
  EXPECT_TRUE(o.body.empty());
  EXPECT_EQ(o.timestep_s, 0.0);
  EXPECT_EQ(o.server, "127.0.0.1:5125");
  EXPECT_FALSE(o.headless);
  EXPECT_FALSE(o.json);
  EXPECT_TRUE(o.power_on);
  EXPECT_TRUE(o.reconnect);
  EXPECT_TRUE(o.report_contacts);
}

TEST(MujocoOptions, EveryOptionIsRead) {
  const MujocoOptions o =
      MujocoOptions::parse({"--model", "m.xml", "--body", "peg", "--timestep", "0.002", "--server",
                            "10.0.0.2:6000", "--headless", "--duration", "3.5", "--json",
                            "--status-ms", "250", "--no-power", "--no-reconnect", "--no-contacts"});
  EXPECT_EQ(o.body, "peg");
  EXPECT_DOUBLE_EQ(o.timestep_s, 0.002);
  EXPECT_EQ(o.server, "10.0.0.2:6000");
  EXPECT_TRUE(o.headless);
  EXPECT_DOUBLE_EQ(o.duration_s, 3.5);
  EXPECT_TRUE(o.json);
  EXPECT_EQ(o.status_ms, 250);
  EXPECT_FALSE(o.power_on);
  EXPECT_FALSE(o.reconnect);
  EXPECT_FALSE(o.report_contacts);
}

TEST(MujocoOptions, AModelIsRequiredAndValuesAreChecked) {
  EXPECT_THROW((void)MujocoOptions::parse({}), std::invalid_argument);
  EXPECT_THROW((void)MujocoOptions::parse({"--model", "m.xml", "--timestep", "0.5"}),
               std::invalid_argument);
  EXPECT_THROW((void)MujocoOptions::parse({"--model", "m.xml", "--duration", "-1"}),
               std::invalid_argument);
  EXPECT_THROW((void)MujocoOptions::parse({"--model", "m.xml", "--bogus"}), std::invalid_argument);
}

TEST(MujocoOptions, TheWorldGoesOutOnTheInstancesChannelUnlessNoLcm) {
  const MujocoOptions d = MujocoOptions::parse({"--model", "m.xml"});
  EXPECT_TRUE(d.publish_world);
  EXPECT_EQ(d.instance, "default");
  EXPECT_DOUBLE_EQ(d.world_rate_hz, 30.0);
  const MujocoOptions o =
      MujocoOptions::parse({"--model", "m.xml", "--instance", "lab", "--world-rate", "60",
                            "--lcm-url", "memq://", "--no-lcm"});
  EXPECT_FALSE(o.publish_world);
  EXPECT_EQ(o.instance, "lab");
  EXPECT_DOUBLE_EQ(o.world_rate_hz, 60.0);
  EXPECT_EQ(o.lcm_url, "memq://");
  EXPECT_THROW((void)MujocoOptions::parse({"--model", "m.xml", "--instance", "a.b"}),
               std::invalid_argument);
  EXPECT_THROW((void)MujocoOptions::parse({"--model", "m.xml", "--world-rate", "0"}),
               std::invalid_argument);
}

TEST(MujocoOptions, HelpNeedsNoModelAndNamesEveryOption) {
  EXPECT_TRUE(MujocoOptions::parse({"--help"}).help);
  const std::string usage = MujocoOptions::usage();
  for (const char* name :
       {"--model", "--body", "--timestep", "--server", "--headless", "--duration", "--json",
        "--status-ms", "--no-power", "--no-reconnect", "--no-contacts", "--instance", "--lcm-url",
        "--world-rate", "--no-lcm"}) {
    EXPECT_NE(usage.find(name), std::string::npos) << name;
  }
}

}  // namespace
}  // namespace hapticctrl::mujoco
