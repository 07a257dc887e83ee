#pragma once
/// ServoTasks for fake-clock tests: the real ServoTask objects run on the test thread, and the
/// duration of each main SERVO cycle is scripted. A task's commit happens "at" release + its
/// duration; it is executed lazily the next time the CLOCK looks (busy/started_at/release), which
/// preserves the order of events because the CLOCK is the only thing that moves fake time.

#include <functional>
#include <optional>

#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/executive.hpp"
#include "hapticctrl/rt_core/servo.hpp"

namespace hapticctrl::test {

class ScriptedServoTasks final : public rt_core::TaskRunners {
 public:
  using CycleLength = std::function<hapticctrl::Duration(std::uint64_t cycle)>;

  ScriptedServoTasks(rt_core::FakeClock& clock, rt_core::ServoTask& main_task,
                     rt_core::ServoTask& degraded_task, rt_core::OverrunInjection& overrun,
                     hapticctrl::Duration period, CycleLength main_duration)
      : clock_(&clock),
        overrun_(&overrun),
        period_(period),
        main_duration_(std::move(main_duration)),
        main_{&main_task},
        degraded_{&degraded_task} {}

  void release(rt_core::TaskRole role, std::uint64_t cycle,
               hapticctrl::TimePoint release_time) noexcept override {
    catch_up();
    Pending& p = pending(role);
    const hapticctrl::TimePoint start = release_time + start_delay;
    p.task->begin(cycle, start, period_);
    hapticctrl::Duration duration =
        role == rt_core::TaskRole::kMain ? main_duration_(cycle) : degraded_duration;
    if (role == rt_core::TaskRole::kMain) {
      const std::uint32_t k = overrun_->take();
      if (k > 0) {
        duration = k * period_ - period_ / 5;
      }
    }
    p.cycle = cycle;
    p.started = start;
    p.finish_at = start + duration;
    catch_up();
  }
  bool busy(rt_core::TaskRole role) noexcept override {
    catch_up();
    return pending(role).cycle.has_value();
  }
  hapticctrl::TimePoint started_at(rt_core::TaskRole role) noexcept override {
    catch_up();
    return pending(role).started;
  }
  hapticctrl::TimePoint finished_at(rt_core::TaskRole role, std::uint64_t cycle) noexcept override {
    catch_up();
    const Pending& p = pending(role);
    return p.last_finished_cycle == cycle ? p.last_finished_at : kNotYet;
  }
  void stop() noexcept override { stopped = true; }

  hapticctrl::Duration start_delay = std::chrono::microseconds(5);
  hapticctrl::Duration degraded_duration = std::chrono::microseconds(20);
  bool stopped = false;
  int discarded = 0;

 private:
  struct Pending {
    rt_core::ServoTask* task;
    std::optional<std::uint64_t> cycle;
    hapticctrl::TimePoint started = kNotYet;
    hapticctrl::TimePoint finish_at;
    std::optional<std::uint64_t> last_finished_cycle;
    hapticctrl::TimePoint last_finished_at = kNotYet;
  };
  Pending& pending(rt_core::TaskRole role) {
    return role == rt_core::TaskRole::kMain ? main_ : degraded_;
  }
  /// Commits every task whose scripted finish time has come, oldest first.
  void catch_up() {
    for (;;) {
      Pending* next = nullptr;
      for (Pending* p : {&main_, &degraded_}) {
        if (p->cycle && p->finish_at <= clock_->now() &&
            (next == nullptr || p->finish_at < next->finish_at)) {
          next = p;
        }
      }
      if (next == nullptr) {
        return;
      }
      if (next->task->finish(*next->cycle, next->finish_at) == rt_core::StepResult::kDiscarded) {
        ++discarded;
      }
      next->last_finished_cycle = next->cycle;
      next->last_finished_at = next->finish_at;
      next->cycle.reset();
    }
  }

  rt_core::FakeClock* clock_;
  rt_core::OverrunInjection* overrun_;
  hapticctrl::Duration period_;
  CycleLength main_duration_;
  Pending main_;
  Pending degraded_;
};

}  // namespace hapticctrl::test
