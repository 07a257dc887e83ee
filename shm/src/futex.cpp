// Implements futex.hpp: thin wrappers over the Linux futex syscall for words that live in shared
// memory.
#include "hapticctrl/shm/futex.hpp"

#include "hapticctrl/base/realtime.hpp"

#include <linux/futex.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <ctime>

namespace hapticctrl::shm {
namespace {

// The futex syscall wants the address of a plain 32-bit word; std::atomic<uint32_t> is exactly
// that (lock-free, same size and alignment), which libstdc++'s own atomic wait relies on too.
static_assert(sizeof(std::atomic<std::uint32_t>) == sizeof(std::uint32_t));
static_assert(std::atomic<std::uint32_t>::is_always_lock_free);

HAPTICCTRL_RT std::uint32_t* futex_address(const std::atomic<std::uint32_t>& word) noexcept {
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-const-cast): the kernel only reads it for WAIT.
  return reinterpret_cast<std::uint32_t*>(const_cast<std::atomic<std::uint32_t>*>(&word));
}

HAPTICCTRL_RT long futex_call(std::uint32_t* address, int op, std::uint32_t value,
                              const timespec* timeout) noexcept {
  return syscall(SYS_futex, address, op, value, timeout, nullptr, 0);
}

}  // namespace

FutexWaitResult futex_wait(const std::atomic<std::uint32_t>& word, std::uint32_t expected,
                           std::chrono::nanoseconds timeout) noexcept {
  if (timeout.count() <= 0) {
    return FutexWaitResult::kTimedOut;
  }
  timespec relative{};
  relative.tv_sec = static_cast<time_t>(timeout.count() / 1'000'000'000);
  relative.tv_nsec = static_cast<long>(timeout.count() % 1'000'000'000);
  if (futex_call(futex_address(word), FUTEX_WAIT, expected, &relative) == 0) {
    return FutexWaitResult::kWoken;
  }
  switch (errno) {
    case EAGAIN:
      return FutexWaitResult::kValueChanged;
    case ETIMEDOUT:
      return FutexWaitResult::kTimedOut;
    default:
      return FutexWaitResult::kInterrupted;
  }
}

void futex_wake_all(const std::atomic<std::uint32_t>& word) noexcept {
  futex_call(futex_address(word), FUTEX_WAKE, static_cast<std::uint32_t>(INT_MAX), nullptr);
}

void futex_wake_one(const std::atomic<std::uint32_t>& word) noexcept {
  futex_call(futex_address(word), FUTEX_WAKE, 1U, nullptr);
}

}  // namespace hapticctrl::shm
