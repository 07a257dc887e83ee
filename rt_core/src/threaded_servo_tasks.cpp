// Implements threaded_servo_tasks.hpp: the real SERVO and degraded SERVO: one thread each, released
// by the CLOCK through a futex.
#include "hapticctrl/rt_core/threaded_servo_tasks.hpp"

#include <pthread.h>
#include <sched.h>
#if defined(__SSE__)
#include <xmmintrin.h>
#endif

#include <chrono>
#include <cstring>
#include <thread>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/futex.hpp"

namespace hapticctrl::rt_core {

namespace {

/// Keeps the compiler from eliding the stack prefault.
void touch_stack(std::size_t bytes) noexcept {
  constexpr std::size_t kChunk = std::size_t{16} * 1024;
  volatile unsigned char buffer[kChunk];
  std::memset(const_cast<unsigned char*>(buffer), 0, kChunk);
  if (bytes > kChunk) {
    touch_stack(bytes - kChunk);
  }
}

/// Subnormal floating-point operands cost up to about a hundred cycles per operation on x86,
/// and the quantities that decay while the arm rests under gravity compensation (filtered
/// velocities, friction-damped motion) drift into that range: flush them to zero in the RT
/// threads so that a quiet arm can never make a cycle slower. Only values below 1e-308 change.
void flush_subnormals_to_zero() noexcept {
#if defined(__SSE__)
  constexpr unsigned kFlushToZero = 0x8000;       // MXCSR.FTZ: subnormal results become 0
  constexpr unsigned kDenormalsAreZero = 0x0040;  // MXCSR.DAZ: subnormal inputs read as 0
  _mm_setcsr(_mm_getcsr() | kFlushToZero | kDenormalsAreZero);
#endif
}

}  // namespace

bool place_current_thread(const ThreadPlacement& placement, std::size_t stack_bytes) noexcept {
  bool ok = true;
  if (placement.cpu >= 0) {
    cpu_set_t set;
    CPU_ZERO(&set);
    CPU_SET(static_cast<unsigned>(placement.cpu), &set);
    ok = pthread_setaffinity_np(pthread_self(), sizeof(set), &set) == 0 && ok;
  }
  if (placement.fifo_priority > 0) {
    sched_param param{};
    param.sched_priority = placement.fifo_priority;
    ok = pthread_setschedparam(pthread_self(), SCHED_FIFO, &param) == 0 && ok;
  }
  flush_subnormals_to_zero();
  touch_stack(stack_bytes);
  return ok;
}

ThreadedServoTasks::ThreadedServoTasks(Clock& clock, ServoTask& main_task, ServoTask& degraded_task,
                                       OverrunInjection& overrun, Duration period,
                                       const ThreadPlacement& main_placement,
                                       const ThreadPlacement& degraded_placement)
    : clock_(&clock), overrun_(&overrun), period_(period) {
  main_.task = &main_task;
  main_.placement = main_placement;
  degraded_.task = &degraded_task;
  degraded_.placement = degraded_placement;
  main_.thread = std::thread([this] { worker_loop(main_); });
  degraded_.thread = std::thread([this] { worker_loop(degraded_); });
  pthread_setname_np(main_.thread.native_handle(), "hc-servo");
  pthread_setname_np(degraded_.thread.native_handle(), "hc-degraded");
  const auto deadline = hapticctrl::MonotonicClock::now() + std::chrono::seconds(5);
  while (!(main_.ready.load(std::memory_order_acquire) &&
           degraded_.ready.load(std::memory_order_acquire)) &&
         hapticctrl::MonotonicClock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
}

ThreadedServoTasks::~ThreadedServoTasks() {
  stop();
}

void ThreadedServoTasks::worker_loop(Worker& w) noexcept {
  w.placement_ok.store(place_current_thread(w.placement), std::memory_order_release);
  w.ready.store(true, std::memory_order_release);
  // Start from the word's initial value, not its current one: a release that happened before
  // this thread got to run must still be seen.
  std::uint32_t seen = 0;
  while (!stopping_.load(std::memory_order_acquire)) {
    shm::futex_wait(w.release_word, seen, std::chrono::milliseconds(100));
    const std::uint32_t now_word = w.release_word.load(std::memory_order_acquire);
    if (now_word == seen) {
      continue;
    }
    seen = now_word;
    if (stopping_.load(std::memory_order_acquire)) {
      break;
    }
    const std::uint64_t cycle = w.released_cycle.load(std::memory_order_acquire);
    const TimePoint start = clock_->now();
    w.started.store(start, std::memory_order_release);
    w.task->begin(cycle, start, period_);
    if (w.task->role() == TaskRole::kMain) {
      // Fault injection: this SERVO overruns for K cycles (stalls (K - 0.2) periods, so that
      // exactly K consecutive cycles miss their deadline).
      const std::uint32_t k = overrun_->take();
      if (k > 0) {
        clock_->sleep_until(w.release_time.load(std::memory_order_relaxed) + k * period_ -
                            period_ / 5);
      }
    }
    w.task->finish(cycle, clock_->now());
    // Timed after finish() returns: the arm commands (the simulator's step) are part of the
    // cycle's cost. Stored before finished_cycle, so a reader that sees the cycle sees its time.
    w.finished.store(clock_->now(), std::memory_order_relaxed);
    w.finished_cycle.store(cycle, std::memory_order_release);
  }
}

void ThreadedServoTasks::release(TaskRole role, std::uint64_t cycle,
                                 TimePoint release_time) noexcept {
  Worker& w = worker(role);
  w.started.store(kNotYet, std::memory_order_relaxed);
  w.release_time.store(release_time, std::memory_order_relaxed);
  w.released_cycle.store(cycle, std::memory_order_release);
  w.release_word.fetch_add(1, std::memory_order_acq_rel);
  shm::futex_wake_one(w.release_word);
}

bool ThreadedServoTasks::busy(TaskRole role) noexcept {
  Worker& w = worker(role);
  return w.finished_cycle.load(std::memory_order_acquire) !=
         w.released_cycle.load(std::memory_order_acquire);
}

TimePoint ThreadedServoTasks::started_at(TaskRole role) noexcept {
  return worker(role).started.load(std::memory_order_acquire);
}

TimePoint ThreadedServoTasks::finished_at(TaskRole role, std::uint64_t cycle) noexcept {
  const Worker& w = worker(role);
  if (w.finished_cycle.load(std::memory_order_acquire) != cycle) {
    return kNotYet;
  }
  return w.finished.load(std::memory_order_relaxed);
}

void ThreadedServoTasks::stop() noexcept {
  stopping_.store(true, std::memory_order_release);
  for (Worker* w : {&main_, &degraded_}) {
    w->release_word.fetch_add(1, std::memory_order_acq_rel);
    shm::futex_wake_all(w->release_word);
  }
  for (Worker* w : {&main_, &degraded_}) {
    if (w->thread.joinable()) {
      w->thread.join();
    }
  }
}

bool ThreadedServoTasks::placement_applied(TaskRole role) const noexcept {
  const Worker& w = role == TaskRole::kMain ? main_ : degraded_;
  return w.placement_ok.load(std::memory_order_acquire);
}

}  // namespace hapticctrl::rt_core
