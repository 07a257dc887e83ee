// The walls (servo_law_walls.cpp): workspace box, soft joint limits, joint-bound bits.
#include <gtest/gtest.h>

#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/law_inputs.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::chain_at;
using test::default_dynamics;
using test::kReady;
using test::powered_at;

TEST(ServoLaw, JointBoundsNameTheJointsInTheirWallsAndTheJ23Sum) {
  ServoLaw law(default_dynamics());
  ServoOutputs out;
  law.compute(powered_at(kReady), false, out);
  EXPECT_EQ(out.joint_bounds, 0U) << "the ready pose is clear of every wall";
  Vector6d q = kReady;
  q(0) = -2.39;  // joint 1: limits -2.4 2.4, wall margin 0.05 rad
  q(5) = 2.58;   // joint 6: limits -2.6 2.6
  law.compute(powered_at(q), false, out);
  EXPECT_EQ(out.joint_bounds,
            shm::state_bits::joint_bound(0, false) | shm::state_bits::joint_bound(5, true));
  q = kReady;
  q(1) = 0.58;  // joint 2 in its upper wall (limit 0.6), the J2 + J3 sum 2.18 in its (2.2)
  q(2) = 1.6;
  law.compute(powered_at(q), false, out);
  EXPECT_EQ(out.joint_bounds,
            shm::state_bits::joint_bound(1, true) | shm::state_bits::joint_bound(6, true));
  q(1) = -1.0;  // the sum -0.7 in its lower wall (-0.6), each joint clear of its own
  q(2) = 0.3;
  law.compute(powered_at(q), false, out);
  EXPECT_EQ(out.joint_bounds, shm::state_bits::joint_bound(6, false));
  EXPECT_EQ(out.joint_bounds & ~shm::state_bits::kJointBoundsMask, 0U);
}

TEST(ServoLaw, WorkspaceWallPushesTheHandleBackIntoTheBox) {
  ServoLaw law(default_dynamics());
  // Shoulder and elbow pitched down: the handle is below the box's bottom face (z = 0.025 m).
  const Vector6d q = (Vector6d() << 0, 0.5, 0.5, 0, 0, 0).finished();
  ServoOutputs out;
  for (int k = 0; k < 50; ++k) {
    law.compute(powered_at(q), false, out);
  }
  EXPECT_GT(law.counters().workspace_walls, 0U);
  const ChainState s = chain_at(q);
  const Vector6d extra = out.commands.torque - default_dynamics().gravity_torque(s);
  // The extra joint torque must have a component of J^T * (upward force) (the wrist is singular
  // here, and the shoulder torque saturates, so project rather than invert J^T).
  const Vector6d up = default_dynamics().jacobian(s).transpose() * Vector6d::Unit(2);
  const double force = extra.dot(up) / up.squaredNorm();
  EXPECT_GT(force, 1.0) << "pushed back up into the box";
}

TEST(ServoLaw, JointLimitWallsPushBack) {
  ServoLaw law(default_dynamics());
  Vector6d q = kReady;
  q(4) = 1.39;  // inside J5's 0.05 rad margin below +1.4
  ServoOutputs out;
  law.compute(powered_at(q), false, out);
  const Vector6d g = default_dynamics().gravity_torque(chain_at(q));
  EXPECT_LT(out.commands.torque(4) - g(4), -0.5);
}

}  // namespace
}  // namespace hapticctrl::rt_core
