#include "hapticctrl/rt_core/decoupled_joint_sim.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <memory>

namespace hapticctrl::rt_core {
namespace {

constexpr TimeNs kDt = kNsPerMs;

struct SimRig {
  std::unique_ptr<shm::SeqlockCell<shm::ForcePayload>> force =
      std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  DecoupledJointSim sim{DecoupledJointParams{}, force.get()};
  void push(double fx) {
    shm::ForcePayload p;
    p.wrench[0] = fx;
    force->publish(p, 0);
  }
  ArmMeasures step(bool enable, int steps = 1, const Vector6d& torque = Vector6d::Zero()) {
    for (int i = 0; i < steps; ++i) {
      sim.send_commands(ArmCommands{torque, enable}, i * kDt, kDt);
    }
    ArmMeasures m;
    sim.get_measures(m);
    return m;
  }
};

TEST(DecoupledJointSim, BrakesHoldTheArmWhenUnpowered) {
  SimRig rig;
  rig.push(20.0);
  const ArmMeasures before = rig.step(false);
  const ArmMeasures after = rig.step(false, 1000);
  EXPECT_TRUE(after.position.isApprox(before.position));
  EXPECT_TRUE(after.velocity.isZero());
}

TEST(DecoupledJointSim, PoweredJointMovesUnderOperatorForce) {
  SimRig rig;
  rig.sim.set_supply(true);
  rig.push(1.0);
  const ArmMeasures m = rig.step(true, 100);
  EXPECT_GT(m.velocity(0), 0.0);
  EXPECT_GT(m.position(0), 0.0);
  EXPECT_DOUBLE_EQ(m.velocity(1), 0.0);
}

TEST(DecoupledJointSim, TorqueIsSaturatedToTheMotorLimit) {
  SimRig rig;
  rig.sim.set_supply(true);
  rig.step(true, 1, Vector6d::Constant(1000.0));
  ArmMeasures m;
  rig.sim.get_measures(m);
  EXPECT_DOUBLE_EQ(m.torque(0), 30.0);
  EXPECT_DOUBLE_EQ(m.torque(5), 3.0);
}

TEST(DecoupledJointSim, InvalidOperatorForceIsRejectedAndCounted) {
  SimRig rig;
  rig.sim.set_supply(true);
  rig.push(std::numeric_limits<double>::infinity());
  rig.step(true);
  rig.push(1e6);
  rig.step(true);
  EXPECT_EQ(rig.sim.rejected_force_samples(), 2U);
  EXPECT_TRUE(rig.sim.operator_wrench().isZero());
}

TEST(DecoupledJointSim, JointLimitsStopTheMotion) {
  SimRig rig;
  rig.sim.set_supply(true);
  const ArmMeasures m = rig.step(true, 5000, (Vector6d() << 0, 0, 0, 0, 3, 0).finished());
  EXPECT_DOUBLE_EQ(m.position(4), 1.4);
}

}  // namespace
}  // namespace hapticctrl::rt_core
