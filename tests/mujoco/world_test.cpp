// The MuJoCo world of hapticctrl-mujoco (world.hpp) on the tests' scene: loading and its error
// paths, the coupled body's state, the contacts it reports and what the hand feels of them.
#include "hapticctrl/mujoco/world.hpp"

#include <gtest/gtest.h>

#include <unistd.h>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>

#include "hapticctrl/mujoco/contact_mapping.hpp"
#include "temp_model.hpp"

namespace hapticctrl::mujoco {
namespace {

using test::TempModel;

const std::string kScenes = HAPTICCTRL_MUJOCO_SCENES;
const std::string kTestBox = kScenes + "/test_box.xml";
constexpr double kG = 9.81;

std::string message_of(const std::string& path, const std::string& body) {
  try {
    World w(path, body, 0.0);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

TEST(World, LoadsTheBodyTheSceneNamesWithItsMassAndTimeStep) {
  World w(kTestBox, "", 0.0);
  EXPECT_EQ(w.body_name(), "tool");
  EXPECT_NEAR(w.mass(), 0.5, 1e-12);
  EXPECT_DOUBLE_EQ(w.timestep(), 0.001);
  const auto i = w.inertia();
  // A 5 cm cube of 0.5 kg: m (2 a)^2 / 6 about each axis.
  EXPECT_NEAR(i[0], 0.5 * 0.05 * 0.05 / 6.0, 1e-9);
  const client::Pose7 p = w.pose();
  EXPECT_NEAR(p[2], 0.035, 1e-12);
  EXPECT_NEAR(p[6], 1.0, 1e-12);
  EXPECT_FALSE(w.has_grip());
}

TEST(World, AnotherBodyAndTimeStepCanBeChosen) {
  World w(kTestBox, "block", 0.002);
  EXPECT_EQ(w.body_name(), "block");
  EXPECT_NEAR(w.mass(), 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(w.timestep(), 0.002);
}

TEST(World, ABadModelGivesMujocosOwnWords) {
  EXPECT_NE(message_of("/nonexistent/scene.xml", "").find("/nonexistent/scene.xml"),
            std::string::npos);
  const TempModel bad(
      R"(<mujoco><worldbody><geom type="box" size="0.1 0.1"/></worldbody></mujoco>)");
  const std::string text = message_of(bad.path(), "");
  EXPECT_NE(text.find("cannot load the model"), std::string::npos) << text;
  EXPECT_NE(text.find("size"), std::string::npos) << "MuJoCo's text names the attribute: " << text;
}

TEST(World, ABodyThatIsMissingOrNotFreeIsRefusedNamingTheFreeOnes) {
  const std::string missing = message_of(kTestBox, "nothing");
  EXPECT_NE(missing.find("no body 'nothing'"), std::string::npos) << missing;
  EXPECT_NE(missing.find("tool, block"), std::string::npos) << missing;
  const std::string fixture = message_of(kTestBox, "fixture");
  EXPECT_NE(fixture.find("is not free"), std::string::npos) << fixture;
  const TempModel unnamed(
      R"(<mujoco><worldbody><body name="b"><freejoint/><geom size="0.01"/></body></worldbody></mujoco>)");
  const std::string none = message_of(unnamed.path(), "");
  EXPECT_NE(none.find("--body"), std::string::npos) << none;
  EXPECT_NE(none.find(": b)"), std::string::npos) << none;
}

TEST(World, TheBodySettlesOnTheTableAsDeepAsTheReportedSpringSays) {
  // Let go 5 mm above the table, the tool lands and rests: the table holds m g, and the depth
  // is m g over the stiffness its contacts report (summed over the surface: one per corner).
  World w(kTestBox, "", 0.0);
  const client::Vector6 none{};
  for (int i = 0; i < 2000; ++i) {
    w.step(none);
  }
  const auto f = w.contact_force();
  EXPECT_NEAR(f[2], 0.5 * kG, 0.005 * 0.5 * kG);
  std::array<EngineContact, 16> found{};
  const std::size_t n = w.contacts(found);
  ASSERT_GE(n, 1U);
  std::array<client::Contact, 16> out{};
  const std::size_t reported =
      to_client_contacts(std::span(found.data(), n), w.timestep(), 0.0, out);
  ASSERT_GE(reported, 1U);
  const double depth = 0.025 - w.pose()[2];  // the cube's half side over the table top at 0
  const double predicted = 0.5 * kG / out[0].stiffness;
  std::printf("rests %.4f mm deep on %zu contacts; m g / K = %.4f mm (K %.0f N/m)\n", depth * 1e3,
              reported, predicted * 1e3, out[0].stiffness);
  EXPECT_NEAR(depth, predicted, 0.05 * predicted);
  EXPECT_NEAR(out[0].normal[2], 1.0, 1e-6);
  EXPECT_EQ(w.instabilities(), 0);
}

TEST(World, ContactsWithinTheReportDistanceAreFoundWithoutChangingThePhysics) {
  World plain(kTestBox, "", 0.0);
  World reporting(kTestBox, "", 0.0);
  reporting.set_report_distance(0.05);
  std::array<EngineContact, 16> found{};
  const client::Vector6 hold_up{0, 0, 0.5 * kG + 0.2, 0, 0, 0};  // rising 2 cm in 0.3 s
  for (int i = 0; i < 300; ++i) {
    plain.step(hold_up);
    reporting.step(hold_up);
  }
  for (std::size_t k = 0; k < 7; ++k) {
    EXPECT_NEAR(plain.pose()[k], reporting.pose()[k], 1e-12) << k;
  }
  EXPECT_EQ(plain.contacts(found), 0U) << "clear of the table";
  const std::size_t n = reporting.contacts(found);
  ASSERT_GE(n, 1U) << "the table is within 5 cm";
  EXPECT_GT(found[0].distance, 0.0);
  for (std::size_t i = 1; i < n; ++i) {
    EXPECT_LE(found[i - 1].distance, found[i].distance) << "deepest first";
  }
}

TEST(World, ContactsOfTheScenesOwnPairsAreFoundWithinTheReportDistanceToo) {
  // The floor meets the box only through an explicit <pair> (the box's contype leaves it out of
  // MuJoCo's dynamic pairs), whose margin is the pair's own, not its geoms'.
  const TempModel model(R"(<mujoco><worldbody>
      <geom name="floor" type="plane" size="1 1 0.1"/>
      <body name="box" pos="0 0 0.03"><freejoint/>
        <geom name="box" type="box" size="0.01 0.01 0.01" mass="0.1" contype="2"
              conaffinity="2"/>
      </body></worldbody>
      <contact><pair geom1="box" geom2="floor" condim="1"/></contact></mujoco>)");
  World w(model.path(), "box", 0.0);
  std::array<EngineContact, 16> found{};
  EXPECT_EQ(w.contacts(found), 0U) << "2 cm above the floor";
  w.set_report_distance(0.05);
  const std::size_t n = w.contacts(found);
  ASSERT_GE(n, 1U) << "the floor is within 5 cm, through the pair";
  for (std::size_t i = 0; i < n; ++i) {
    EXPECT_NEAR(found[i].distance, 0.02, 1e-9) << "corner " << i;
  }
}

TEST(World, TheWrenchActsAtTheBodysOriginAndANonFiniteOneAsNothing) {
  World w(kTestBox, "", 0.0);
  const client::Vector6 lift{0, 0, 0.5 * kG + 5.0, 0, 0, 0};  // 10 m/s^2 up, no turn
  for (int i = 0; i < 100; ++i) {
    w.step(lift);
  }
  EXPECT_NEAR(w.twist()[2], 1.0, 0.01);
  EXPECT_NEAR(w.twist()[3], 0.0, 1e-9);
  World still(kTestBox, "", 0.0);
  const client::Vector6 bad{std::nan(""), 0, 1e300 * 1e300, 0, 0, 0};
  for (int i = 0; i < 30; ++i) {  // 4 mm of its 10 mm fall to the table
    still.step(bad);
  }
  EXPECT_TRUE(std::isfinite(still.pose()[2]));
  EXPECT_LT(still.twist()[2], 0.0) << "falls: the wrench was taken as zero";
}

TEST(World, TheAngularVelocityIsInTheWorldFrame) {
  World w(kTestBox, "", 0.0);
  const client::Vector6 spin{0, 0, 0.5 * kG + 1.0, 0, 0, 1e-3};  // lift off, turn about z
  for (int i = 0; i < 200; ++i) {
    w.step(spin);
  }
  const auto v = w.twist();
  EXPECT_GT(v[5], 0.0);
  EXPECT_NEAR(v[3], 0.0, 1e-9);
  EXPECT_NEAR(v[4], 0.0, 1e-9);
}

TEST(World, ResetPutsTheSceneBackAndListsItsBodiesAndJoints) {
  World w(kTestBox, "", 0.0);
  for (int i = 0; i < 200; ++i) {
    w.step({0, 0, 20, 0, 0, 0});
  }
  EXPECT_GT(w.pose()[2], 0.05);
  w.reset();
  EXPECT_NEAR(w.pose()[2], 0.035, 1e-12);
  EXPECT_DOUBLE_EQ(w.time(), 0.0);
  const auto bodies = w.free_bodies();
  ASSERT_EQ(bodies.size(), 1U);
  EXPECT_EQ(bodies[0].first, "block");
  EXPECT_NEAR(bodies[0].second[0], 0.1, 1e-12);
  const auto joints = w.joints();
  ASSERT_EQ(joints.size(), 1U);
  EXPECT_EQ(joints[0].first, "slider");
}

}  // namespace
}  // namespace hapticctrl::mujoco
