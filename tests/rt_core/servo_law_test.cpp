#include "hapticctrl/rt_core/servo_law.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(ServoLaw, UnpoweredOutputsNothing) {
  ServoLaw law;
  ServoInputs in;
  in.measures.velocity.setConstant(2.0);
  in.measures.supply_on = true;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_FALSE(out.commands.enable);
  EXPECT_TRUE(out.commands.torque.isZero());
}

TEST(ServoLaw, PoweredDampsJointVelocityInBothModes) {
  ServoLaw law(Vector6d::Constant(0.5));
  ServoInputs in;
  in.logical.powered = true;
  in.measures.supply_on = true;
  in.measures.velocity << 1, -2, 0, 0, 0, 4;
  for (const bool degraded : {false, true}) {
    ServoOutputs out;
    law.compute(in, degraded, out);
    EXPECT_TRUE(out.commands.enable);
    EXPECT_DOUBLE_EQ(out.commands.torque(0), -0.5);
    EXPECT_DOUBLE_EQ(out.commands.torque(1), 1.0);
    EXPECT_DOUBLE_EQ(out.commands.torque(5), -2.0);
    EXPECT_TRUE(out.coupling_wrench.isZero());
  }
}

}  // namespace
}  // namespace hapticctrl::rt_core
