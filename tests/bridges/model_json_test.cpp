// Tests of model_json.hpp: the arm's kinematics for the page: each joint's origin (in the previous
// link frame at q = 0) and axis (in its own frame), its limits, the handle point in the last frame,
// and the workspace box.
#include "hapticctrl/web_bridge/model_json.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

namespace hapticctrl::web_bridge {
namespace {

TEST(ModelJson, CarriesTheKinematicsOfTheShippedModel) {
  const arm_model::ArmModel model = arm_model::load_arm_model(arm_model::default_arm_model_path());
  const auto j = nlohmann::json::parse(model_json(model));
  EXPECT_EQ(j["type"], "model");
  EXPECT_EQ(j["name"], model.name);
  ASSERT_EQ(j["joints"].size(), 6U);
  EXPECT_EQ(j["joints"][1]["origin"][2], model.joints[1].origin.z());
  EXPECT_EQ(j["joints"][1]["axis"][1], 1.0);  // J2 pitches about y
  EXPECT_EQ(j["joints"][2]["limits"][0], model.joints[2].q_min);
  EXPECT_EQ(j["handle"][0], model.handle.x());
  EXPECT_EQ(j["workspace"]["half_size"][2], model.limits.workspace_half_size.z());
}

}  // namespace
}  // namespace hapticctrl::web_bridge
