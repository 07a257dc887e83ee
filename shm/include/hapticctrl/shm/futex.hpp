#pragma once
/// @file futex.hpp
/// Thin wrappers over the Linux futex syscall for words that live in shared memory.
///
/// The futexes here are process-shared (no FUTEX_PRIVATE_FLAG) because the word sits in a
/// MAP_SHARED segment that several processes map, some of them read-only.

#include <atomic>
#include <chrono>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::shm {

/// Outcome of a futex wait.
enum class FutexWaitResult : std::uint8_t {
  kWoken,         ///< woken by a wake call (or spuriously): re-check the word
  kValueChanged,  ///< the word no longer held the expected value when the call was made
  kTimedOut,      ///< the timeout elapsed
  kInterrupted,   ///< a signal interrupted the wait
};

/// Blocks while `*word == expected`, at most `timeout`.
/// Real-time contract: blocking; never call from the cycle.
FutexWaitResult futex_wait(const std::atomic<std::uint32_t>& word, std::uint32_t expected,
                           std::chrono::nanoseconds timeout) noexcept;

/// Wakes every waiter blocked on `word`. One syscall, never blocks.
/// Real-time contract: safe to call from the cycle (it is the "notify" the cycle may do).
HAPTICCTRL_RT void futex_wake_all(const std::atomic<std::uint32_t>& word) noexcept;

/// Wakes at most one waiter blocked on `word`. Same contract as futex_wake_all().
HAPTICCTRL_RT void futex_wake_one(const std::atomic<std::uint32_t>& word) noexcept;

}  // namespace hapticctrl::shm
