// Tests of servo_law.hpp: the control law: inputs of one cycle in, motor torques and coupling
// wrench out.
#include "hapticctrl/rt_core/servo_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/law_inputs.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::chain_at;
using test::coupled_to_object_ahead;
using test::default_dynamics;
using test::kReady;
using test::powered_at;

TEST(ServoLaw, UnpoweredOutputsNothing) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.logical.powered = false;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_FALSE(out.commands.enable);
  EXPECT_TRUE(out.commands.torque.isZero());
}

TEST(ServoLaw, PoweredWithoutClientCompensatesGravityExactly) {
  ServoLaw law(default_dynamics());
  ServoOutputs out;
  law.compute(powered_at(kReady), false, out);
  ASSERT_TRUE(out.commands.enable);
  const Vector6d g = default_dynamics().gravity_torque(chain_at(kReady));
  EXPECT_LT((out.commands.torque - g).norm(), 1e-12);
  EXPECT_NEAR(out.handle_pose[0], 0.628, 5e-4);
}

TEST(ServoLaw, WrenchIsSaturatedToTheDeviceAndClientLimits) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client.session_id = 1;
  in.client.command = ClientCommand::kImpedance;
  in.client.impedance_wrench = {500, 0, 0, 0, 0, 50};
  in.client_valid = true;
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_NEAR(out.rendered_wrench.head<3>().norm(), 35.0, 1e-9);
  EXPECT_NEAR(out.rendered_wrench.tail<3>().norm(), 3.0, 1e-9);
  in.client.force_limits = {5.0, 0.5};
  for (int k = 0; k < 100; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_NEAR(out.rendered_wrench.head<3>().norm(), 5.0, 1e-9);
  EXPECT_NEAR(out.rendered_wrench.tail<3>().norm(), 0.5, 1e-9);
}

TEST(ServoLaw, AClippedWrenchIsFlaggedSaturatedAndAnUnclippedOneIsNot) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client.session_id = 1;
  in.client.command = ClientCommand::kImpedance;
  in.client.impedance_wrench = {10, 0, 0, 0, 0, 1};
  in.client_valid = true;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_FALSE(out.saturated) << "10 N and 1 N.m are within 35 N and 3 N.m";
  in.client.impedance_wrench = {0, 0, 0, 0, 0, 3.5};
  law.compute(in, false, out);
  EXPECT_TRUE(out.saturated) << "3.5 N.m over the 3 N.m peak";
  in.client.impedance_wrench = {4, 0, 0, 0, 0, 0};
  in.client.force_limits = {3.0, 0.0};
  law.compute(in, false, out);
  EXPECT_TRUE(out.saturated) << "over the client's own 3 N limit (virtSaturateTorque)";
  in.logical.powered = false;
  law.compute(in, false, out);
  EXPECT_FALSE(out.saturated) << "unpowered: nothing rendered, nothing clipped";
}

TEST(ServoLaw, SaturationKeepsTheCouplingsDamping) {
  // A heavy object far from the handle: the spring alone asks for more than the peak. The
  // damper must keep its share, or nothing damps the swing.
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.5);
  in.client.object_mass = 3.0;
  in.client.object_twist = {-0.5, 0, 0, 0, 0, 0};  // closing in at 0.5 m/s
  ServoOutputs out;
  for (int k = 0; k < 800; ++k) {  // restarted relaxed: 4 cm of stretch back, 80 N asked
    law.compute(in, false, out);
  }
  ASSERT_NEAR(out.rendered_wrench.head<3>().norm(), 35.0, 1e-6);
  EXPECT_NEAR(-out.object_wrench(0), 35.0, 1e-6);
  // Now the object moves away fast: spring and damper pull the same way, the sum saturates;
  // then it turns back: the damper (now opposing) must be there at once, whole.
  in.client.object_twist = {0.5, 0, 0, 0, 0, 0};
  law.compute(in, false, out);
  in.client.object_twist = {-1.0, 0, 0, 0, 0, 0};
  law.compute(in, false, out);
  const double damper = out.gains.b_linear * -1.0;
  ASSERT_LT(damper, -5.0);
  const double spring_share = -out.object_wrench(0) - damper;  // what is left of the spring
  EXPECT_NEAR(-out.object_wrench(0), 35.0, 1e-6) << "the force budget is used whole";
  EXPECT_GT(spring_share, 35.0) << "the spring gave way to the damper, not the other way";
}

TEST(ServoLaw, ADegradedCycleKeepsRenderingTheCoupling) {
  // A missed cycle renders the coupling from the last sample (rendering nothing dipped a
  // carried weight by about 1 N at every VM stall, J1): the degraded law's output is the main
  // law's.
  ServoLaw main_law(default_dynamics());
  ServoLaw degraded_law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  ServoOutputs main_out;
  ServoOutputs degraded_out;
  for (int k = 0; k < 300; ++k) {
    main_law.compute(in, false, main_out);
    degraded_law.continue_from(main_law.memory());
  }
  degraded_law.compute(in, true, degraded_out);
  main_law.compute(in, false, main_out);
  EXPECT_TRUE(degraded_out.coupled);
  EXPECT_NEAR(degraded_out.rendered_wrench(0), 4.0, 1e-6) << "2000 N/m x 2 mm";
  EXPECT_LT((degraded_out.commands.torque - main_out.commands.torque).norm(), 1e-12);
}

TEST(ServoLaw, ExcessiveHandleSpeedBrakesInsteadOfRendering) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.measures.velocity << 0, 3.0, 0, 0, 0, 0;  // fast shoulder swing: > 1 m/s at the handle
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_GT(law.counters().speed_limited, 0U);
  EXPECT_TRUE(out.braking);
  const ChainState s = chain_at(kReady);
  const Vector3d v = (default_dynamics().jacobian(s) * in.measures.velocity).head<3>();
  EXPECT_LT(out.rendered_wrench.head<3>().dot(v), 0.0) << "the wrench opposes the motion";
}

TEST(ServoLaw, TheBrakeIsNeverPassedToTheObjectWhichKeepsItsSpring) {
  // Mirrored onto the client's object, the brake (and the passivity guard's damping, which also
  // only brakes the handle) pushed a free object along with the handle's motion: the demo's
  // sphere flew tens of metres under random operator pushes (found by the soak, 2026-12-01).
  // Suspending the coupling instead let a weighted object fall away and come back at full
  // strength (H1): the object keeps its spring to the braked handle.
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
  }
  in.measures.velocity << 0, 2.0, 0, 0, 0, 0;  // 1.25 m/s at the handle
  law.compute(in, false, out);
  EXPECT_TRUE(out.braking);
  EXPECT_TRUE(out.coupled);
  const Vector3d spring = out.gains.k_linear * Vector3d(0.002, 0, 0);
  const Vector3d damper = -out.gains.b_linear * out.handle_twist.head<3>();
  EXPECT_LT((-out.object_wrench.head<3>() - (spring + damper)).norm(), 1e-6)
      << "the object feels the coupling, not the brake";
  EXPECT_EQ(out.engage, 0.0) << "the handle gets the brake instead of the coupling";
}

TEST(ServoLaw, AfterTheBrakeTheCouplingComesBackThroughTheRamp) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.005);
  ServoOutputs out;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
  }
  in.measures.velocity << 0, 3.0, 0, 0, 0, 0;
  for (int k = 0; k < 20; ++k) {
    law.compute(in, false, out);
  }
  in.measures.velocity.setZero();
  double previous = out.rendered_wrench(0);
  double max_step = 0.0;
  for (int k = 0; k < 200; ++k) {
    law.compute(in, false, out);
    max_step = std::max(max_step, std::abs(out.rendered_wrench(0) - previous));
    previous = out.rendered_wrench(0);
  }
  EXPECT_FALSE(out.braking);
  EXPECT_NEAR(out.rendered_wrench(0), 10.0, 1e-6);
  EXPECT_LE(max_step, 1.0 + 1e-9);
}

TEST(ServoLaw, SpeedThatOutlastsTheBrakeIsAVelocityFault) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.measures.velocity << 0, 3.0, 0, 0, 0, 0;
  ServoOutputs out;
  for (int k = 0; k < 249; ++k) {
    law.compute(in, false, out);
    ASSERT_FALSE(out.velocity_fault) << k;
  }
  law.compute(in, false, out);
  EXPECT_TRUE(out.velocity_fault) << "250 ms over the limit despite the brake";
  in.measures.velocity.setZero();
  law.compute(in, false, out);
  EXPECT_FALSE(out.velocity_fault);
}

TEST(ServoLaw, HandleIsReportedInTheClientsEnvironmentFrame) {
  ServoLaw law(test::default_dynamics());
  ServoInputs in;
  in.dt = 1ms;
  in.measures.position = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();
  // Our base sits 1 m along the client's x, turned 90 degrees about z.
  in.client.base_frame = {1.0, 0, 0, 0, 0, std::sqrt(0.5), std::sqrt(0.5)};
  in.client.speed_factor = 2.0;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_NEAR(out.client_handle_pose[0], 1.0, 1e-9);            // base x (0.628) -> client +y
  EXPECT_NEAR(out.client_handle_pose[1], 2.0 * 0.62821, 2e-5);  // scaled by the speed factor
  EXPECT_NEAR(out.client_handle_pose[2], 2.0 * 0.22741, 2e-5);
  EXPECT_NEAR(out.handle_pose[0], 0.62821, 2e-5) << "the base-frame pose is unchanged";
}

}  // namespace
}  // namespace hapticctrl::rt_core
