// Tests of hand_motion.hpp: a simulated operator's hand for `hapticctrl-hmi play --hand`: a
// spring-damper grip (shm:.
#include "hapticctrl/hmi/hand_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

namespace hapticctrl::hmi {
namespace {

constexpr std::array<double, 3> kGrip{0.6, 0.0, 0.2};

TEST(HandMotion, GripsWhereTheHandleIsThroughARampAndHoldsStillWithoutWander) {
  const HandMotion hand({400.0, 8.0, 0.0, 1}, kGrip);
  EXPECT_EQ(hand.at(0.0).stiffness, 0.0);
  EXPECT_GT(hand.at(0.1).stiffness, 0.0);
  EXPECT_LT(hand.at(0.1).stiffness, 400.0);
  for (const double t : {0.3, 5.0, 60.0}) {
    const shm::HandGrip g = hand.at(t);
    EXPECT_EQ(g.stiffness, 400.0);
    EXPECT_EQ(g.damping, 8.0);
    EXPECT_EQ(g.anchor, kGrip);
    EXPECT_EQ(g.anchor_velocity, (std::array<double, 3>{}));
  }
}

TEST(HandMotion, TheWristHoldsTheGripsRotationThroughTheSameRamp) {
  constexpr std::array<double, 4> kTurned{0.0, 0.6, 0.0, 0.8};
  const HandMotion hand({100.0, 5.0, 0.01, 1, 2.0, 0.05}, kGrip, kTurned);
  EXPECT_EQ(hand.at(0.0).angular_stiffness, 0.0);
  EXPECT_NEAR(hand.at(0.1).angular_stiffness / 2.0, hand.at(0.1).stiffness / 100.0, 1e-12);
  for (const double t : {0.3, 5.0}) {
    const shm::HandGrip g = hand.at(t);
    EXPECT_EQ(g.angular_stiffness, 2.0);
    EXPECT_EQ(g.angular_damping, 0.05);
    EXPECT_EQ(g.anchor_rotation, kTurned) << "the rotation does not wander";
  }
  EXPECT_EQ(HandMotion({100.0, 5.0}, kGrip).at(1.0).angular_stiffness, 0.0);
}

TEST(HandMotion, WandersWithinItsAmplitudeWithAConsistentVelocityAndIsReproducible) {
  const HandOptions options{300.0, 5.0, 0.02, 7};
  const HandMotion hand(options, kGrip);
  const HandMotion same(options, kGrip);
  const HandMotion other({300.0, 5.0, 0.02, 8}, kGrip);
  double peak = 0.0;
  double moved = 0.0;
  bool differs = false;
  constexpr double kStep = 1e-3;
  for (int k = 0; k < 60'000; ++k) {  // 60 s
    const double t = k * kStep;
    const shm::HandGrip g = hand.at(t);
    const shm::HandGrip next = hand.at(t + kStep);
    EXPECT_EQ(g.anchor, same.at(t).anchor);
    differs = differs || g.anchor != other.at(t).anchor;
    for (std::size_t axis = 0; axis < 3; ++axis) {
      const double offset = g.anchor[axis] - kGrip[axis];
      peak = std::max(peak, std::abs(offset));
      moved = std::max(moved, std::abs(offset));
      // The velocity is the anchor's derivative (central difference, to the step's precision).
      const double rate = (next.anchor[axis] - g.anchor[axis]) / kStep;
      const double mean = 0.5 * (g.anchor_velocity[axis] + next.anchor_velocity[axis]);
      ASSERT_NEAR(rate, mean, 1e-4) << "t " << t << " axis " << axis;
    }
  }
  EXPECT_LE(peak, 0.02 + 1e-12);
  EXPECT_GT(moved, 0.005) << "a wander that hardly moves tests nothing";
  EXPECT_TRUE(differs);
  EXPECT_EQ(hand.at(0.0).anchor, kGrip) << "the wander fades in from the grip point";
}

TEST(HandMotion, RefusesAGripOrWanderOutOfRange) {
  EXPECT_THROW(HandMotion({5000.0, 5.0, 0.0, 1}, kGrip), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, -1.0, 0.0, 1}, kGrip), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, 5.0, 0.5, 1}, kGrip), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, 5.0, std::nan(""), 1}, kGrip), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, 5.0, 0.0, 1}, {3.0, 0.0, 0.0}), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, 5.0, 0.0, 1, 31.0, 0.0}, kGrip), std::invalid_argument);
  EXPECT_THROW(HandMotion({300.0, 5.0, 0.0, 1, 2.0, 0.05}, kGrip, {0.0, 0.0, 0.0, 2.0}),
               std::invalid_argument);
}

}  // namespace
}  // namespace hapticctrl::hmi
