// Tests of arm_simulator.hpp: rigid-body simulation of the arm: M(q) qdd + C(q, qd) qd + G(q) =
// tau_motor + J^T w_operator + tau_friction + tau_stops, integrated with semi-implicit Euler in
// sub-steps.
#include "hapticctrl/rt_core/arm_simulator.hpp"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <atomic>
#include <memory>
#include <thread>

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

const Vector6d kReady = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();

class ArmSimulatorTest : public ::testing::Test {
 protected:
  ArmDynamics dynamics_{load_arm_model(default_arm_model_path())};
};

TEST_F(ArmSimulatorTest, EnergyIsConservedWithoutFrictionOrControl) {
  SimulatorOptions options;
  options.friction = false;
  options.stop_damping = 0.0;  // the stops stay elastic: no dissipation anywhere
  // Mid-range pose: a free swing under gravity for 10 s at 1 kHz, through the elastic stops.
  const Vector6d start = (Vector6d() << 0.2, -0.5, 1.3, 0.4, 0.2, 0.1).finished();
  ArmSimulator sim(dynamics_, options, start);
  const double e0 = sim.energy();
  double swing = 0.0;
  double last_second = 0.0;
  for (int k = 0; k < 10'000; ++k) {
    sim.step(Vector6d::Zero(), Vector6d::Zero(), 1e-3, false);
    swing = std::max(swing, sim.velocity().norm());
    if (k >= 9'000) {
      last_second += sim.energy() / 1000.0;
    }
  }
  EXPECT_GT(swing, 1.0) << "the arm really moved";
  // Energy is measured from the base plane (|E0| = 4.39 J here, of which up to 2.8 J swing
  // between kinetic and potential).
  EXPECT_LT(std::abs(sim.energy() - e0) / std::abs(e0), 0.01);
  EXPECT_LT(std::abs(last_second - e0) / std::abs(e0), 0.01);
}

TEST_F(ArmSimulatorTest, BrakesHoldAgainstGravityAndOperatorForce) {
  ArmSimulator sim(dynamics_, SimulatorOptions{}, kReady);
  Vector6d push;
  push << 30, 0, -30, 0, 0, 0;
  for (int k = 0; k < 2000; ++k) {
    sim.step(Vector6d::Zero(), push, 1e-3, true);
  }
  EXPECT_LT((sim.position() - kReady).norm(), 1e-12);
}

TEST_F(ArmSimulatorTest, UnbrakedArmFallsUnderGravity) {
  ArmSimulator sim(dynamics_, SimulatorOptions{}, kReady);
  const double z0 = sim.chain().handle_position.z();
  for (int k = 0; k < 200; ++k) {
    sim.step(Vector6d::Zero(), Vector6d::Zero(), 1e-3, false);
  }
  EXPECT_LT(sim.chain().handle_position.z(), z0 - 0.01);
}

TEST_F(ArmSimulatorTest, JointStopsHoldTheArmInsideItsLimits) {
  ArmSimulator sim(dynamics_, SimulatorOptions{}, kReady);
  Vector6d push_j5 = Vector6d::Zero();
  push_j5(4) = 2.0;
  for (int k = 0; k < 3000; ++k) {
    sim.step(push_j5, Vector6d::Zero(), 1e-3, false);
  }
  EXPECT_LT(sim.position()(4), 1.4 + 2.0 / 300.0 + 0.01) << "stiff stop: a few mrad of overshoot";
}

TEST_F(ArmSimulatorTest, SimulatedArmQuantisesAndSaturates) {
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  arm.set_supply(true);
  ArmCommands cmd;
  cmd.enable = true;
  cmd.torque.setConstant(1000.0);
  arm.send_commands(cmd, TimePoint{}, 1ms);
  ArmMeasures m;
  ASSERT_TRUE(arm.get_measures(m));
  EXPECT_DOUBLE_EQ(m.torque(0), 30.0);
  EXPECT_DOUBLE_EQ(m.torque(5), 3.0);
  const double step = 2.0 * 3.141592653589793 / 262144;
  EXPECT_NEAR(std::remainder(m.position(0), step), 0.0, 1e-12);
}

TEST_F(ArmSimulatorTest, TheSupplyCutFromAnotherThreadReachesARunningCycle) {
  // The fail-safe cuts the supply even when a SERVO hangs in the cycle (H4: set_supply was a
  // plain bool written beside the cycle; the ThreadSanitizer build checks this race).
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  arm.set_supply(true);
  ArmCommands cmd;
  cmd.enable = true;
  cmd.torque.setConstant(0.5);
  std::atomic<bool> cut{false};
  std::thread fail_safe([&] {
    for (int k = 0; k < 200; ++k) {
      arm.set_supply(k % 2 == 0);
    }
    arm.set_supply(false);
    cut.store(true);
  });
  ArmMeasures m;
  for (int k = 0; k < 2000 && !cut.load(); ++k) {
    arm.send_commands(cmd, TimePoint{}, 100us);
    arm.get_measures(m);
  }
  fail_safe.join();
  arm.send_commands(cmd, TimePoint{}, 100us);
  ASSERT_TRUE(arm.get_measures(m));
  EXPECT_FALSE(m.supply_on);
  EXPECT_EQ(m.torque, Vector6d::Zero()) << "no torque once the supply is cut";
}

TEST_F(ArmSimulatorTest, UnpoweredSimulatedArmDoesNotMoveUnderOperatorForce) {
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  shm::ForcePayload push;
  push.wrench[0] = 20.0;
  force->publish(push, 0);
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  ArmMeasures before;
  arm.get_measures(before);
  for (int k = 0; k < 1000; ++k) {
    arm.send_commands(ArmCommands{}, TimePoint{}, 1ms);
  }
  ArmMeasures after;
  arm.get_measures(after);
  EXPECT_TRUE(after.position.isApprox(before.position));
  EXPECT_DOUBLE_EQ(arm.operator_wrench()(0), 20.0);
}

TEST_F(ArmSimulatorTest, InvalidOperatorWrenchIsRejected) {
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  shm::ForcePayload bad;
  bad.wrench[2] = 1e9;
  force->publish(bad, 0);
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  arm.send_commands(ArmCommands{}, TimePoint{}, 1ms);
  EXPECT_EQ(arm.rejected_force_samples(), 1U);
  EXPECT_TRUE(arm.operator_wrench().isZero());
}

TEST(HandModel, PullsTowardsTheMovingAnchorAndDampsTheRelativeSpeed) {
  HandModel hand;
  hand.anchor = Vector3d(0.5, 0.0, 0.2);
  hand.anchor_velocity = Vector3d(0.1, 0.0, 0.0);
  hand.stiffness = 400.0;
  hand.damping = 10.0;
  // 10 ms after the sample the anchor is 1 mm further along x.
  const Vector3d f = hand.force(Vector3d(0.5, 0.01, 0.2), Vector3d(0.0, 0.0, 0.3), 0.01);
  EXPECT_NEAR(f.x(), 400.0 * 0.001 + 10.0 * 0.1, 1e-9);
  EXPECT_NEAR(f.y(), -400.0 * 0.01, 1e-9);
  EXPECT_NEAR(f.z(), -10.0 * 0.3, 1e-9);
  EXPECT_FALSE(HandModel{}.gripping());
}

TEST(HandModel, TheWristTurnsTowardsItsRotationAndDampsTheTurning) {
  HandModel hand;
  hand.angular_stiffness = 2.0;
  hand.angular_damping = 0.05;
  EXPECT_TRUE(hand.gripping());
  // The handle turned 0.1 rad about z from the wrist's rotation, turning on at 1 rad/s about x.
  const Matrix3d turned = Eigen::AngleAxisd(0.1, Vector3d::UnitZ()).toRotationMatrix();
  const Vector3d t = hand.torque(turned, Vector3d(1.0, 0.0, 0.0));
  EXPECT_NEAR(t.z(), -2.0 * 0.1, 1e-9);
  EXPECT_NEAR(t.x(), -0.05, 1e-9);
  EXPECT_NEAR(t.y(), 0.0, 1e-12);
}

TEST_F(ArmSimulatorTest, AWristHoldsTheHandlesRotationAgainstATorque) {
  // Motors off, no brakes: a hand (1000 N/m) and the firmest wrist the force region accepts
  // (30 N.m/rad, 1 N.m.s/rad) hold the handle where it was while 0.2 N.m turns it about x: it
  // turns by the torque over the wrist's stiffness (the arm's own weight adds its share) and
  // comes to rest; without the wrist the same torque turns it on.
  const auto turned_by = [this](double wrist_k, double wrist_b) {
    ArmSimulator sim(dynamics_, SimulatorOptions{}, kReady);
    HandModel hand;
    hand.anchor = sim.chain().handle_position;
    hand.stiffness = 1000.0;
    hand.damping = 20.0;
    hand.anchor_rotation = sim.chain().handle_rotation;
    hand.angular_stiffness = wrist_k;
    hand.angular_damping = wrist_b;
    const Vector6d torque = (Vector6d() << 0, 0, 0, 0.2, 0, 0).finished();
    double fastest_late = 0.0;
    for (int k = 0; k < 3000; ++k) {
      sim.step(Vector6d::Zero(), torque, 1e-3, false, hand);
      if (k >= 2000) {
        fastest_late = std::max(fastest_late, sim.velocity().norm());
      }
    }
    const Eigen::AngleAxisd turn(hand.anchor_rotation.transpose() * sim.chain().handle_rotation);
    return std::pair{turn.angle(), fastest_late};
  };
  const auto [held, held_speed] = turned_by(30.0, 1.0);
  EXPECT_LT(held, 0.03) << "0.2 N.m / 30 N.m/rad = 0.0067 rad, plus the arm's own weight";
  EXPECT_LT(held_speed, 0.01) << "at rest, not ringing";
  const auto [free, free_speed] = turned_by(0.0, 0.0);
  EXPECT_GT(free, 5.0 * held) << "without a wrist the torque turns the handle on";
  (void)free_speed;
}

TEST_F(ArmSimulatorTest, AHandHoldsTheUnpoweredButReleasedArmNearItsAnchor) {
  // Motors off but no brakes (the pure simulator): gravity pulls the handle down, the hand
  // (1000 N/m) holds it where its anchor is, within the sag weight / stiffness, and the wrench
  // the arm reports as the operator's is the hand's.
  ArmSimulator sim(dynamics_, SimulatorOptions{}, kReady);
  HandModel hand;
  hand.anchor = sim.chain().handle_position;
  hand.stiffness = 1000.0;
  hand.damping = 20.0;
  for (int k = 0; k < 3000; ++k) {
    sim.step(Vector6d::Zero(), Vector6d::Zero(), 1e-3, false, hand);
  }
  const double sag = (sim.chain().handle_position - hand.anchor).norm();
  EXPECT_GT(sag, 1e-4);
  EXPECT_LT(sag, 0.05);
  EXPECT_GT(sim.operator_applied().z(), 0.5);  // the hand holds the arm up
  EXPECT_LT(sim.velocity().norm(), 0.05);
}

TEST_F(ArmSimulatorTest, TheOperatorWrenchIsSaturatedAndRateLimitedWhateverTheRegionSays) {
  // H3: a writer that skips the HMI's ramp (a wrench of 100 N per axis written at once), or a
  // hand anchored a metre away, reaches the handle at 500 N/s at most and never beyond 100 N
  // per axis; torques at 50 N.m/s.
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  arm.set_supply(true);
  ArmCommands hold;
  hold.enable = true;
  shm::ForcePayload blow;
  blow.wrench = {100, -100, 0, 0, 0, 10};
  force->publish(blow, 0);
  Vector6d before = Vector6d::Zero();
  for (int k = 0; k < 20; ++k) {
    arm.send_commands(hold, TimePoint{}, 1ms);
    const Vector6d now = arm.operator_wrench();
    EXPECT_LE((now - before).head<3>().cwiseAbs().maxCoeff(), 0.5 + 1e-9) << "cycle " << k;
    EXPECT_LE((now - before).tail<3>().cwiseAbs().maxCoeff(), 0.05 + 1e-9) << "cycle " << k;
    before = now;
  }
  EXPECT_NEAR(arm.operator_wrench()(0), 10.0, 1e-9) << "20 ms at 500 N/s";

  auto hand_force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm held(dynamics_, SimulatorOptions{}, kReady, hand_force.get());
  held.set_supply(true);
  shm::ForcePayload far;
  const Vector3d p = held.simulator().chain().handle_position;
  far.hand.anchor = {p.x() + 1.0, p.y(), p.z()};  // 3000 N/m x 1 m: 3000 N asked
  far.hand.stiffness = 3000.0;
  hand_force->publish(far, 0);
  double largest = 0.0;
  for (int k = 0; k < 400; ++k) {
    held.send_commands(hold, TimePoint{}, 1ms);
    largest = std::max(largest, held.operator_wrench()(0));
    ASSERT_LE(held.operator_wrench()(0), 0.5 * (k + 1) + 1e-9);
  }
  EXPECT_LE(largest, 100.0 + 1e-9);
  EXPECT_GT(largest, 50.0);
}

TEST_F(ArmSimulatorTest, TheSimulatedArmReadsTheHandAndRefusesOneOutOfRange) {
  auto force = std::make_unique<shm::SeqlockCell<shm::ForcePayload>>();
  SimulatedArm arm(dynamics_, SimulatorOptions{}, kReady, force.get());
  arm.set_supply(true);
  ArmCommands hold;
  hold.enable = true;  // zero torque: gravity pulls, the hand holds
  shm::ForcePayload grip;
  const Vector3d start = arm.simulator().chain().handle_position;
  grip.hand.anchor = {start.x(), start.y(), start.z()};
  grip.hand.stiffness = 800.0;
  grip.hand.damping = 15.0;
  force->publish(grip, 0);
  for (int k = 0; k < 2000; ++k) {
    arm.send_commands(hold, TimePoint{}, 1ms);
  }
  EXPECT_LT((arm.simulator().chain().handle_position - start).norm(), 0.05);
  EXPECT_GT(arm.operator_wrench()(2), 0.5);
  ArmMeasures m;
  arm.get_measures(m);
  EXPECT_DOUBLE_EQ(m.operator_wrench(2), arm.operator_wrench()(2));

  shm::ForcePayload bad = grip;
  bad.hand.stiffness = 1e6;
  force->publish(bad, 0);
  arm.send_commands(hold, TimePoint{}, 1ms);
  EXPECT_EQ(arm.rejected_force_samples(), 1U);
  EXPECT_GT(arm.operator_wrench()(2), 0.5) << "the last valid hand keeps holding";
}

}  // namespace
}  // namespace hapticctrl::rt_core
