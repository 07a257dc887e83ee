// Where the hand holds the coupled body (grasp.hpp): the body is sent where the handle was at
// the start, turned as the handle was, and moves with the same translations and rotations.
#include "hapticctrl/mujoco/grasp.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hapticctrl::mujoco {
namespace {

/// x y z w of a turn by `angle` about z.
client::Pose7 turned_about_z(double x, double y, double z, double angle) {
  return {x, y, z, 0, 0, std::sin(angle / 2), std::cos(angle / 2)};
}

void expect_pose_near(const client::Pose7& a, const client::Pose7& b) {
  const double same_sign = a[3] * b[3] + a[4] * b[4] + a[5] * b[5] + a[6] * b[6] < 0 ? -1 : 1;
  for (std::size_t i = 0; i < 7; ++i) {
    EXPECT_NEAR(a[i], (i >= 3 ? same_sign : 1.0) * b[i], 1e-12) << "component " << i;
  }
}

TEST(Grasp, TheIdentityLeavesTheSceneAsItIs) {
  const client::Pose7 p = turned_about_z(0.1, 0.2, 0.3, 0.4);
  expect_pose_near(Grasp{}.to_client(p), p);
}

TEST(Grasp, AtTheStartTheBodyIsSentWhereTheHandleIs) {
  const client::Pose7 body = turned_about_z(1.0, -2.0, 0.05, 0.7);
  const client::Pose7 handle = turned_about_z(0.5, 0.0, 0.2, -0.3);
  expect_pose_near(Grasp::between(body, handle).to_client(body), handle);
}

TEST(Grasp, TranslationsAndWorldRotationsOfTheBodyAreTheHandles) {
  const client::Pose7 body = turned_about_z(1.0, -2.0, 0.05, 0.7);
  const client::Pose7 handle = turned_about_z(0.5, 0.0, 0.2, -0.3);
  const Grasp g = Grasp::between(body, handle);
  // The body moved by (0.01, 0.02, -0.03) and turned a further 0.25 rad about the world's z.
  const client::Pose7 moved = turned_about_z(1.01, -1.98, 0.02, 0.95);
  expect_pose_near(g.to_client(moved), turned_about_z(0.51, 0.02, 0.17, -0.05));
}

TEST(Grasp, PointsOfTheSceneShiftByTheSameOffset) {
  const Grasp g = Grasp::between(turned_about_z(1, 2, 3, 0), turned_about_z(0, 0, 0, 1));
  const auto p = g.point_to_client({1.5, 2.0, 2.9});
  EXPECT_NEAR(p[0], 0.5, 1e-12);
  EXPECT_NEAR(p[1], 0.0, 1e-12);
  EXPECT_NEAR(p[2], -0.1, 1e-12);
}

}  // namespace
}  // namespace hapticctrl::mujoco
