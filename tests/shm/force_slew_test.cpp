// Tests of force_slew.hpp: the operator wrench a writer of the `force` region applies, moved
// towards a requested wrench at a bounded rate: whatever a panel, a script or a remote HMI asks
// for, the simulated hand never jumps.
#include "hapticctrl/shm/force_slew.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace hapticctrl::shm {
namespace {

TEST(ForceSlew, RefusesNonFiniteAndOutOfRangeWrenches) {
  ForceSlew slew;
  EXPECT_TRUE(slew.set_target({100, -100, 0, 10, -10, 0}));
  EXPECT_FALSE(slew.set_target({100.1, 0, 0, 0, 0, 0}));
  EXPECT_FALSE(slew.set_target({0, 0, 0, 0, 0, 10.5}));
  EXPECT_FALSE(slew.set_target({std::nan(""), 0, 0, 0, 0, 0}));
  EXPECT_FALSE(slew.set_target({0, std::numeric_limits<double>::infinity(), 0, 0, 0, 0}));
  EXPECT_EQ(slew.target(), (Vector6{100, -100, 0, 10, -10, 0})) << "refusals leave the target";
}

TEST(ForceSlew, MovesAtTheBoundedRatePerAxisAndSettlesExactly) {
  ForceSlew slew(ForceLimits{100, 10, 500, 50});
  ASSERT_TRUE(slew.set_target({10, -5, 0, 1, 0, 0}));
  EXPECT_DOUBLE_EQ(slew.time_to_settle(), 0.02);  // 10 N at 500 N/s; 1 N.m at 50 N.m/s
  EXPECT_TRUE(slew.step(0.01));
  EXPECT_DOUBLE_EQ(slew.applied()[0], 5.0);
  EXPECT_DOUBLE_EQ(slew.applied()[1], -5.0);
  EXPECT_DOUBLE_EQ(slew.applied()[3], 0.5);
  EXPECT_FALSE(slew.settled());
  EXPECT_TRUE(slew.step(0.05));
  EXPECT_TRUE(slew.settled());
  EXPECT_EQ(slew.applied(), slew.target());
  EXPECT_FALSE(slew.step(0.01)) << "nothing left to move";
}

TEST(ForceSlew, IgnoresNegativeAndNonFiniteTimeSteps) {
  ForceSlew slew;
  ASSERT_TRUE(slew.set_target({50, 0, 0, 0, 0, 0}));
  EXPECT_FALSE(slew.step(-1.0));
  EXPECT_FALSE(slew.step(std::nan("")));
  EXPECT_FALSE(slew.step(std::numeric_limits<double>::infinity()));
  EXPECT_EQ(slew.applied(), Vector6{});
}

TEST(HandAcceptable, RefusesNonFiniteAndOutOfRangeGrips) {
  HandGrip g;
  EXPECT_TRUE(hand_acceptable(g)) << "no hand";
  g.anchor = {0.6, 0.0, 0.2};
  g.anchor_velocity = {0.1, 0.0, 0.0};
  g.stiffness = 500.0;
  g.damping = 10.0;
  EXPECT_TRUE(hand_acceptable(g));
  g.anchor_rotation = {0.0, 0.0, 0.0, 0.0};
  EXPECT_TRUE(hand_acceptable(g)) << "a zeroed rotation without a wrist";
  g.anchor_rotation = {0.0, 0.6, 0.0, 0.8};
  g.angular_stiffness = 2.0;
  g.angular_damping = 0.05;
  EXPECT_TRUE(hand_acceptable(g));
  for (auto bad :
       {+[](HandGrip& h) { h.stiffness = 3001.0; }, +[](HandGrip& h) { h.stiffness = -1.0; },
        +[](HandGrip& h) { h.damping = 101.0; }, +[](HandGrip& h) { h.damping = std::nan(""); },
        +[](HandGrip& h) { h.anchor[1] = 2.5; },
        +[](HandGrip& h) { h.anchor[2] = std::numeric_limits<double>::infinity(); },
        +[](HandGrip& h) { h.anchor_velocity[0] = 6.0; },
        +[](HandGrip& h) { h.angular_stiffness = 31.0; },
        +[](HandGrip& h) { h.angular_damping = -0.1; },
        +[](HandGrip& h) { h.angular_damping = std::nan(""); },
        +[](HandGrip& h) {
          h.anchor_rotation = {0.0, 0.0, 0.0, 0.0};
        },
        +[](HandGrip& h) {
          h.anchor_rotation = {0.0, 0.0, 0.0, 1.1};
        },
        +[](HandGrip& h) { h.anchor_rotation[0] = std::nan(""); }}) {
    HandGrip h = g;
    bad(h);
    EXPECT_FALSE(hand_acceptable(h));
  }
}

}  // namespace
}  // namespace hapticctrl::shm
