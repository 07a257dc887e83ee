// Tests of futex.hpp: thin wrappers over the Linux futex syscall for words that live in shared
// memory.
#include "hapticctrl/shm/futex.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <thread>

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;

TEST(Futex, WaitOnChangedValueReturnsImmediately) {
  std::atomic<std::uint32_t> word{5};
  EXPECT_EQ(futex_wait(word, 4, 1s), FutexWaitResult::kValueChanged);
}

TEST(Futex, WaitTimesOut) {
  std::atomic<std::uint32_t> word{5};
  EXPECT_EQ(futex_wait(word, 5, 5ms), FutexWaitResult::kTimedOut);
}

TEST(Futex, NonPositiveTimeoutDoesNotBlock) {
  std::atomic<std::uint32_t> word{5};
  EXPECT_EQ(futex_wait(word, 5, 0ns), FutexWaitResult::kTimedOut);
}

TEST(Futex, WakeReleasesWaiter) {
  std::atomic<std::uint32_t> word{0};
  std::atomic<bool> done{false};
  std::thread waiter([&] {
    while (word.load() == 0) {
      futex_wait(word, 0, 5s);
    }
    done = true;
  });
  std::this_thread::sleep_for(10ms);
  word.store(1);
  futex_wake_one(word);
  waiter.join();
  EXPECT_TRUE(done.load());
}

}  // namespace
}  // namespace hapticctrl::shm
