// Tests of demo_options.hpp: command line of hapticctrl-demo.
#include "hapticctrl/demo/demo_options.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::demo {
namespace {

TEST(DemoOptions, DefaultsTalkToTheLocalBridgeAndPowerOn) {
  const DemoOptions o = DemoOptions::parse({});
  EXPECT_EQ(o.server, "127.0.0.1:5125");
  EXPECT_TRUE(o.power_on);
  EXPECT_FALSE(o.headless);
  EXPECT_DOUBLE_EQ(o.gap, 0.01);
}

TEST(DemoOptions, ParsesTheSceneAndTheRun) {
  const DemoOptions o = DemoOptions::parse({"--server",    "10.0.0.2:6000",
                                            "--headless",  "--duration",
                                            "2.5",         "--script",
                                            "s.txt",       "--log",
                                            "d.csv",       "--json",
                                            "--status-ms", "250",
                                            "--no-power",  "--mass",
                                            "1.2",         "--radius",
                                            "0.04",        "--gap",
                                            "0.005",       "--contact-stiffness",
                                            "3000",        "--contact-damping",
                                            "40",          "--friction",
                                            "0.3",         "--gravity"});
  EXPECT_EQ(o.server, "10.0.0.2:6000");
  EXPECT_TRUE(o.headless);
  EXPECT_DOUBLE_EQ(o.duration_s, 2.5);
  EXPECT_EQ(o.script_path, "s.txt");
  EXPECT_EQ(o.log_path, "d.csv");
  EXPECT_TRUE(o.json);
  EXPECT_EQ(o.status_ms, 250);
  EXPECT_FALSE(o.power_on);
  EXPECT_DOUBLE_EQ(o.scene.mass, 1.2);
  EXPECT_DOUBLE_EQ(o.scene.mobile_radius, 0.04);
  EXPECT_DOUBLE_EQ(o.scene.fixed_radius, 0.04);
  EXPECT_DOUBLE_EQ(o.gap, 0.005);
  EXPECT_DOUBLE_EQ(o.scene.contact_stiffness, 3000);
  EXPECT_DOUBLE_EQ(o.scene.contact_damping, 40);
  EXPECT_DOUBLE_EQ(o.scene.friction, 0.3);
  EXPECT_TRUE(o.scene.gravity);
}

TEST(DemoOptions, PublishesTheSceneOnTheLocalBusUnlessTold) {
  const DemoOptions defaults = DemoOptions::parse({});
  EXPECT_TRUE(defaults.publish_scene);
  EXPECT_NE(defaults.lcm_url.find("ttl=0"), std::string::npos);
  EXPECT_EQ(defaults.instance, "default");
  EXPECT_EQ(defaults.scene_rate_hz, 30.0);
  const DemoOptions o = DemoOptions::parse(
      {"--lcm-url", "memq://", "--instance", "lab", "--scene-rate", "60", "--no-lcm"});
  EXPECT_FALSE(o.publish_scene);
  EXPECT_EQ(o.lcm_url, "memq://");
  EXPECT_EQ(o.instance, "lab");
  EXPECT_EQ(o.scene_rate_hz, 60.0);
  EXPECT_THROW((void)DemoOptions::parse({"--instance", "a.b"}), std::invalid_argument);
  EXPECT_THROW((void)DemoOptions::parse({"--scene-rate", "0"}), std::invalid_argument);
}

TEST(DemoOptions, RefusesOutOfRangeValuesAndUnknownOptions) {
  EXPECT_THROW((void)DemoOptions::parse({"--mass", "0"}), std::invalid_argument);
  EXPECT_THROW((void)DemoOptions::parse({"--mass", "nan"}), std::invalid_argument);
  EXPECT_THROW((void)DemoOptions::parse({"--gap", "-1"}), std::invalid_argument);
  EXPECT_THROW((void)DemoOptions::parse({"--duration"}), std::invalid_argument);
  EXPECT_THROW((void)DemoOptions::parse({"--fly"}), std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::demo
