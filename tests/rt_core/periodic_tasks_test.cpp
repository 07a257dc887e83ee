// The periodic-task manager against scripted runners and a fake clock's times: which tick
// releases what, the degraded function, the gate, the deadline verdicts, and activate, force,
// stop and restart.
#include "hapticctrl/rt_core/periodic_tasks.hpp"

#include <gtest/gtest.h>

#include <array>
#include <stdexcept>
#include <vector>

#include "hapticctrl/rt_core/clock.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

constexpr Duration kTick = 1ms;

/// The moment `since` after the clock's origin.
constexpr TimePoint at(Duration since) {
  return TimePoint{since};
}

/// Runners whose functions finish when the test says so.
class ScriptedRunners final : public TaskRunners {
 public:
  struct Release {
    TaskRole role;
    std::uint64_t cycle;
    TimePoint time;
  };

  void release(TaskRole role, std::uint64_t cycle, TimePoint release_time) noexcept override {
    releases.push_back({role, cycle, release_time});
    Function& f = function(role);
    f.cycle = cycle;
    f.busy = true;
    f.started = release_time + 10us;
  }
  bool busy(TaskRole role) noexcept override { return function(role).busy; }
  TimePoint started_at(TaskRole role) noexcept override { return function(role).started; }
  TimePoint finished_at(TaskRole role, std::uint64_t cycle) noexcept override {
    const Function& f = function(role);
    return !f.busy && f.cycle == cycle ? f.finished : kNotYet;
  }
  void stop() noexcept override { stopped = true; }

  /// The function `role` finishes its cycle at `at`.
  void finish(TaskRole role, TimePoint at) {
    function(role).busy = false;
    function(role).finished = at;
  }

  std::vector<Release> releases;
  bool stopped = false;

 private:
  struct Function {
    bool busy = false;
    std::uint64_t cycle = 0;
    TimePoint started = kNotYet;
    TimePoint finished = kNotYet;
  };
  Function& function(TaskRole role) { return functions_[role == TaskRole::kMain ? 0 : 1]; }
  std::array<Function, 2> functions_{};
};

/// Drives the manager the way the CLOCK does: tick k is scheduled at k ms, released at once,
/// checked at k + 3/4 ms; the normal function finishes 200 us after its release unless the
/// test holds it.
struct Rig {
  PeriodicTasks tasks{kTick};
  ScriptedRunners runners;
  bool hold_normal = false;

  TaskId add(std::uint32_t multiple, CycleGate* gate = nullptr) {
    return tasks.add({.runners = &runners, .period_multiple = multiple, .gate = gate});
  }
  MonitorVerdict tick(std::uint64_t k) {
    const TimePoint scheduled{k * kTick};
    tasks.release_due(k, scheduled, scheduled);
    if (!hold_normal && runners.busy(TaskRole::kMain)) {
      runners.finish(TaskRole::kMain, scheduled + 200us);
    }
    if (runners.busy(TaskRole::kDegraded)) {
      runners.finish(TaskRole::kDegraded, scheduled + 50us);
    }
    return tasks.check_deadlines(scheduled + kTick * 3 / 4);
  }
  std::vector<std::uint64_t> released_cycles() const {
    std::vector<std::uint64_t> cycles;
    for (const auto& r : runners.releases) {
      cycles.push_back(r.cycle);
    }
    return cycles;
  }
};

TEST(PeriodicTasks, ATaskIsReleasedOnlyOnceActivatedAndEveryMultipleOfTheTick) {
  Rig rig;
  const TaskId id = rig.add(3);
  EXPECT_EQ(rig.tasks.state(id), TaskState::kAdded);
  rig.tick(3);
  EXPECT_TRUE(rig.runners.releases.empty()) << "not active yet";
  rig.tasks.activate(id);
  for (std::uint64_t k = 4; k <= 13; ++k) {
    EXPECT_EQ(rig.tick(k), MonitorVerdict::kGood) << "tick " << k;
  }
  EXPECT_EQ(rig.released_cycles(), (std::vector<std::uint64_t>{6, 9, 12}));
  EXPECT_EQ(rig.tasks.monitor(id).cycles(), 2U)
      << "its deadline is 3/4 of its own period: tick 12's is judged at 14.25 ms";
  rig.tick(14);
  EXPECT_EQ(rig.tasks.monitor(id).cycles(), 3U) << "each release judged once";
}

TEST(PeriodicTasks, AForcedTaskRunsOnceAtTheNextTickDueOrNotActiveOrNot) {
  Rig rig;
  const TaskId id = rig.add(10);
  rig.tasks.force(id);
  rig.tick(1);
  rig.tick(2);
  EXPECT_EQ(rig.released_cycles(), (std::vector<std::uint64_t>{1})) << "once, though not active";
  rig.tasks.activate(id);
  rig.tasks.force(id);
  rig.tick(10);  // due and forced: one release
  EXPECT_EQ(rig.released_cycles(), (std::vector<std::uint64_t>{1, 10}));
}

TEST(PeriodicTasks, AStoppedTaskIsNotReleasedAndARestartedOneStartsAfresh) {
  Rig rig;
  const TaskId id = rig.add(1);
  rig.tasks.activate(id);
  rig.hold_normal = true;  // it overruns: misses
  rig.tick(1);
  rig.tick(2);
  EXPECT_EQ(rig.tasks.monitor(id).total_misses(), 2U);
  rig.tasks.stop(id);
  EXPECT_EQ(rig.tasks.state(id), TaskState::kStopped);
  rig.runners.finish(TaskRole::kMain, at(3 * kTick));
  rig.hold_normal = false;
  const std::size_t released = rig.runners.releases.size();
  rig.tick(3);
  EXPECT_EQ(rig.runners.releases.size(), released) << "stopped: nothing released";
  rig.tasks.restart(id);
  EXPECT_EQ(rig.tasks.state(id), TaskState::kActive);
  EXPECT_EQ(rig.tasks.monitor(id).total_misses(), 0U) << "its deadline record starts afresh";
  EXPECT_EQ(rig.tick(4), MonitorVerdict::kGood);
  EXPECT_EQ(rig.released_cycles().back(), 4U);
}

TEST(PeriodicTasks, ABusyNormalFunctionHandsTheReleaseToTheDegradedOneAndMisses) {
  Rig rig;
  const TaskId id = rig.add(1);
  rig.tasks.activate(id);
  EXPECT_EQ(rig.tick(1), MonitorVerdict::kGood);
  rig.hold_normal = true;
  EXPECT_EQ(rig.tick(2), MonitorVerdict::kMiss) << "the normal function overran";
  EXPECT_EQ(rig.tick(3), MonitorVerdict::kMiss) << "the degraded function ran it: still a miss";
  const TaskRelease& last = rig.tasks.last_release(id);
  EXPECT_EQ(last.role, TaskRole::kDegraded);
  EXPECT_TRUE(last.ran);
  EXPECT_EQ(rig.runners.releases.back().role, TaskRole::kDegraded);
  EXPECT_EQ(rig.tasks.degraded_releases(id), 1U);
}

TEST(PeriodicTasks, WithoutADegradedFunctionABusyTaskMissesTheRelease) {
  Rig rig;
  const TaskId id = rig.tasks.add({.runners = &rig.runners, .has_degraded = false});
  rig.tasks.activate(id);
  rig.hold_normal = true;
  rig.tick(1);
  rig.tick(2);
  EXPECT_EQ(rig.runners.releases.size(), 1U) << "nothing took tick 2";
  EXPECT_FALSE(rig.tasks.last_release(id).ran);
  EXPECT_EQ(rig.tasks.monitor(id).total_misses(), 2U);
}

TEST(PeriodicTasks, FiveConsecutiveMissesTripTheFailSafeAndAGoodReleaseResetsTheRun) {
  Rig rig;
  const TaskId id = rig.add(1);
  rig.tasks.activate(id);
  rig.hold_normal = true;
  for (std::uint64_t k = 1; k <= 4; ++k) {
    EXPECT_EQ(rig.tick(k), MonitorVerdict::kMiss) << "tick " << k;
  }
  rig.hold_normal = false;
  rig.runners.finish(TaskRole::kMain, at(5 * kTick));
  EXPECT_EQ(rig.tick(6), MonitorVerdict::kGood);
  rig.hold_normal = true;
  for (std::uint64_t k = 7; k <= 10; ++k) {
    EXPECT_EQ(rig.tick(k), MonitorVerdict::kMiss) << "tick " << k;
  }
  EXPECT_EQ(rig.tick(11), MonitorVerdict::kFailSafe);
  EXPECT_EQ(rig.tasks.monitor(id).consecutive_misses(), 5U);
}

TEST(PeriodicTasks, AFinishAfterTheCheckIsAMissAndAReleaseIsJudgedOnlyAtItsDeadline) {
  Rig rig;
  const TaskId id = rig.add(1);
  rig.tasks.activate(id);
  rig.tasks.release_due(1, at(kTick), at(kTick));
  EXPECT_EQ(rig.tasks.check_deadlines(at(kTick + kTick / 2)), MonitorVerdict::kGood);
  EXPECT_EQ(rig.tasks.last_release(id).checked, kNotYet) << "before its deadline: not judged";
  rig.runners.finish(TaskRole::kMain, at(kTick + kTick * 9 / 10));  // after the 3/4 check
  EXPECT_EQ(rig.tasks.check_deadlines(at(kTick + kTick * 3 / 4)), MonitorVerdict::kMiss);
  EXPECT_EQ(rig.tasks.last_release(id).checked, at(kTick + kTick * 3 / 4));
  EXPECT_EQ(rig.tasks.check_deadlines(at(2 * kTick)), MonitorVerdict::kGood) << "judged once";
}

TEST(PeriodicTasks, TheGateIsGrantedTheReleasesCycleAndAHeldGateStopsTheRelease) {
  Rig rig;
  CycleGate gate;
  const TaskId id = rig.add(1, &gate);
  rig.tasks.activate(id);
  rig.tick(1);
  EXPECT_TRUE(gate.enter(1)) << "cycle 1 was granted to the release";
  // Still inside at the next tick (a runner stuck in the gate): tick 2 cannot be granted.
  rig.tick(2);
  EXPECT_FALSE(rig.tasks.last_release(id).ran);
  EXPECT_EQ(rig.tasks.monitor(id).total_misses(), 1U);
  gate.leave(1);
  EXPECT_EQ(rig.tick(3), MonitorVerdict::kGood);
}

TEST(PeriodicTasks, SkippedTicksAreMissesForTasksOfOneTickOnly) {
  Rig rig;
  const TaskId every = rig.add(1);
  const TaskId slow = rig.add(4);
  rig.tasks.activate(every);
  rig.tasks.activate(slow);
  EXPECT_EQ(rig.tasks.skip(3), MonitorVerdict::kMiss);
  EXPECT_EQ(rig.tasks.monitor(every).total_misses(), 3U);
  EXPECT_EQ(rig.tasks.monitor(slow).total_misses(), 0U) << "judged by its next release";
  EXPECT_EQ(rig.tasks.skip(2), MonitorVerdict::kFailSafe) << "five in a row";
}

TEST(PeriodicTasks, BadTasksAreRefusedAtSetup) {
  PeriodicTasks tasks{kTick};
  ScriptedRunners runners;
  EXPECT_THROW(tasks.add({}), std::invalid_argument);
  EXPECT_THROW(tasks.add({.runners = &runners, .period_multiple = 0}), std::invalid_argument);
  for (std::size_t i = 0; i < PeriodicTasks::kMaxTasks; ++i) {
    tasks.add({.runners = &runners});
  }
  EXPECT_THROW(tasks.add({.runners = &runners}), std::length_error);
  tasks.stop_runners();
  EXPECT_TRUE(runners.stopped);
}

}  // namespace
}  // namespace hapticctrl::rt_core
