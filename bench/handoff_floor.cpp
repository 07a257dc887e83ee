// The floor for "SERVO starts after CLOCK release": a bare two-thread futex hand-off with the
// same scheduling as the core (SCHED_FIFO when permitted; same CPU or different CPUs), measured
// as release-to-start latency over N hand-offs. Prints one JSON object.
//
// usage: hapticctrl-bench-handoff [--iterations N] [--cpu-a A] [--cpu-b B] [--priority P]

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/rt_core/threaded_servo_tasks.hpp"  // place_current_thread
#include "hapticctrl/shm/futex.hpp"

namespace {

using Clock = std::chrono::steady_clock;

long long percentile(std::vector<long long>& v, double p) {
  const auto index = static_cast<std::size_t>(p * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(index), v.end());
  return v[index];
}

}  // namespace

int main(int argc, char** argv) {
  int iterations = 5000;
  int cpu_a = 1;
  int cpu_b = 1;
  int priority = 80;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string opt = argv[i];
    const int value = std::stoi(argv[i + 1]);  // throws on a word that is not a number
    if (opt == "--iterations") {
      iterations = std::max(10, value);
    } else if (opt == "--cpu-a") {
      cpu_a = value;
    } else if (opt == "--cpu-b") {
      cpu_b = value;
    } else if (opt == "--priority") {
      priority = value;
    }
  }
  std::atomic<std::uint32_t> release{0};
  std::atomic<std::int64_t> started_ns{0};
  std::atomic<bool> stop{false};
  std::thread worker([&] {
    hapticctrl::rt_core::place_current_thread({.fifo_priority = priority - 1, .cpu = cpu_b});
    std::uint32_t seen = 0;
    while (!stop.load()) {
      hapticctrl::shm::futex_wait(release, seen, std::chrono::milliseconds(100));
      const std::uint32_t now = release.load();
      if (now == seen) {
        continue;
      }
      seen = now;
      started_ns.store(Clock::now().time_since_epoch().count(), std::memory_order_release);
    }
  });
  hapticctrl::rt_core::place_current_thread({.fifo_priority = priority, .cpu = cpu_a});
  std::vector<long long> delays;
  delays.reserve(static_cast<std::size_t>(iterations));
  for (int i = 0; i < iterations; ++i) {
    std::this_thread::sleep_for(std::chrono::microseconds(500));  // like CLOCK: sleep, then release
    started_ns.store(0);
    const auto released = Clock::now().time_since_epoch().count();
    release.fetch_add(1);
    hapticctrl::shm::futex_wake_one(release);
    // CLOCK goes back to sleep right after the release, which is what lets SERVO run on a
    // shared CPU; model that with a short sleep before collecting the start time.
    std::this_thread::sleep_for(std::chrono::microseconds(200));
    const auto started = started_ns.load(std::memory_order_acquire);
    if (started > 0) {
      delays.push_back(started - released);
    }
  }
  stop = true;
  release.fetch_add(1);
  hapticctrl::shm::futex_wake_all(release);
  worker.join();
  if (delays.empty()) {
    std::printf("{\"error\":\"no hand-off completed\"}\n");
    return 1;
  }
  std::printf(
      "{\"samples\":%zu,\"cpu_a\":%d,\"cpu_b\":%d,\"p50_ns\":%lld,\"p99_ns\":%lld,\"max_ns\":%lld}"
      "\n",
      delays.size(), cpu_a, cpu_b, percentile(delays, 0.50), percentile(delays, 0.99),
      *std::max_element(delays.begin(), delays.end()));
  return 0;
}
