// The demo client's two-sphere physics, with no controller: fixed-step scenarios.
#include "hapticctrl/demo/sphere_scene.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hapticctrl::demo {
namespace {

constexpr double kDt = 1e-3;

SceneConfig touching_scene() {
  SceneConfig c;
  c.fixed_center = {0.1, 0.0, 0.0};  // mobile at the origin: 4 cm gap (radii 3 cm)
  return c;
}

TEST(SphereScene, FreeSphereFollowsNewtonUnderAConstantForce) {
  SphereScene scene(touching_scene(), {});
  for (int i = 0; i < 100; ++i) {
    scene.step({0, 2, 0, 0, 0, 0}, {}, kDt);  // 2 N on 0.5 kg for 0.1 s
  }
  EXPECT_NEAR(scene.state().velocity.y(), 0.4, 1e-12);
  // Semi-implicit Euler: x_N = a dt^2 N (N + 1) / 2 exactly.
  EXPECT_NEAR(scene.state().position.y(), 0.5 * 4.0 * kDt * kDt * 100 * 101, 1e-12);
  EXPECT_EQ(scene.contact_force(), Eigen::Vector3d::Zero());
}

TEST(SphereScene, TorqueSpinsTheSphereAboutItsCentreWithSolidSphereInertia) {
  SphereScene scene(touching_scene(), {});
  const double inertia = scene.config().inertia();
  EXPECT_DOUBLE_EQ(inertia, 0.4 * 0.5 * 0.03 * 0.03);
  for (int i = 0; i < 10; ++i) {
    scene.step({}, {0, 0, 0, 0, 0, 1e-3}, kDt);
  }
  EXPECT_NEAR(scene.state().angular_velocity.z(), 1e-3 * 0.01 / inertia, 1e-9);
  EXPECT_NEAR(scene.state().orientation.norm(), 1.0, 1e-12);
  EXPECT_GT(scene.pose()[5], 0.0) << "turned about +z";
}

TEST(SphereScene, PushedOntoTheFixedSphereItComesToRestWithTheContactBalancingThePush) {
  SphereScene scene(touching_scene(), {});
  for (int i = 0; i < 5000; ++i) {
    scene.step({}, {5, 0, 0, 0, 0, 0}, kDt);
  }
  EXPECT_NEAR(scene.contact_force().x(), -5.0, 1e-3);
  EXPECT_NEAR(scene.penetration(), 5.0 / 2000.0, 1e-5) << "half-rigid: k * depth = push";
  EXPECT_LT(scene.state().velocity.norm(), 1e-5);
}

TEST(SphereScene, TheContactReportIsTheFixedSphereTangentPlaneTowardTheHandle) {
  SphereScene scene(touching_scene(), {});  // mobile at the origin, fixed at x = 0.1: 4 cm gap
  EXPECT_FALSE(scene.contact_report(0.01, 0.0)) << "4 cm away: nothing within 1 cm";
  const auto ahead = scene.contact_report(0.05, 1500.0);
  ASSERT_TRUE(ahead);
  EXPECT_NEAR(ahead->distance, 0.04, 1e-12);
  EXPECT_NEAR(ahead->normal[0], -1.0, 1e-12) << "the surface pushes the object back along -x";
  EXPECT_NEAR(ahead->point[0], 0.03, 1e-12) << "on the mobile sphere, facing the fixed one";
  EXPECT_DOUBLE_EQ(ahead->stiffness, 1500.0) << "clamped to the controller's limit";

  // The handle 45 degrees off the line of centres, 2 cm out from the fixed sphere: the plane
  // turns to face it (Mark et al. 1996), the mobile sphere's gap measured along that normal.
  const Eigen::Vector3d fixed = scene.config().fixed_center;
  const Eigen::Vector3d toward = Eigen::Vector3d(-1.0, 1.0, 0.0).normalized();
  const Eigen::Vector3d handle = fixed + 0.05 * toward;
  const auto tangent = scene.contact_report_toward(handle, 0.1, 0.0);
  ASSERT_TRUE(tangent);
  const Eigen::Vector3d n(tangent->normal[0], tangent->normal[1], tangent->normal[2]);
  EXPECT_NEAR((n - toward).norm(), 0.0, 1e-12);
  const double gap = (Eigen::Vector3d::Zero() - fixed).dot(toward) - 0.03 - 0.03;
  EXPECT_NEAR(tangent->distance, gap, 1e-12);
  EXPECT_FALSE(scene.contact_report_toward(handle, gap - 1e-3, 0.0)) << "farther than near";

  SceneConfig wall = touching_scene();
  wall.obstacle = Obstacle::kWall;
  SphereScene walled(wall, {});
  const auto plane = walled.contact_report(1.0, 0.0);
  const auto same = walled.contact_report_toward(handle, 1.0, 0.0);
  ASSERT_TRUE(plane && same);
  EXPECT_EQ(plane->normal, same->normal) << "a wall is one plane wherever the handle is";
  EXPECT_EQ(plane->distance, same->distance);
}

TEST(SphereScene, AMovedObstacleMovesItsSurface) {
  SceneConfig c = touching_scene();
  c.obstacle = Obstacle::kWall;
  SphereScene scene(c, {});
  const double before = scene.contact_report(1.0, 0.0)->distance;
  scene.move_obstacle({-0.005, 0.0, 0.0});
  EXPECT_NEAR(scene.contact_report(1.0, 0.0)->distance, before - 0.005, 1e-12) << "5 mm nearer";
  scene.move_obstacle({std::nan(""), 0.0, 0.0});
  EXPECT_NEAR(scene.config().fixed_center.x(), 0.095, 1e-12) << "a non-finite move is ignored";
}

TEST(SphereScene, ContactNeverPullsAndBouncingLosesEnergy) {
  SphereState start;
  start.velocity = {0.2, 0, 0};  // coasting into the fixed sphere, 4 cm away
  SphereScene scene(touching_scene(), start);
  const double initial = scene.kinetic_energy();
  bool touched = false;
  for (int i = 0; i < 1000; ++i) {
    scene.step({}, {}, kDt);
    touched = touched || scene.penetration() > 0.0;
    EXPECT_LE(scene.contact_force().x(), 0.0) << "pushes the mobile sphere away only, step " << i;
    EXPECT_LE(scene.kinetic_energy(), initial * (1 + 1e-9)) << "step " << i;
  }
  EXPECT_TRUE(touched);
  EXPECT_LT(scene.state().velocity.x(), 0.0) << "it bounced back";
  EXPECT_LT(scene.kinetic_energy(), 0.9 * initial) << "the contact damping took energy";
}

TEST(SphereScene, FrictionAndRollingResistanceHoldASlightlyObliquePush) {
  SceneConfig c = touching_scene();
  c.fixed_center = {0.06, -0.003, 0.0};  // the normal tilted by ~2.9 degrees
  SphereState start;
  start.position = {0.0001, 0.0, 0.0};
  SphereScene held(c, start);
  for (int i = 0; i < 3000; ++i) {
    held.step({}, {5, 0, 0, 0, 0, 0}, kDt);
  }
  EXPECT_LT(held.state().velocity.norm(), 1e-4);
  EXPECT_NEAR(held.contact_force().x(), -5.0, 1e-3);
  EXPECT_NEAR(held.contact_force().y(), 0.0, 1e-3) << "friction takes the tangential part";

  // A free-rolling sphere rolls over the fixed one: the equilibrium is unstable without it.
  c.rolling_resistance = 0.0;
  SphereScene rolling(c, start);
  for (int i = 0; i < 3000; ++i) {
    rolling.step({}, {5, 0, 0, 0, 0, 0}, kDt);
  }
  EXPECT_GT(rolling.state().position.y(), 0.01) << "rolled off sideways";
}

TEST(SphereScene, ACoarseClientStepBoundsTheContactGainsAndStaysStable) {
  SceneConfig c = touching_scene();
  c.fixed_center = {0.06, -0.003, 0.0};
  SphereState start;
  start.position = {0.0001, 0.0, 0.0};
  SphereScene scene(c, start);
  constexpr double kCoarse = 0.01;  // a 10 ms client step: the configured damping would diverge
  for (int i = 0; i < 500; ++i) {
    scene.step({}, {5, 0, 0, 0, 0, 0}, kCoarse);
  }
  EXPECT_LT(scene.state().velocity.norm(), 1e-3);
  EXPECT_NEAR(scene.contact_force().x(), -5.0, 1e-2);
  EXPECT_DOUBLE_EQ(scene.contact_damping(), 0.5 * c.mass / kCoarse) << "bounded for the step";
  EXPECT_DOUBLE_EQ(scene.contact_stiffness(), c.contact_stiffness) << "already stable";
}

TEST(SphereScene, ACoarseStepLeavesTheClientLibrarysDamperRoomOnTheRotation) {
  // The client library's passivity controller adds a damper of up to I / (2 dt) on the object's
  // rotation (channel_passivity.cpp), on the twist of the step before, beside the scene's own
  // rolling and friction terms. With the scene's stiffness at its integration's bound (m / dt^2)
  // the three together rang at the step's Nyquist rate on a 10 ms step (2026-12-07); with half
  // of the bound they come to rest.
  SceneConfig c = touching_scene();
  c.fixed_center = {0.06, 0.0, 0.0};
  SphereState start;
  start.position = {0.0001, 0.0, 0.0};
  SphereScene scene(c, start);
  constexpr double kCoarse = 0.01;
  for (int i = 0; i < 200; ++i) {
    scene.step({}, {5, 0, 0, 0, 0, 0}, kCoarse);
  }
  SphereState spun = scene.state();
  spun.angular_velocity = {0.0, 0.0, 1.0};  // rolling along the fixed sphere's surface
  SphereScene rolled(c, spun);
  const double damper = 0.5 * c.inertia() / kCoarse;
  for (int i = 0; i < 300; ++i) {
    const Eigen::Vector3d w = rolled.state().angular_velocity;
    rolled.step({0, 0, 0, -damper * w.x(), -damper * w.y(), -damper * w.z()}, {5, 0, 0, 0, 0, 0},
                kCoarse);
  }
  EXPECT_LT(rolled.state().angular_velocity.norm(), 1e-3);
  EXPECT_LT(rolled.state().velocity.norm(), 1e-3);
}

TEST(SphereScene, CorruptInputsAndBadStepsLeaveTheSceneUntouched) {
  SphereScene scene(touching_scene(), {});
  scene.step({std::nan(""), 0, 0, 0, 0, 0}, {}, kDt);
  scene.step({1, 0, 0, 0, 0, 0}, {}, -1.0);
  scene.step({1, 0, 0, 0, 0, 0}, {}, std::nan(""));
  EXPECT_EQ(scene.state().position, Eigen::Vector3d::Zero());
  EXPECT_EQ(scene.state().velocity, Eigen::Vector3d::Zero());
  SceneConfig bad;
  bad.mass = 0.0;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  bad = SceneConfig{};
  bad.friction = -1.0;
  EXPECT_THROW(bad.validate(), std::invalid_argument);
  EXPECT_NO_THROW(SceneConfig{}.validate());
}

TEST(SphereScene, GravityIsOptional) {
  SceneConfig c = touching_scene();
  c.gravity = true;
  SphereScene falling(c, {});
  falling.step({}, {}, kDt);
  EXPECT_NEAR(falling.state().velocity.z(), -9.81e-3, 1e-12);
  SphereScene floating(touching_scene(), {});
  floating.step({}, {}, kDt);
  EXPECT_EQ(floating.state().velocity.z(), 0.0);
}

}  // namespace
}  // namespace hapticctrl::demo
