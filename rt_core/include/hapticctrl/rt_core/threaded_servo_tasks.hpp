#pragma once
/// @file threaded_servo_tasks.hpp
/// The real SERVO and degraded SERVO: one thread each, released by the CLOCK through a futex.

#include <atomic>
#include <cstdint>
#include <thread>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/executive.hpp"
#include "hapticctrl/rt_core/servo.hpp"

namespace hapticctrl::rt_core {

/// Scheduling of one task thread (applied by the thread itself before its loop).
struct ThreadPlacement {
  int fifo_priority = 0;  ///< 0: leave SCHED_OTHER
  int cpu = -1;           ///< -1: no affinity
};

class ThreadedServoTasks final : public TaskRunners {
 public:
  /// Starts both threads and returns once both are placed and waiting for their first release
  /// (bounded by 5 s), so that CLOCK never counts a thread's start-up as deadline misses (seen
  /// 2026-11-24: under ASan with parallel tests the first 5 cycles at 10 ms missed and the core
  /// failed safe at start). Setup: allocates.
  ThreadedServoTasks(Clock& clock, ServoTask& main_task, ServoTask& degraded_task,
                     OverrunInjection& overrun, Duration period,
                     const ThreadPlacement& main_placement,
                     const ThreadPlacement& degraded_placement);
  ThreadedServoTasks(const ThreadedServoTasks&) = delete;
  ThreadedServoTasks& operator=(const ThreadedServoTasks&) = delete;
  ~ThreadedServoTasks() override;

  HAPTICCTRL_RT void release(TaskRole role, std::uint64_t cycle,
                             TimePoint release_time) noexcept override;
  HAPTICCTRL_RT bool busy(TaskRole role) noexcept override;
  HAPTICCTRL_RT TimePoint started_at(TaskRole role) noexcept override;
  HAPTICCTRL_RT TimePoint finished_at(TaskRole role, std::uint64_t cycle) noexcept override;
  void stop() noexcept override;

  /// Whether each thread got the scheduling it asked for (reported by the preflight).
  [[nodiscard]] bool placement_applied(TaskRole role) const noexcept;

 private:
  struct Worker {
    ServoTask* task = nullptr;
    ThreadPlacement placement;
    std::atomic<std::uint32_t> release_word{0};
    std::atomic<std::uint64_t> released_cycle{0};
    std::atomic<std::uint64_t> finished_cycle{0};
    std::atomic<TimePoint> release_time{TimePoint{}};
    std::atomic<TimePoint> started{kNotYet};
    std::atomic<TimePoint> finished{kNotYet};  ///< end of `finished_cycle`, stored before it
    std::atomic<bool> placement_ok{false};
    std::atomic<bool> ready{false};  ///< placed, about to wait for the first release
    std::thread thread;
  };

  void worker_loop(Worker& worker) noexcept;
  HAPTICCTRL_RT Worker& worker(TaskRole role) noexcept {
    return role == TaskRole::kMain ? main_ : degraded_;
  }

  Clock* clock_;
  OverrunInjection* overrun_;  ///< taken by the main SERVO after begin()
  Duration period_;
  std::atomic<bool> stopping_{false};
  Worker main_;
  Worker degraded_;
};

/// Applies SCHED_FIFO `priority` (if > 0) and CPU affinity (if >= 0) to the calling thread,
/// flushes subnormal floats to zero in it (FTZ/DAZ) and touches `stack_bytes` of stack so page
/// faults happen now, not in the cycle. Returns whether
/// everything asked for was granted. Not for the cycle.
bool place_current_thread(const ThreadPlacement& placement,
                          std::size_t stack_bytes = std::size_t{256} * 1024) noexcept;

}  // namespace hapticctrl::rt_core
