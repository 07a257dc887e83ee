// Proves the armed cycle allocates nothing: a counting global operator new is active while the
// executive runs (CLOCK + SERVO + degraded SERVO + simulator + region exchanges).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <memory>
#include <new>

#include "hapticctrl/rt_core/arm_simulator.hpp"
#include "hapticctrl/rt_core/executive.hpp"
#include "support/allocation_counter.hpp"
#include "support/default_dynamics.hpp"
#include "support/in_memory_regions.hpp"
#include "support/scripted_servo_tasks.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

TEST(NoAllocation, CounterSeesAllocations) {
  test::allocations = 0;
  test::counting = true;
  auto probe = std::make_unique<int>(3);
  test::counting = false;
  EXPECT_EQ(test::allocations.load(), 1U) << "the counter works, so a zero below means something";
}

/// Two seconds of armed cycles at 1 kHz with `client` in VPr and an operator's push; every 50th
/// cycle overruns, so degraded cycles and discarded late commits are exercised too.
void expect_no_allocation(const shm::VprPayload& client) {
  constexpr Duration kPeriod = 1ms;
  FakeClock clock;
  test::InMemoryRegions regions;
  shm::ForcePayload push;
  push.wrench[0] = 2.0;
  regions.force->publish(push, 0);
  regions.vpr->publish(client, 0);
  const Vector6d ready = (Vector6d() << 0, -0.6, 1.2, 0, -0.6, 0).finished();
  SimulatedArm arm(test::default_dynamics(), SimulatorOptions{}, ready, regions.force.get());
  ServoShared shared(arm, regions.ctrl_reader(), regions.servo_regions(), true);
  ServoTask main_task(shared, TaskRole::kMain, ServoLaw(test::default_dynamics()));
  ServoTask degraded_task(shared, TaskRole::kDegraded, ServoLaw(test::default_dynamics()));
  test::ScriptedServoTasks tasks(
      clock, main_task, degraded_task, shared.overrun, kPeriod,
      [=](std::uint64_t c) { return c % 50 == 0 ? kPeriod * 3 / 2 : Duration{100us}; });
  BlackBox box(2000);
  ExecutiveConfig config;
  config.period = kPeriod;
  config.duration = 2s;
  config.telemetry_every = 10;
  Executive executive(config, clock, tasks, shared, arm,
                      ExecutiveOutputs{nullptr, regions.telemetry.get(), regions.position.get()},
                      box);
  regions.ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);

  test::allocations = 0;
  test::counting = true;
  const ExecutiveResult result = executive.run();
  test::counting = false;

  EXPECT_EQ(result.reason, shm::StopReason::kDurationElapsed);
  EXPECT_GT(executive.cycles(), 1900U);
  EXPECT_GT(executive.telemetry().degraded_cycles, 0U);
  EXPECT_GT(executive.telemetry().late_servo_discarded, 0U);
  EXPECT_EQ(test::allocations.load(), 0U);
}

TEST(NoAllocation, ArmedCyclesAllocateNothing) {
  shm::VprPayload client;
  client.session_id = 1;
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kVirtmech);
  client.flags = shm::vpr_flags::kObjectAttached;
  client.object_pose = {0.63, 0.02, 0.2, 0, 0, 0, 1};
  client.object_twist = {0.01, 0, 0, 0, 0, 0.1};
  client.object_mass = 0.3;
  client.client_time_step = 1e-3;
  expect_no_allocation(client);
}

TEST(NoAllocation, ArmedJointSpaceCyclesAllocateNothing) {
  shm::VprPayload client;
  client.session_id = 1;
  client.flags = shm::vpr_flags::kJointCommand;
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kArticular);
  client.joint_target = {0.2, -0.5, 1.1, 0.5, -0.4, 0.6};
  expect_no_allocation(client);
  client.command_type = static_cast<std::uint32_t>(shm::CommandType::kArticularImpedance);
  client.joint_torque = {1, -1, 0.5, 0.1, 0, -0.1};
  expect_no_allocation(client);
}

}  // namespace
}  // namespace hapticctrl::rt_core
