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
  using Duration = std::function<hapticctrl::TimeNs(std::uint64_t cycle)>;

  ScriptedServoTasks(rt_core::FakeClock& clock, rt_core::ServoTask& main_task,
                     rt_core::ServoTask& degraded_task, rt_core::OverrunInjection& overrun,
                     hapticctrl::TimeNs period, Duration main_duration)
      : clock_(&clock),
        overrun_(&overrun),
        period_(period),
        main_duration_(std::move(main_duration)),
        main_{&main_task},
        degraded_{&degraded_task} {}

  void release(rt_core::TaskRole role, std::uint64_t cycle,
               hapticctrl::TimeNs release_time) noexcept override {
    catch_up();
    Pending& p = pending(role);
    const hapticctrl::TimeNs start = release_time + start_delay;
    p.task->begin(cycle, start, period_);
    hapticctrl::TimeNs duration =
        role == rt_core::TaskRole::kMain ? main_duration_(cycle) : degraded_duration;
    if (role == rt_core::TaskRole::kMain) {
      const std::uint32_t k = overrun_->take();
      if (k > 0) {
        duration = static_cast<hapticctrl::TimeNs>(k) * period_ - period_ / 5;
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
  hapticctrl::TimeNs started_at(rt_core::TaskRole role) noexcept override {
    catch_up();
    return pending(role).started;
  }
  hapticctrl::TimeNs finished_at(rt_core::TaskRole role, std::uint64_t cycle) noexcept override {
    catch_up();
    const Pending& p = pending(role);
    return p.last_finished_cycle == cycle ? p.last_finished_at : -1;
  }
  void stop() noexcept override { stopped = true; }

  hapticctrl::TimeNs start_delay = 5 * hapticctrl::kNsPerUs;
  hapticctrl::TimeNs degraded_duration = 20 * hapticctrl::kNsPerUs;
  bool stopped = false;
  int discarded = 0;

 private:
  struct Pending {
    rt_core::ServoTask* task;
    std::optional<std::uint64_t> cycle;
    hapticctrl::TimeNs started = -1;
    hapticctrl::TimeNs finish_at = 0;
    std::optional<std::uint64_t> last_finished_cycle;
    hapticctrl::TimeNs last_finished_at = -1;
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
  hapticctrl::TimeNs period_;
  Duration main_duration_;
  Pending main_;
  Pending degraded_;
};

}  // namespace hapticctrl::test
