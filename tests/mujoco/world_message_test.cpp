// The world as the web view gets it (world_message.hpp): geoms placed as the controller sees the
// scene, the reported contacts, and a model larger than the message.
#include "hapticctrl/mujoco/world_message.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <array>
#include <cstdio>
#include <fstream>
#include <string>

namespace hapticctrl::mujoco {
namespace {

const std::string kScenes = HAPTICCTRL_MUJOCO_SCENES;

TEST(WorldMessage, GeomsArePlacedWhereTheControllerSeesTheSceneAndKeepTheirAxes) {
  World w(kScenes + "/table_blocks.xml", "", 0.0);
  // The handle holds the tool (at 0 0 0.03 in the scene) at 0.5 0 0.2.
  const Grasp grasp = Grasp::between(w.pose(), {0.5, 0.0, 0.2, 0, 0, 0, 1});
  const hapticctrl_lcm::world_t m = to_world_message(w, grasp, {}, {7, 999.5, 42});
  EXPECT_EQ(m.utime, 42);
  EXPECT_EQ(m.steps, 7);
  EXPECT_DOUBLE_EQ(m.steps_per_second, 999.5);
  EXPECT_DOUBLE_EQ(m.model_steps_per_second, 1000.0);
  ASSERT_EQ(m.geom_count, 6);
  EXPECT_EQ(m.geoms_total, 6);
  // MuJoCo's order: the world's geoms (table, tower base), then the bodies' (tool, red block,
  // ...). The table (scene 0 0 -0.02) and the red block (0.06 0 0.02), shifted like the tool.
  EXPECT_NEAR(m.geoms[0].pose[0], 0.5, 1e-12);
  EXPECT_NEAR(m.geoms[0].pose[2], 0.2 - 0.05, 1e-12);
  EXPECT_NEAR(m.geoms[3].pose[0], 0.56, 1e-12);
  EXPECT_NEAR(m.geoms[3].pose[2], 0.19, 1e-12);
  EXPECT_NEAR(m.geoms[3].pose[6], 1.0, 1e-12);
  EXPECT_EQ(m.geoms[3].type, 6);
  EXPECT_DOUBLE_EQ(m.geoms[3].size[0], 0.02);
  EXPECT_TRUE(m.geoms[2].coupled);
  EXPECT_FALSE(m.geoms[3].coupled);
  EXPECT_EQ(m.contact_count, 0);
}

TEST(WorldMessage, CarriesTheContactsAsReported) {
  World w(kScenes + "/test_box.xml", "", 0.0);
  std::array<client::Contact, 2> contacts{};
  contacts[1].point = {0.1, 0.2, 0.3};
  contacts[1].normal = {0, 0, 1};
  contacts[1].distance = -0.001;
  contacts[1].stiffness = 2000.0;
  const hapticctrl_lcm::world_t m = to_world_message(w, Grasp{}, contacts, {});
  ASSERT_EQ(m.contact_count, 2);
  EXPECT_DOUBLE_EQ(m.contacts[1].point[1], 0.2);
  EXPECT_DOUBLE_EQ(m.contacts[1].normal[2], 1.0);
  EXPECT_DOUBLE_EQ(m.contacts[1].distance, -0.001);
  EXPECT_DOUBLE_EQ(m.contacts[1].stiffness, 2000.0);
}

TEST(WorldMessage, AModelLargerThanTheMessageSendsItsFirstGeomsAndSaysHowManyThereAre) {
  const std::string path =
      "/tmp/hapticctrl_world_message_test_" + std::to_string(getpid()) + ".xml";
  {
    std::ofstream model(path);
    model << "<mujoco><worldbody>";
    for (int i = 0; i < 130; ++i) {
      model << "<geom type='sphere' size='0.001' pos='" << 0.01 * i << " 0 0'/>";
    }
    model << "<body name='held'><freejoint/><geom type='box' size='0.01 0.01 0.01'/></body>";
    model << "</worldbody></mujoco>";
  }
  World w(path, "held", 0.0);
  std::remove(path.c_str());
  const hapticctrl_lcm::world_t m = to_world_message(w, Grasp{}, {}, {});
  EXPECT_EQ(m.geom_count, 128);
  EXPECT_EQ(m.geoms_total, 131);
}

}  // namespace
}  // namespace hapticctrl::mujoco
