// The real task threads with the real clock, run briefly (no timing assertions).
#include "hapticctrl/rt_core/threaded_servo_tasks.hpp"

#include <gtest/gtest.h>

#include <memory>

#include "support/default_dynamics.hpp"
#include "support/in_memory_regions.hpp"
#include "support/mock_arm.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

struct ThreadRig {
  test::MockArm arm;
  test::InMemoryRegions regions;
  ServoShared shared{arm, regions.ctrl_reader(), ServoRegions{nullptr, regions.vp.get(), nullptr},
                     true};
  ServoTask main_task{shared, TaskRole::kMain, ServoLaw(test::default_dynamics())};
  ServoTask degraded_task{shared, TaskRole::kDegraded, ServoLaw(test::default_dynamics())};
  RealClock clock;
};

bool wait_idle(ThreadedServoTasks& tasks, TaskRole role) {
  for (int i = 0; i < 5000; ++i) {
    if (!tasks.busy(role)) {
      return true;
    }
    std::this_thread::sleep_for(std::chrono::microseconds(200));
  }
  return false;
}

TEST(ThreadedServoTasks, ReleasedCyclesRunAndCommit) {
  ThreadRig rig;
  ThreadedServoTasks tasks(rig.clock, rig.main_task, rig.degraded_task, rig.shared.overrun, 1ms, {},
                           {});
  for (std::uint64_t k = 1; k <= 20; ++k) {
    ASSERT_TRUE(rig.shared.gate.grant(k));
    tasks.release(TaskRole::kMain, k, rig.clock.now());
    ASSERT_TRUE(wait_idle(tasks, TaskRole::kMain)) << "cycle " << k;
    EXPECT_NE(tasks.started_at(TaskRole::kMain), kNotYet);
    EXPECT_EQ(rig.shared.to_clock.commit_cycle.load(), k);
    EXPECT_GE(tasks.finished_at(TaskRole::kMain, k), tasks.started_at(TaskRole::kMain))
        << "timed after the commit, arm commands included";
    EXPECT_EQ(tasks.finished_at(TaskRole::kMain, k + 1), kNotYet) << "not finished yet";
  }
  tasks.stop();
}

TEST(ThreadedServoTasks, InjectedOverrunKeepsMainBusyWhileDegradedCommits) {
  ThreadRig rig;
  ThreadedServoTasks tasks(rig.clock, rig.main_task, rig.degraded_task, rig.shared.overrun, 1ms, {},
                           {});
  rig.shared.overrun.request(20);  // ~20 ms stall
  ASSERT_TRUE(rig.shared.gate.grant(1));
  tasks.release(TaskRole::kMain, 1, rig.clock.now());
  std::this_thread::sleep_for(std::chrono::milliseconds(2));
  EXPECT_TRUE(tasks.busy(TaskRole::kMain));
  ASSERT_TRUE(rig.shared.gate.grant(2));
  tasks.release(TaskRole::kDegraded, 2, rig.clock.now());
  ASSERT_TRUE(wait_idle(tasks, TaskRole::kDegraded));
  EXPECT_EQ(rig.shared.to_clock.commit_cycle.load(), 2U);
  ASSERT_TRUE(wait_idle(tasks, TaskRole::kMain));
  EXPECT_EQ(rig.shared.to_clock.counters.late_discarded.load(), 1U);
  EXPECT_EQ(rig.shared.to_clock.commit_cycle.load(), 2U)
      << "the late main cycle 1 did not overwrite 2";
  tasks.stop();
}

TEST(ThreadedServoTasks, StopJoinsPromptly) {
  ThreadRig rig;
  auto tasks = std::make_unique<ThreadedServoTasks>(rig.clock, rig.main_task, rig.degraded_task,
                                                    rig.shared.overrun, 1ms, ThreadPlacement{},
                                                    ThreadPlacement{});
  const auto start = std::chrono::steady_clock::now();
  tasks->stop();
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(2));
}

}  // namespace
}  // namespace hapticctrl::rt_core
