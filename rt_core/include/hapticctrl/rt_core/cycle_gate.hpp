#pragma once
/// @file cycle_gate.hpp
/// Who may touch the arm and publish this cycle: the cycle-numbered token that keeps a late main
/// SERVO from overwriting the commands of a newer cycle.
///
/// CLOCK grants cycle k to the task it releases (main or degraded). A task enters the gate for
/// its own cycle to read inputs and again to commit outputs; between the two it computes without
/// holding anything. If CLOCK granted a newer cycle meanwhile (the degraded SERVO took over),
/// the late task's enter() fails and its outputs are discarded. Everything done inside the gate
/// (arm I/O, ctrl draining, logical state, VP/position publishing) is therefore serialised:
/// exactly one writer at a time, without a lock that can block.

#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::rt_core {

/// Real-time contract of every method: wait-free (one CAS or store), safe in the cycle.
class CycleGate {
 public:
  /// CLOCK: hand cycle `cycle` to the task about to be released. Fails (returns false) while the
  /// previous holder is inside; that cycle's task will then fail to enter.
  HAPTICCTRL_RT bool grant(std::uint64_t cycle) noexcept {
    std::uint64_t current = state_.load(std::memory_order_acquire);
    while ((current & kBusy) == 0 && (current >> 1) != kClosedCycle) {
      if (state_.compare_exchange_weak(current, cycle << 1, std::memory_order_acq_rel)) {
        return true;
      }
    }
    return false;
  }

  /// Task: enter for `cycle`; true only if that cycle is the granted one and nobody is inside.
  HAPTICCTRL_RT bool enter(std::uint64_t cycle) noexcept {
    std::uint64_t expected = cycle << 1;
    return state_.compare_exchange_strong(expected, (cycle << 1) | kBusy,
                                          std::memory_order_acq_rel);
  }

  /// Task: leave after enter(cycle) succeeded.
  HAPTICCTRL_RT void leave(std::uint64_t cycle) noexcept {
    state_.store(cycle << 1, std::memory_order_release);
  }

  /// Fail-safe: no task may enter again. Returns false while a task is inside (retry).
  bool close() noexcept { return grant(kClosedCycle); }

  [[nodiscard]] bool closed() const noexcept {
    return (state_.load(std::memory_order_acquire) >> 1) == kClosedCycle;
  }

 private:
  static constexpr std::uint64_t kBusy = 1;
  static constexpr std::uint64_t kClosedCycle = ~std::uint64_t{0} >> 2;
  std::atomic<std::uint64_t> state_{0};
};

}  // namespace hapticctrl::rt_core
