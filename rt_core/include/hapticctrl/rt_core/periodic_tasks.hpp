#pragma once
/// @file periodic_tasks.hpp
/// The periodic-task manager (the seeds' "horloge"): tasks added with a period that is a
/// multiple of the CLOCK's base tick, a normal and a degraded function (run by TaskRunners:
/// threads in the core, scripted in tests) and a deadline; activated, forced to run once,
/// stopped and restarted. The CLOCK (Executive) drives it once per tick: release_due() at the
/// tick, check_deadlines() at its check point. It reads no clock: every time comes in.
///
/// Per release: the normal function runs unless it is still busy with an older release, then the
/// degraded function takes it (a task without one misses it); a task with a CycleGate has the
/// release's cycle granted first, so a late normal execution can no longer commit. A release is
/// judged at the first check at or after its deadline: good when the normal function finished it
/// by then, a miss otherwise (late, degraded, or not run); each task has its own DeadlineMonitor.
///
/// Real-time contract: add() is setup (it may throw); every other member is noexcept, allocates
/// nothing and makes no syscall but the runners' wake-ups; safe in the cycle. stop_runners() is
/// the exception: it joins threads (fail-safe step 4).

#include <array>
#include <cstddef>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/cycle_gate.hpp"
#include "hapticctrl/rt_core/deadline_monitor.hpp"

namespace hapticctrl::rt_core {

/// Which of a task's two functions: the normal one or the degraded one that takes a release
/// the normal one is still busy with.
enum class TaskRole : std::uint8_t { kMain, kDegraded };

/// Runs a task's normal and degraded functions (threads in the process, a scripted fake in tests).
class TaskRunners {
 public:
  virtual ~TaskRunners() = default;
  /// Releases `role` for `cycle` (its gate, if any, was granted just before). Safe in the cycle.
  HAPTICCTRL_RT virtual void release(TaskRole role, std::uint64_t cycle,
                                     TimePoint release_time) noexcept = 0;
  /// True while `role` has not finished the last cycle released to it.
  HAPTICCTRL_RT virtual bool busy(TaskRole role) noexcept = 0;
  /// Start time of the last cycle released to `role`, kNotYet if it has not started.
  HAPTICCTRL_RT virtual TimePoint started_at(TaskRole role) noexcept = 0;
  /// When `role` finished `cycle` (everything the function does, its outputs included), or
  /// kNotYet if it has not finished that cycle.
  HAPTICCTRL_RT virtual TimePoint finished_at(TaskRole role, std::uint64_t cycle) noexcept = 0;
  /// Stops and joins the runners. Not for the cycle.
  virtual void stop() noexcept = 0;
};

/// A task as it is added.
struct PeriodicTaskSpec {
  TaskRunners* runners = nullptr;     ///< required
  bool has_degraded = true;           ///< a busy normal function hands its release to it
  std::uint32_t period_multiple = 1;  ///< released every this many base ticks (>= 1)
  CycleGate* gate = nullptr;          ///< granted each release's cycle first (optional)
  /// Judged this long after the release's scheduled tick (0: 3/4 of the task's period).
  Duration deadline{0};
  ChronicMissConfig chronic;
};

enum class TaskState : std::uint8_t { kAdded, kActive, kStopped };

/// One release and how it went.
struct TaskRelease {
  std::uint64_t cycle = 0;  ///< the base tick it was released at (0: none yet)
  TaskRole role = TaskRole::kMain;
  bool ran = false;              ///< a function was released (false: both busy, or gate held)
  TimePoint scheduled;           ///< its tick's scheduled time
  TimePoint released;            ///< when it was released
  TimePoint started = kNotYet;   ///< the normal function's start (kNotYet: not at the check)
  TimePoint finished = kNotYet;  ///< the normal function's end (kNotYet: not by the check)
  TimePoint checked = kNotYet;   ///< when it was judged
  MonitorVerdict verdict = MonitorVerdict::kGood;
};

using TaskId = std::size_t;

class PeriodicTasks {
 public:
  static constexpr std::size_t kMaxTasks = 8;

  /// `base_period`: the CLOCK's tick.
  explicit PeriodicTasks(Duration base_period) noexcept : base_period_(base_period) {}

  /// Adds a task (state kAdded: not released until activated). Setup: throws
  /// std::invalid_argument for no runners or a multiple of 0, std::length_error beyond kMaxTasks.
  TaskId add(const PeriodicTaskSpec& spec);

  /// Released from its next due tick on.
  void activate(TaskId id) noexcept;
  /// Released once at the next tick, due or not, active or not.
  void force(TaskId id) noexcept;
  /// Not released any more; an execution under way finishes; its last release is not judged.
  void stop(TaskId id) noexcept;
  /// Its deadline record starts afresh, then it is activated.
  void restart(TaskId id) noexcept;
  [[nodiscard]] TaskState state(TaskId id) const noexcept { return tasks_[id].state; }

  /// CLOCK, at base tick `tick` (scheduled at `scheduled`, now `now`): releases every task due
  /// (tick % multiple == 0, or forced).
  HAPTICCTRL_RT void release_due(std::uint64_t tick, TimePoint scheduled, TimePoint now) noexcept;
  /// CLOCK, at `now`: judges every release whose deadline has passed. Returns the most severe
  /// verdict (fail-safe, chronic misses, miss, good).
  HAPTICCTRL_RT MonitorVerdict check_deadlines(TimePoint now) noexcept;
  /// CLOCK: `count` ticks were skipped (a late wake-up). Each is a miss for every active task
  /// released at every tick; a task with a longer period is judged by its next release.
  MonitorVerdict skip(std::uint32_t count) noexcept;

  /// The task's last release (judged or not).
  [[nodiscard]] HAPTICCTRL_RT const TaskRelease& last_release(TaskId id) const noexcept {
    return tasks_[id].last;
  }
  [[nodiscard]] HAPTICCTRL_RT const DeadlineMonitor& monitor(TaskId id) const noexcept {
    return tasks_[id].monitor;
  }
  /// Releases handed to the degraded function.
  [[nodiscard]] HAPTICCTRL_RT std::uint64_t degraded_releases(TaskId id) const noexcept {
    return tasks_[id].degraded_releases;
  }
  /// Stops every task's runners (joins their threads). Not for the cycle.
  void stop_runners() noexcept;

 private:
  struct Task {
    PeriodicTaskSpec spec;
    TaskState state = TaskState::kAdded;
    bool forced = false;
    bool pending_check = false;  ///< `last` awaits its judgement
    TaskRelease last;
    DeadlineMonitor monitor{ChronicMissConfig{}};
    std::uint64_t degraded_releases = 0;
  };

  HAPTICCTRL_RT void release(Task& task, std::uint64_t tick, TimePoint scheduled,
                             TimePoint now) noexcept;
  HAPTICCTRL_RT static MonitorVerdict judge(Task& task, TimePoint now) noexcept;
  HAPTICCTRL_RT static MonitorVerdict worse(MonitorVerdict a, MonitorVerdict b) noexcept;

  Duration base_period_;
  std::array<Task, kMaxTasks> tasks_;
  std::size_t count_ = 0;
};

}  // namespace hapticctrl::rt_core
