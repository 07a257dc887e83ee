// Tests of joint_law.hpp: ARTICULAR's set points and ARTICULAR_IMPEDANCE's torques, with the
// safety layer per joint (range, clamp, fade, rate limit, passivity guard).
#include "hapticctrl/rt_core/joint_law.hpp"

#include <gtest/gtest.h>

#include "support/default_dynamics.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::default_dynamics;

const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();
constexpr double kDt = 1e-3;

const ArmModel& model() {
  return default_dynamics().model();
}

struct Cycle {
  explicit Cycle(ClientCommand command) {
    client.session_id = 1;
    client.command = command;
    client.joint_command = true;
    in.client = &client;
    in.q = kReady;
    in.inertia = Vector6d::Constant(0.05);
    in.share = 1.0;
    in.rate = 1000.0;  // a whole peak torque per ms: the rate limit out of the way
    in.dt = kDt;
  }
  JointLawResult run(const JointLaw& law) { return law.torque(in, memory); }

  ClientSample client;
  JointLawInputs in;
  JointMemory memory;
};

TEST(JointLaw, ArticularStartsWhereTheJointsAreAndRampsTowardAFarTarget) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticular);
  for (int i = 0; i < 6; ++i) {
    c.client.joint_target[static_cast<std::size_t>(i)] = kReady(i);
  }
  c.client.joint_target[0] = 1.0;  // 1 rad away
  const JointLawResult first = c.run(law);
  EXPECT_NEAR(c.memory.setpoint(0), 1e-3, 1e-12) << "1 rad/s for 1 ms";
  // The damper's pull toward the set point's 1 rad/s (2 * 0.7 * sqrt(100 * 0.05) = 3.1 N.m) and
  // 1 mrad of spring: not the spring stretched by 1 rad (clamped at 10 N.m).
  EXPECT_LT(std::abs(first.torque(0)), 3.5) << "a ramp, not the spring stretched by 1 rad";
  for (int k = 0; k < 2000; ++k) {
    (void)c.run(law);
  }
  EXPECT_NEAR(c.memory.setpoint(0), 1.0, 1e-12) << "reached after 1 s, and held";
  EXPECT_NEAR(c.memory.setpoint(1), kReady(1), 1e-12);
}

TEST(JointLaw, ArticularTargetsStayInsideEachJointsRange) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticular);
  c.in.q = Vector6d::Zero();
  c.client.joint_target = {5, -5, 5, -5, 5, -5};
  for (int k = 0; k < 10'000; ++k) {
    (void)c.run(law);
  }
  for (int i = 0; i < 6; ++i) {
    const JointModel& j = model().joints[static_cast<std::size_t>(i)];
    const double expected = i % 2 == 0 ? j.q_max - 0.05 : j.q_min + 0.05;
    EXPECT_NEAR(c.memory.setpoint(i), expected, 1e-9) << "joint " << i + 1;
  }
}

TEST(JointLaw, ArticularGainsKeepTheContinuousTorqueAtTheSpanAndTheSamplingBound) {
  const JointLaw law(model());
  Vector6d k;
  Vector6d b;
  law.gains(Vector6d::Constant(0.05), 1e-3, k, b);
  EXPECT_NEAR(k(0), model().joints[0].torque_continuous / 0.1, 1e-9);
  for (int i = 0; i < 6; ++i) {
    EXPECT_LE(k(i), 0.25 * model().joints[static_cast<std::size_t>(i)].rotor_inertia / 1e-6);
    EXPECT_LE(b(i), 0.05 / 1e-3);
  }
  law.gains(Vector6d::Constant(0.05), 10e-3, k, b);  // a 10 ms period: softer
  EXPECT_LT(k(3), model().joints[3].torque_continuous / 0.1);
}

TEST(JointLaw, ATorqueBeyondTheContinuousRatingIsClampedAndSaidSaturated) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticularImpedance);
  c.client.joint_torque = {100, -100, 0.5, 0, 0, 0};
  const JointLawResult r = c.run(law);
  EXPECT_TRUE(r.saturated);
  EXPECT_DOUBLE_EQ(r.torque(0), model().joints[0].torque_continuous);
  EXPECT_DOUBLE_EQ(r.torque(1), -model().joints[1].torque_continuous);
  EXPECT_DOUBLE_EQ(r.torque(2), 0.5);
}

TEST(JointLaw, TheTorqueChangesNoFasterThanTheRateLimit) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticularImpedance);
  c.in.rate = 10.0;  // a tenth of the peak per 10 ms
  c.client.joint_torque = {5, 0, 0, 0, 0, 0};
  const double step = model().joints[0].torque_peak * 10.0 * kDt;
  EXPECT_NEAR(c.run(law).torque(0), step, 1e-12);
  EXPECT_NEAR(c.run(law).torque(0), 2 * step, 1e-12);
}

TEST(JointLaw, NothingIsRenderedBeforeTheCommandOfTheModeHasCome) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticular);
  c.client.joint_command = false;  // the joint fields are zeros, not a target of the client's
  EXPECT_TRUE(c.run(law).torque.isZero());
  EXPECT_FALSE(c.memory.tracking);
}

TEST(JointLaw, AFadedLinkTakesTheTorqueAwayAndTheSetPointRestartsFromTheJoints) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticular);
  c.client.joint_target = {0.5, -0.6, 1.2, 0, -0.6, 0};
  for (int k = 0; k < 100; ++k) {
    (void)c.run(law);
  }
  ASSERT_GT(c.run(law).torque(0), 0.0);
  c.in.share = 0.0;
  EXPECT_TRUE(c.run(law).torque.isZero());
  c.in.share = 1.0;
  c.in.q(0) = 0.3;  // the hand moved the joint while the link was lost
  (void)c.run(law);
  EXPECT_NEAR(c.memory.setpoint(0), 0.3 + 1e-3, 1e-12);
}

TEST(JointLaw, AModeChangeStartsFromZero) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticularImpedance);
  c.client.joint_torque = {1, 1, 1, 0.5, 0.5, 0.5};
  ASSERT_FALSE(c.run(law).torque.isZero());
  c.client.command = ClientCommand::kArticular;
  c.client.joint_target = {0, -0.6, 1.2, 0, -0.6, 0};  // where the joints are
  EXPECT_LT(c.run(law).torque.norm(), 1e-9);
}

TEST(JointLaw, TheGuardTakesBackTheEnergyATorqueDeliversAndLeavesAPassiveOneAlone) {
  const JointLaw law(model());
  Cycle c(ClientCommand::kArticularImpedance);
  c.in.qd(0) = 1.0;
  // Along the motion: the torque does work on the hand, which never put energy in.
  c.client.joint_torque = {2, 0, 0, 0, 0, 0};
  (void)c.run(law);
  const JointLawResult pushing = c.run(law);
  EXPECT_TRUE(pushing.guarded);
  EXPECT_LT(pushing.torque(0), 2.0);
  EXPECT_GT(c.memory.observed_energy(0), -1e-12) << "the deficit was dissipated";
  // Against the motion: the hand gives energy, nothing to take back.
  Cycle d(ClientCommand::kArticularImpedance);
  d.in.qd(0) = 1.0;
  d.client.joint_torque = {-2, 0, 0, 0, 0, 0};
  for (int k = 0; k < 10; ++k) {
    EXPECT_FALSE(d.run(law).guarded);
  }
  EXPECT_DOUBLE_EQ(d.memory.torque(0), -2.0);
}

}  // namespace
}  // namespace hapticctrl::rt_core
