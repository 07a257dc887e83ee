#include "hapticctrl/rt_core/servo_law.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "support/default_dynamics.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::default_dynamics;

const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();

ServoInputs powered_at(const Vector6d& q) {
  ServoInputs in;
  in.dt = kNsPerMs;
  in.logical.powered = true;
  in.measures.supply_on = true;
  in.measures.position = q;
  return in;
}

ChainState chain_at(const Vector6d& q) {
  ChainState s;
  default_dynamics().forward_kinematics(q, s);
  return s;
}

shm::VprPayload virtmech_client(const std::array<double, 7>& object_pose) {
  shm::VprPayload c;
  c.session_id = 1;
  c.command_type = static_cast<std::uint32_t>(shm::CommandType::kVirtmech);
  c.flags = shm::vpr_flags::kObjectAttached;
  c.object_pose = object_pose;
  c.object_mass = 0.5;
  c.client_time_step = 1e-3;
  return c;
}

/// Powered at the ready pose, coupled (VIRTMECH) to an object `dx` ahead of the handle along x.
ServoInputs coupled_to_object_ahead(double dx) {
  ServoInputs in = powered_at(kReady);
  const ChainState s = chain_at(kReady);
  in.client = virtmech_client(
      {s.handle_position.x() + dx, s.handle_position.y(), s.handle_position.z(), 0, 0, 0, 1});
  in.client_valid = true;
  return in;
}

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

TEST(ServoLaw, ImpedanceWrenchReachesTheJointsThroughTheJacobianAfterTheRamp) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client.session_id = 1;
  in.client.command_type = static_cast<std::uint32_t>(shm::CommandType::kImpedance);
  in.client.impedance_wrench = {0, 0, -10, 1, 0, 0};
  in.client_valid = true;
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_NEAR(out.handle_wrench.head<3>().norm(), 2.0, 1e-9) << "2000 N/s x 1 ms: first step";
  for (int k = 0; k < 20; ++k) {
    law.compute(in, false, out);
  }
  const ChainState s = chain_at(kReady);
  const Vector6d expected =
      default_dynamics().gravity_torque(s) +
      default_dynamics().jacobian(s).transpose() * (Vector6d() << 0, 0, -10, 1, 0, 0).finished();
  EXPECT_LT((out.commands.torque - expected).norm(), 1e-9);
}

TEST(ServoLaw, WrenchIsSaturatedToTheDeviceAndClientLimits) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client.session_id = 1;
  in.client.command_type = static_cast<std::uint32_t>(shm::CommandType::kImpedance);
  in.client.impedance_wrench = {500, 0, 0, 0, 0, 50};
  in.client_valid = true;
  ServoOutputs out;
  for (int k = 0; k < 100; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_NEAR(out.handle_wrench.head<3>().norm(), 35.0, 1e-9);
  EXPECT_NEAR(out.handle_wrench.tail<3>().norm(), 3.0, 1e-9);
  in.client.force_limits = {5.0, 0.5};
  for (int k = 0; k < 100; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_NEAR(out.handle_wrench.head<3>().norm(), 5.0, 1e-9);
  EXPECT_NEAR(out.handle_wrench.tail<3>().norm(), 0.5, 1e-9);
}

TEST(ServoLaw, GainsFollowObjectMassAndTimeStepWithinDeviceBounds) {
  ServoLaw law(default_dynamics());
  shm::VprPayload c;
  c.object_mass = 0.5;
  c.client_time_step = 1e-3;
  CouplingGains g = law.derive_gains(c);
  EXPECT_DOUBLE_EQ(g.k_linear, 2000.0) << "bounded by the device";
  EXPECT_DOUBLE_EQ(g.b_linear, 20.0);
  c.object_mass = 0.01;
  c.client_time_step = 10e-3;
  g = law.derive_gains(c);
  EXPECT_DOUBLE_EQ(g.k_linear, 25.0) << "0.25 m / T^2";
  EXPECT_NEAR(g.b_linear, 0.7, 1e-12) << "damping ratio 0.7";
  c.gain_override = {1e6, 5.0, 0, 0};
  g = law.derive_gains(c);
  EXPECT_DOUBLE_EQ(g.k_linear, 2000.0) << "override bounded";
  EXPECT_DOUBLE_EQ(g.b_linear, 5.0);
}

TEST(ServoLaw, VirtmechPullsTheHandleTowardTheObjectAndReturnsTheOpposite) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  // The handle frame is the identity rotation at the ready pose (pitches cancel).
  ServoOutputs out;
  for (int k = 0; k < 50; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_TRUE(out.coupled);
  EXPECT_NEAR(out.handle_wrench(0), 4.0, 1e-6) << "2000 N/m x 2 mm";
  EXPECT_NEAR(out.coupling_wrench(0), -4.0, 1e-6);
}

TEST(ServoLaw, VirtmechWithoutAnAttachedObjectRendersNothing) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  in.client.flags = 0;  // virtDetachVO
  ServoOutputs out;
  for (int k = 0; k < 50; ++k) {
    law.compute(in, false, out);
  }
  EXPECT_TRUE(out.handle_wrench.isZero());
  EXPECT_TRUE(out.coupling_wrench.isZero());
}

TEST(ServoLaw, StaleClientFadesOnTheRampWithoutSteps) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.005);
  ServoOutputs out;
  for (int k = 0; k < 20; ++k) {
    law.compute(in, false, out);
  }
  ASSERT_NEAR(out.handle_wrench(0), 10.0, 1e-6);
  double previous = out.handle_wrench(0);
  double max_step = 0.0;
  for (int age_ms = 1; age_ms <= 200; ++age_ms) {
    in.client_age = age_ms * kNsPerMs;
    law.compute(in, false, out);
    max_step = std::max(max_step, std::abs(out.handle_wrench(0) - previous));
    previous = out.handle_wrench(0);
    if (age_ms == 40) {
      EXPECT_NEAR(out.handle_wrench(0), 10.0, 1e-6) << "held (extrapolated) before the fade";
      EXPECT_TRUE(out.client_stale);
    }
    if (age_ms == 100) {
      EXPECT_NEAR(out.fade, 0.5, 1e-9);
      EXPECT_NEAR(out.handle_wrench(0), 5.0, 1e-6);
    }
  }
  EXPECT_DOUBLE_EQ(out.handle_wrench(0), 0.0);
  EXPECT_LE(max_step, 2.0 + 1e-9) << "never a step beyond the rate limit";
}

TEST(ServoLaw, DegradedModeHasNoCoupling) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.client = virtmech_client({0.7, 0, 0.2, 0, 0, 0, 1});
  in.client_valid = true;
  ServoOutputs out;
  law.compute(in, true, out);
  EXPECT_FALSE(out.coupled);
  EXPECT_TRUE(out.handle_wrench.isZero());
}

TEST(ServoLaw, ExcessiveHandleSpeedBrakesInsteadOfRendering) {
  ServoLaw law(default_dynamics());
  ServoInputs in = powered_at(kReady);
  in.measures.velocity << 0, 3.0, 0, 0, 0, 0;  // fast shoulder swing: > 1 m/s at the handle
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_GT(law.counters().speed_limited, 0U);
  const ChainState s = chain_at(kReady);
  const Vector3d v = (default_dynamics().jacobian(s) * in.measures.velocity).head<3>();
  EXPECT_LT(out.handle_wrench.head<3>().dot(v), 0.0) << "the wrench opposes the motion";
}

TEST(ServoLaw, TheBrakeOfTheSpeedSafetyIsNeverPassedToTheCoupledObject) {
  // Mirrored onto the client's object, the brake (and the passivity guard's damping, which also
  // only brakes the handle) pushed a free object along with the handle's motion: the demo's
  // sphere flew tens of metres under random operator pushes (found by the soak, 2026-12-01).
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  in.measures.velocity << 0, 3.0, 0, 0, 0, 0;  // > 1 m/s at the handle
  ServoOutputs out;
  law.compute(in, false, out);
  EXPECT_GT(law.counters().speed_limited, 0U);
  EXPECT_FALSE(out.coupled) << "the coupling is suspended while the handle is braked";
  EXPECT_TRUE(out.coupling_wrench.isZero());
  EXPECT_FALSE(out.handle_wrench.isZero()) << "the handle is braked";
}

TEST(ServoLaw, TheObjectFeelsTheCouplingButNotThePassivityGuardsDamping) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.002);
  ServoOutputs out;
  for (int k = 0; k < 50; ++k) {  // ramp the coupling up, handle at rest
    law.compute(in, false, out);
  }
  // The handle now moves along the spring's pull, faster and faster: the port gives energy
  // to the hand, the guard turns on and adds damping on the handle only.
  in.measures.velocity << 0.0, 0.0, 0.0, 0.0, 0.0, 0.0;
  for (int k = 0; k < 200 && law.counters().passivity_active == 0; ++k) {
    in.measures.velocity(1) = -0.01 * k;
    law.compute(in, false, out);
  }
  ASSERT_GT(law.counters().passivity_active, 0U);
  EXPECT_TRUE(out.coupled);
  EXPECT_GT((out.handle_wrench + out.coupling_wrench).norm(), 1e-6)
      << "the handle got damping that the object did not";
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

namespace hapticctrl::rt_core {
namespace {

TEST(ServoLaw, HandleIsReportedInTheClientsEnvironmentFrame) {
  ServoLaw law(test::default_dynamics());
  ServoInputs in;
  in.dt = kNsPerMs;
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
