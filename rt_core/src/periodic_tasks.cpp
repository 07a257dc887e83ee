// Implements periodic_tasks.hpp: the periodic-task manager. Each task keeps its spec, its
// state, its last release and its own DeadlineMonitor in a fixed array (kMaxTasks), so releasing
// and judging allocate nothing; the functions themselves run in the task's TaskRunners.
#include "hapticctrl/rt_core/periodic_tasks.hpp"

#include <stdexcept>
#include <string>

namespace hapticctrl::rt_core {

TaskId PeriodicTasks::add(const PeriodicTaskSpec& spec) {
  if (spec.runners == nullptr) {
    throw std::invalid_argument("a periodic task needs runners for its functions");
  }
  if (spec.period_multiple == 0) {
    throw std::invalid_argument("a periodic task's period is a multiple (>= 1) of the base tick");
  }
  if (count_ == kMaxTasks) {
    throw std::length_error("at most " + std::to_string(kMaxTasks) + " periodic tasks");
  }
  Task& task = tasks_[count_];
  task.spec = spec;
  if (task.spec.deadline <= Duration{0}) {
    task.spec.deadline = base_period_ * spec.period_multiple * 3 / 4;
  }
  task.monitor = DeadlineMonitor(spec.chronic);
  return count_++;
}

void PeriodicTasks::activate(TaskId id) noexcept {
  tasks_[id].state = TaskState::kActive;
}

void PeriodicTasks::force(TaskId id) noexcept {
  tasks_[id].forced = true;
}

void PeriodicTasks::stop(TaskId id) noexcept {
  Task& task = tasks_[id];
  task.state = TaskState::kStopped;
  task.forced = false;
  task.pending_check = false;
}

void PeriodicTasks::restart(TaskId id) noexcept {
  Task& task = tasks_[id];
  task.monitor = DeadlineMonitor(task.spec.chronic);
  task.degraded_releases = 0;
  task.pending_check = false;
  task.last = TaskRelease{};
  activate(id);
}

void PeriodicTasks::release_due(std::uint64_t tick, TimePoint scheduled, TimePoint now) noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    Task& task = tasks_[i];
    const bool due = task.state == TaskState::kActive && tick % task.spec.period_multiple == 0;
    if (due || task.forced) {
      task.forced = false;
      release(task, tick, scheduled, now);
    }
  }
}

void PeriodicTasks::release(Task& task, std::uint64_t tick, TimePoint scheduled,
                            TimePoint now) noexcept {
  TaskRunners& runners = *task.spec.runners;
  TaskRelease& r = task.last;
  r = TaskRelease{};
  r.cycle = tick;
  r.scheduled = scheduled;
  r.released = now;
  // The normal function still busy with an older release: the degraded function takes this one.
  r.role = runners.busy(TaskRole::kMain) ? TaskRole::kDegraded : TaskRole::kMain;
  task.pending_check = true;
  if (r.role == TaskRole::kDegraded) {
    ++task.degraded_releases;
    if (!task.spec.has_degraded || runners.busy(TaskRole::kDegraded)) {
      return;  // nothing can run this release: a miss
    }
  }
  if (task.spec.gate != nullptr && !task.spec.gate->grant(tick)) {
    return;  // the previous holder is still inside: this release cannot run
  }
  runners.release(r.role, tick, now);
  r.ran = true;
}

MonitorVerdict PeriodicTasks::check_deadlines(TimePoint now) noexcept {
  MonitorVerdict verdict = MonitorVerdict::kGood;
  for (std::size_t i = 0; i < count_; ++i) {
    Task& task = tasks_[i];
    if (task.pending_check && now >= task.last.scheduled + task.spec.deadline) {
      verdict = worse(verdict, judge(task, now));
    }
  }
  return verdict;
}

MonitorVerdict PeriodicTasks::judge(Task& task, TimePoint now) noexcept {
  TaskRunners& runners = *task.spec.runners;
  TaskRelease& r = task.last;
  (void)runners.busy(TaskRole::kMain);  // lets a scripted runner catch up to `now`
  r.checked = now;
  const bool degraded = r.role == TaskRole::kDegraded;
  if (!degraded) {
    r.started = runners.started_at(TaskRole::kMain);
    r.finished = runners.finished_at(TaskRole::kMain, r.cycle);
  }
  CycleTimes times;
  times.scheduled = r.scheduled;
  times.released = r.released;
  times.started = r.started;
  times.finished = r.finished;
  times.checked = now;
  times.degraded = degraded;
  r.verdict = task.monitor.on_cycle(times);
  task.pending_check = false;
  return r.verdict;
}

MonitorVerdict PeriodicTasks::skip(std::uint32_t count) noexcept {
  MonitorVerdict verdict = MonitorVerdict::kGood;
  for (std::size_t i = 0; i < count_; ++i) {
    Task& task = tasks_[i];
    if (task.state == TaskState::kActive && task.spec.period_multiple == 1 && count > 0) {
      verdict = worse(verdict, task.monitor.on_skipped(count));
    }
  }
  return verdict;
}

MonitorVerdict PeriodicTasks::worse(MonitorVerdict a, MonitorVerdict b) noexcept {
  const auto rank = [](MonitorVerdict v) {
    switch (v) {
      case MonitorVerdict::kFailSafe:
        return 3;
      case MonitorVerdict::kChronicMisses:
        return 2;
      case MonitorVerdict::kMiss:
        return 1;
      case MonitorVerdict::kGood:
        break;
    }
    return 0;
  };
  return rank(b) > rank(a) ? b : a;
}

void PeriodicTasks::stop_runners() noexcept {
  for (std::size_t i = 0; i < count_; ++i) {
    tasks_[i].spec.runners->stop();
  }
}

}  // namespace hapticctrl::rt_core
