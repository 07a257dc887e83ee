// The shipped scenes (mujoco/scenes/) do what their comments promise, in the engine alone: a
// hand (a spring-damper to an anchor, holding the body's orientation and weight as an operator
// does) moves the coupled body, and the scene answers. The same scenes through the real
// processes: mujoco_process_test.cpp.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <string>

#include "hapticctrl/mujoco/world.hpp"

namespace hapticctrl::mujoco {
namespace {

const std::string kScenes = HAPTICCTRL_MUJOCO_SCENES;
constexpr double kG = 9.81;

/// An operator's hand on the body: 500 N/m and 20 N.s/m to an anchor, 0.2 N.m/rad and
/// 0.004 N.m.s/rad (stable on the peg's 3e-5 kg.m^2 at 1 ms) to the body's first orientation, the
/// body's weight carried (unless `feel_weight`), and a push of its own.
class Hand {
 public:
  explicit Hand(const World& w, bool feel_weight = false)
      : anchor_{w.pose()[0], w.pose()[1], w.pose()[2]},
        hold_{w.pose()[3], w.pose()[4], w.pose()[5], w.pose()[6]},
        weight_(feel_weight ? 0.0 : w.mass() * kG) {}

  std::array<double, 3> anchor_;
  std::array<double, 3> push{};

  [[nodiscard]] client::Vector6 wrench(const World& w) const {
    const client::Pose7 p = w.pose();
    const client::Vector6 v = w.twist();
    client::Vector6 f{};
    for (std::size_t i = 0; i < 3; ++i) {
      f[i] = 500.0 * (anchor_[i] - p[i]) - 20.0 * v[i] + push[i];
    }
    f[2] += weight_;
    // Orientation error: the turn from the body to the hold, q_hold * conj(q), small angle.
    const double x = p[3], y = p[4], z = p[5], s = p[6];
    const double hx = hold_[0], hy = hold_[1], hz = hold_[2], hs = hold_[3];
    std::array<double, 4> e{
        hs * -x + hx * s + hy * -z - hz * -y, hs * -y - hx * -z + hy * s + hz * -x,
        hs * -z + hx * -y - hy * -x + hz * s, hs * s - hx * -x - hy * -y - hz * -z};
    const double sign = e[3] < 0 ? -1.0 : 1.0;
    for (std::size_t i = 0; i < 3; ++i) {
      f[3 + i] = 2.0 * 0.2 * sign * e[i] - 0.004 * v[3 + i];
    }
    return f;
  }

  /// `seconds` of the world with the anchor moving at `velocity` (m/s).
  void run(World& w, double seconds, std::array<double, 3> velocity = {}) {
    const auto steps = static_cast<int>(std::lround(seconds / w.timestep()));
    for (int i = 0; i < steps; ++i) {
      for (std::size_t k = 0; k < 3; ++k) {
        anchor_[k] += velocity[k] * w.timestep();
      }
      w.step(wrench(w));
      // As hapticctrl-mujoco does after its steps: the contacts within 1 cm are looked for,
      // which must not change the physics.
      w.set_report_distance(0.01);
      (void)w.contacts(contacts_);
    }
  }

 private:
  std::array<double, 4> hold_;
  double weight_;
  std::array<EngineContact, 16> contacts_{};
};

double joint(const World& w, const std::string& name) {
  for (const auto& [n, q] : w.joints()) {
    if (n == name) {
      return q;
    }
  }
  ADD_FAILURE() << "no joint " << name;
  return std::nan("");
}

std::array<double, 3> body(const World& w, const std::string& name) {
  for (const auto& [n, p] : w.free_bodies()) {
    if (n == name) {
      return p;
    }
  }
  ADD_FAILURE() << "no body " << name;
  return {};
}

class EveryScene : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryScene, LoadsNamesItsBodyAndStaysPutWhileHeld) {
  World w(kScenes + "/" + GetParam() + ".xml", "", 0.0);
  EXPECT_FALSE(w.body_name().empty());
  EXPECT_GT(w.mass(), 0.0);
  const client::Pose7 start = w.pose();
  Hand hand(w);
  hand.run(w, 2.0);
  const client::Pose7 now = w.pose();
  EXPECT_LT(std::hypot(now[0] - start[0], now[1] - start[1], now[2] - start[2]), 0.002);
  EXPECT_EQ(w.instabilities(), 0);
}

INSTANTIATE_TEST_SUITE_P(Shipped, EveryScene,
                         ::testing::Values("test_box", "table_blocks", "peg_in_hole", "door_latch",
                                           "heavy_lift"));

TEST(PegInHole, PushedDownThePegSlidesAlongTheChamferAndGoesIn) {
  World w(kScenes + "/peg_in_hole.xml", "", 0.0);
  Hand hand(w);
  hand.run(w, 0.2);
  hand.push = {0, 0, -3.0};
  hand.run(w, 1.0, {0, 0, -0.08});  // the anchor goes 8 cm down; 3 N on top
  hand.run(w, 1.0);
  const client::Pose7 p = w.pose();
  std::printf("peg at (%.4f, %.4f, %.4f) m\n", p[0], p[1], p[2]);
  EXPECT_LT(p[2], 0.005) << "its bottom within 5 mm of the hole's floor (centre 30 mm above it)";
  EXPECT_LT(std::hypot(p[0], p[1]), 0.001) << "on the hole's axis";
  EXPECT_EQ(w.instabilities(), 0);
}

TEST(TableBlocks, TheToolPushesABlockAlongTheTable) {
  World w(kScenes + "/table_blocks.xml", "", 0.0);
  Hand hand(w);
  const double start = body(w, "block_red")[0];
  hand.run(w, 1.5, {0.06, 0, 0});  // 9 cm toward the block 2.5 cm away
  hand.run(w, 0.5);
  const auto block = body(w, "block_red");
  std::printf("block from x %.4f to (%.4f, %.4f, %.4f) m\n", start, block[0], block[1], block[2]);
  EXPECT_GT(block[0] - start, 0.04);
  EXPECT_NEAR(block[2], 0.02, 0.002) << "still on the table";
}

TEST(TableBlocks, WithTheGripOnABlockIsLiftedAndStacked) {
  World w(kScenes + "/table_blocks.xml", "", 0.0);
  ASSERT_TRUE(w.has_grip());
  Hand hand(w);
  hand.run(w, 0.5, {0.12, 0, 0.09});  // over the red block: (0.06, 0, 0.075)
  hand.run(w, 0.5, {0, 0, -0.05});    // down onto it (the anchor 5 mm into its top)
  w.set_grip(true);
  hand.run(w, 0.5);
  hand.run(w, 0.5, {0, 0, 0.08});  // up 4 cm
  const auto lifted = body(w, "block_red");
  std::printf("block lifted to z %.4f m\n", lifted[2]);
  EXPECT_GT(lifted[2], 0.045);
  hand.run(w, 1.0, {-0.14, 0, 0});  // over the tower base at x -0.08
  hand.run(w, 0.5, {0, 0, -0.04});  // down onto it
  w.set_grip(false);
  hand.run(w, 0.3, {0, 0, 0.1});  // away
  hand.run(w, 0.5);
  const auto stacked = body(w, "block_red");
  std::printf("block let go at (%.4f, %.4f, %.4f) m\n", stacked[0], stacked[1], stacked[2]);
  EXPECT_NEAR(stacked[0], -0.08, 0.02);
  EXPECT_NEAR(stacked[2], 0.04, 0.003) << "resting on the 2 cm base";
}

TEST(DoorLatch, TheLatchHoldsTheDoorUntilItsBoltIsPressed) {
  World w(kScenes + "/door_latch.xml", "", 0.0);
  Hand hand(w);
  // Down to the door's face near its free end, then push toward -y.
  hand.run(w, 0.5, {0, -0.06, -0.2});  // from (0.06, 0.05, 0.2) to (0.06, 0.02, 0.1)
  hand.push = {0, -3.0, 0};
  hand.run(w, 1.0, {0, -0.02, 0});
  const double latched = joint(w, "hinge");
  std::printf("pushed while latched: hinge %.3f rad\n", latched);
  EXPECT_GT(latched, -0.06) << "the bolt stops the door on the keeper";
  // Back off, over the bolt's top (0.09, 0, 0.171), press it 3 cm down, push the door.
  hand.push = {};
  hand.run(w, 0.5, {0, 0.08, 0.2});
  hand.run(w, 1.0, {0.03, -0.04, 0});
  hand.push = {0, 0, -4.0};
  hand.run(w, 1.0, {0, 0, -0.06});
  const double pressed = joint(w, "bolt_slide");
  std::printf("bolt pressed to %.4f m\n", pressed);
  EXPECT_LT(pressed, -0.02);
  hand.push = {0, -3.0, -4.0};
  hand.run(w, 1.5, {0, -0.06, 0});
  const double opened = joint(w, "hinge");
  std::printf("pushed with the bolt pressed: hinge %.3f rad\n", opened);
  // The bolt's far side passes the keeper's (2.8 cm out) at 0.114 rad.
  EXPECT_LT(opened, -0.12) << "the door swings open past the keeper";
  EXPECT_EQ(w.instabilities(), 0);
}

TEST(HeavyLift, LiftedClearTheWeightIsAllTheHandCarries) {
  World w(kScenes + "/heavy_lift.xml", "", 0.0);
  Hand hand(w, /*feel_weight=*/true);
  hand.run(w, 1.5, {0, 0, 0.04});  // 6 cm up: clear of the shelf once the spring carries m g
  hand.run(w, 1.0);
  const auto f = hand.wrench(w);
  const auto contact = w.contact_force();
  std::printf("lifted to z %.4f m; the hand carries %.3f N (m g %.3f N)\n", w.pose()[2], f[2],
              w.mass() * kG);
  EXPECT_NEAR(w.mass(), 0.8, 1e-9);
  EXPECT_NEAR(std::hypot(contact[0], contact[1], contact[2]), 0.0, 1e-9) << "clear of the shelf";
  EXPECT_NEAR(f[2], w.mass() * kG, 0.01 * w.mass() * kG);
}

}  // namespace
}  // namespace hapticctrl::mujoco
