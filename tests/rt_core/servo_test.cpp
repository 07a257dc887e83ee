// Tests of servo.hpp: the SERVO task's steps (docs/rt_core.md, *The cycle*): read measures, build
// the logical state from ctrl, exchange with the protocol regions, run the law, send commands,
// publish VP and position.
#include "hapticctrl/rt_core/servo.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "support/default_dynamics.hpp"
#include "support/in_memory_regions.hpp"
#include "support/mock_arm.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::MockArm;

struct ServoRig {
  MockArm arm;
  test::InMemoryRegions regions;
  std::unique_ptr<shm::SeqlockCell<shm::VprPayload>>& vpr = regions.vpr;
  std::unique_ptr<shm::SeqlockCell<shm::VpPayload>>& vp = regions.vp;
  ServoShared shared{arm, regions.ctrl_reader(), regions.servo_regions(), false};
  ServoTask main_task{shared, TaskRole::kMain, ServoLaw(test::default_dynamics())};
  ServoTask degraded_task{shared, TaskRole::kDegraded, ServoLaw(test::default_dynamics())};
  shm::CtrlWriter writer = regions.ctrl_writer();

  StepResult cycle(ServoTask& task, std::uint64_t k) {
    shared.gate.grant(k);
    return task.run(k, TimePoint{k * 1ms}, 1ms);
  }
  shm::VpPayload last_vp() {
    shm::VpPayload out;
    EXPECT_TRUE(vp->read(out).ok());
    return out;
  }
};

TEST(Servo, MotorCommandsStayInhibitedUntilPowerOn) {
  ServoRig rig;
  rig.arm.measures.velocity.setConstant(1.0);
  ASSERT_EQ(rig.cycle(rig.main_task, 1), StepResult::kDone);
  EXPECT_FALSE(rig.arm.last.enable);
  EXPECT_TRUE(rig.arm.last.torque.isZero());
  EXPECT_FALSE(rig.arm.supply);

  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);
  ASSERT_EQ(rig.cycle(rig.main_task, 2), StepResult::kDone);
  EXPECT_TRUE(rig.arm.supply) << "power-on switches the supply at once";
  EXPECT_TRUE(rig.arm.last.enable);
  EXPECT_LT(rig.arm.last.torque(0), 0.0) << "damping opposes the motion";
  EXPECT_NE(rig.last_vp().state_word & shm::state_bits::kPowered, 0U);
}

TEST(Servo, EmergencyStopCutsPowerAndLatches) {
  ServoRig rig;
  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);
  rig.cycle(rig.main_task, 1);
  rig.writer.send(shm::CtrlCode::kEmergencyStop, 0, 0);
  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);  // refused while latched
  rig.cycle(rig.main_task, 2);
  EXPECT_FALSE(rig.arm.supply);
  EXPECT_FALSE(rig.arm.last.enable);
  EXPECT_NE(rig.last_vp().state_word & shm::state_bits::kEmergencyStop, 0U);
  EXPECT_EQ(rig.shared.to_clock.counters.ctrl_rejected.load(), 1U);
}

TEST(Servo, VpEchoesTheClientAndCarriesTheCycle) {
  ServoRig rig;
  shm::VprPayload client;
  client.session_id = 9;
  client.client_sequence = 1234;
  client.client_time_ns = 5678;
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kImpedance);
  rig.vpr->publish(client, 0);
  rig.cycle(rig.main_task, 7);
  const shm::VpPayload vp = rig.last_vp();
  EXPECT_EQ(vp.cycle, 7U);
  EXPECT_EQ(vp.echo_client_sequence, 1234U);
  EXPECT_EQ(vp.echo_client_time_ns, 5678);
  EXPECT_EQ(vp.command_type, static_cast<std::uint32_t>(shm::CommandType::kImpedance));
}

TEST(Servo, NonFiniteClientSampleIsRejectedAndCounted) {
  ServoRig rig;
  shm::VprPayload good;
  good.session_id = 1;
  good.client_sequence = 1;
  rig.vpr->publish(good, 0);
  rig.cycle(rig.main_task, 1);
  shm::VprPayload bad = good;
  bad.client_sequence = 2;
  bad.object_pose[0] = std::numeric_limits<double>::quiet_NaN();
  rig.vpr->publish(bad, 0);
  rig.cycle(rig.main_task, 2);
  EXPECT_EQ(rig.shared.to_clock.counters.vpr_rejected.load(), 1U);
  EXPECT_EQ(rig.last_vp().echo_client_sequence, 1U) << "the last valid sample stays in use";
}

TEST(Servo, ClientFrameThatIsNotARotationIsRejected) {
  ServoRig rig;
  shm::VprPayload bad;
  bad.session_id = 1;
  bad.client_sequence = 1;
  bad.base_frame = {0, 0, 0, 0, 0, 0, 0};  // zero quaternion
  rig.vpr->publish(bad, 0);
  rig.cycle(rig.main_task, 1);
  EXPECT_EQ(rig.shared.to_clock.counters.vpr_rejected.load(), 1U);
  EXPECT_EQ(rig.last_vp().echo_client_sequence, 0U) << "never used";
}

TEST(Servo, StaleClientIsFlagged) {
  ServoRig rig;
  shm::VprPayload client;
  client.session_id = 1;
  rig.vpr->publish(client, 0);
  rig.cycle(rig.main_task, 1);
  rig.cycle(rig.main_task, 10);  // 9 ms later, no new sample
  EXPECT_NE(rig.last_vp().state_word & shm::state_bits::kClientStale, 0U);
  EXPECT_GT(rig.shared.to_clock.counters.vpr_stale.load(), 0U);
}

TEST(Servo, LateMainCommitAfterDegradedIsDiscarded) {
  ServoRig rig;
  rig.shared.gate.grant(5);
  ASSERT_EQ(rig.main_task.begin(5, TimePoint{}, 1ms), StepResult::kDone);
  ASSERT_EQ(rig.cycle(rig.degraded_task, 6), StepResult::kDone);
  EXPECT_NE(rig.last_vp().state_word & shm::state_bits::kDegraded, 0U);
  const int sends_before = rig.arm.sends;
  EXPECT_EQ(rig.main_task.finish(5, TimePoint{}), StepResult::kDiscarded);
  EXPECT_EQ(rig.arm.sends, sends_before) << "nothing reached the arm";
  EXPECT_EQ(rig.last_vp().cycle, 6U);
  EXPECT_EQ(rig.shared.to_clock.counters.late_discarded.load(), 1U);
}

TEST(Servo, MainAndDegradedServoContinueOneRateLimitedWrench) {
  ServoRig rig;
  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);
  shm::VprPayload client;
  client.session_id = 1;
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kImpedance);
  client.impedance_wrench = {30.0, 0, 0, 0, 0, 0};
  const double limit = test::default_dynamics().model().limits.force_rate * 1e-3;  // per 1 ms
  double previous = 0.0;
  double largest_step = 0.0;
  double largest = 0.0;
  for (std::uint64_t k = 1; k <= 240; ++k) {
    client.client_sequence = static_cast<std::uint32_t>(k);
    rig.vpr->publish(client, to_ns(k * 1ms));
    // After the 150 ms engagement ramp, every other cycle is the degraded SERVO's (it renders
    // no coupling).
    ServoTask& task = (k >= 170 && k % 2 == 0) ? rig.degraded_task : rig.main_task;
    ASSERT_EQ(rig.cycle(task, k), StepResult::kDone);
    shm::PositionPayload p;
    ASSERT_TRUE(rig.regions.position->read(p).ok());
    largest_step = std::max(largest_step, std::abs(p.rendered_wrench[0] - previous));
    largest = std::max(largest, p.rendered_wrench[0]);
    previous = p.rendered_wrench[0];
  }
  EXPECT_GT(largest, 10.0) << "the impedance wrench ramped up";
  EXPECT_LE(largest_step, limit + 1e-9) << "whichever SERVO renders, the wrench never steps";
}

TEST(Servo, InhibitFlagOverridesPower) {
  ServoRig rig;
  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);
  rig.shared.from_clock.inhibit_commands();
  rig.cycle(rig.main_task, 1);
  EXPECT_FALSE(rig.arm.last.enable);
}

TEST(Servo, TheLawSeesTheSampleConvertedAtTheEdge) {
  ServoRig rig;
  rig.writer.send(shm::CtrlCode::kPowerOn, 0, 0);
  rig.cycle(rig.main_task, 1);
  shm::PositionPayload handle;
  ASSERT_TRUE(rig.regions.position->read(handle).ok());
  shm::VprPayload client;
  client.session_id = 7;
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kVirtmech);
  client.flags = shm::vpr_flags::kObjectAttached;
  client.object_pose = handle.handle_pose;
  client.object_pose[0] += 0.01;  // 1 cm along x: the coupling pulls the handle that way
  client.object_mass = 0.5;
  client.client_time_step = 1e-3;
  std::uint64_t k = 2;
  for (; k <= 200; ++k) {
    client.client_sequence = k;
    rig.vpr->publish(client, to_ns(k * 1ms));
    rig.cycle(rig.main_task, k);
  }
  shm::VpPayload vp = rig.last_vp();
  EXPECT_NE(vp.state_word & shm::state_bits::kCoupled, 0U) << "VIRTMECH with an object couples";
  EXPECT_LT(vp.object_wrench[0], 0.0) << "the object is pulled back towards the handle (-x)";
  EXPECT_EQ(rig.shared.to_clock.committed_session.load(), 7U);

  client.flags = 0;  // the object detached: the same sample without the flag
  for (const std::uint64_t last = k + 50; k <= last; ++k) {
    client.client_sequence = k;
    rig.vpr->publish(client, to_ns(k * 1ms));
    rig.cycle(rig.main_task, k);
  }
  EXPECT_EQ(rig.last_vp().state_word & shm::state_bits::kCoupled, 0U) << "no object, no coupling";
}

TEST(Servo, WhatTheClockAnnouncesReachesTheNextPublish) {
  ServoRig rig;
  rig.cycle(rig.main_task, 1);
  EXPECT_EQ(rig.last_vp().core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));
  rig.shared.from_clock.add_state_bits(shm::state_bits::kStopping);
  rig.shared.from_clock.announce(shm::CoreState::kStopping, shm::StopReason::kSignal);
  rig.cycle(rig.main_task, 2);
  const shm::VpPayload vp = rig.last_vp();
  EXPECT_EQ(vp.core_state, static_cast<std::uint32_t>(shm::CoreState::kStopping));
  EXPECT_EQ(vp.stop_reason, static_cast<std::uint32_t>(shm::StopReason::kSignal));
  EXPECT_NE(vp.state_word & shm::state_bits::kStopping, 0U);
  EXPECT_EQ(rig.shared.to_clock.committed_state_word.load(), vp.state_word);
}

TEST(Servo, ArmReadFaultIsCounted) {
  ServoRig rig;
  rig.arm.fail_reads = true;
  rig.cycle(rig.main_task, 1);
  EXPECT_EQ(rig.shared.to_clock.counters.arm_faults.load(), 1U);
}

}  // namespace
}  // namespace hapticctrl::rt_core
