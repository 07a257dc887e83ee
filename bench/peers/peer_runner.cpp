// Implements peer_runner.hpp: the writer and reader processes of one run, and what they record
// in a shared mapping for the parent to collect.
#include "peers/peer_runner.hpp"

#include <signal.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <thread>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/rt_core/threaded_servo_tasks.hpp"  // place_current_thread

namespace hapticctrl::bench {
namespace {

constexpr std::uint32_t kMaxMessages = 60'000;
constexpr Duration kWarmUpLimit = std::chrono::seconds(3);

/// What the two processes write and the parent reads, in one shared anonymous mapping.
struct Shared {
  std::atomic<bool> reader_warm{false};  ///< the reader saw a warm-up message
  std::atomic<bool> stop_reader{false};
  std::atomic<pid_t> reader_pid{0};
  std::atomic<std::uint32_t> latency_count{0};
  std::atomic<std::uint32_t> read_count{0};
  std::atomic<std::uint32_t> publish_count{0};
  std::atomic<std::uint64_t> failed_publishes{0};
  /// CPU time (user + system, every thread) over the measured messages only: set up and warm-up
  /// left out.
  std::atomic<double> writer_cpu_s{0.0};
  std::atomic<double> reader_cpu_s{0.0};
  std::array<char, 256> error{};
  std::array<std::int64_t, kMaxMessages> latency{};
  std::array<std::int64_t, kMaxMessages> read{};
  std::array<std::int64_t, kMaxMessages> publish{};
  std::array<Phase, kMaxMessages> phase{};
};

double cpu_seconds(const rusage& ru) {
  return static_cast<double>(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         static_cast<double>(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec) * 1e-6;
}

/// This process's CPU time so far.
double own_cpu_seconds() {
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return cpu_seconds(ru);
}

void say_error(Shared& shared, const char* what) {
  std::snprintf(shared.error.data(), shared.error.size(), "%s", what);
}

void sleep_until(TimePoint t) {
  const std::int64_t ns = to_ns(t);
  timespec ts{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

Phase phase_of(std::uint32_t i, std::uint32_t n) {
  if (i < n / 5) {
    return Phase::kRunning;
  }
  if (i < n * 3 / 5) {
    return Phase::kStopped;
  }
  return i < n * 4 / 5 ? Phase::kResumed : Phase::kKilled;
}

/// The reader's signals at the phase boundaries of a stall run.
void signal_reader(const Shared& shared, Phase from, Phase to) {
  const pid_t reader = shared.reader_pid.load();
  if (from == to || reader <= 0) {
    return;
  }
  kill(reader, to == Phase::kStopped ? SIGSTOP : to == Phase::kResumed ? SIGCONT : SIGKILL);
}

void writer_main(PeerTransport& transport, const RunConfig& config, int cpu, int priority,
                 Shared& shared) {
  rt_core::place_current_thread({.fifo_priority = priority, .cpu = cpu});
  std::unique_ptr<PeerWriter> writer = transport.make_writer(config.mode);
  Message m{};
  // Warm-up: until the reader has seen one (a subscription takes effect, a multicast group is
  // joined), message 0 once a millisecond.
  const TimePoint warm_until = MonotonicClock::now() + kWarmUpLimit;
  while (!shared.reader_warm.load() && MonotonicClock::now() < warm_until) {
    m.echo_client_time_ns = to_ns(MonotonicClock::now());
    writer->publish(m);
    sleep_until(MonotonicClock::now() + std::chrono::milliseconds(1));
  }
  const Duration period = from_seconds(1.0 / config.rate_hz);
  const TimePoint start = MonotonicClock::now() + period;
  const std::uint32_t n = std::min(config.messages, kMaxMessages);
  Phase phase = Phase::kRunning;
  const double cpu_start = own_cpu_seconds();
  for (std::uint32_t i = 0; i < n; ++i) {
    sleep_until(start + i * period);
    if (config.stall_reader) {
      const Phase next = phase_of(i, n);
      signal_reader(shared, phase, next);
      phase = next;
    }
    m.cycle = i + 1;
    const TimePoint t0 = MonotonicClock::now();
    m.echo_client_time_ns = to_ns(t0);
    const bool ok = writer->publish(m);
    shared.publish[i] = to_ns(MonotonicClock::now() - t0);
    shared.phase[i] = phase;
    if (!ok) {
      shared.failed_publishes.fetch_add(1);
    }
    shared.publish_count.store(i + 1);
  }
  shared.writer_cpu_s.store(own_cpu_seconds() - cpu_start);
}

/// The reader's CPU account: from its first measured message to its last.
struct ReaderCpu {
  double start = -1.0;
  bool done = false;
};

void record(Shared& shared, const Message& m, TimePoint t0, TimePoint t1, std::uint32_t last,
            ReaderCpu& cpu) {
  if (m.cycle == 0) {
    shared.reader_warm.store(true);
    return;
  }
  if (cpu.start < 0.0) {
    cpu.start = own_cpu_seconds();
  } else if (m.cycle >= last && !cpu.done) {
    shared.reader_cpu_s.store(own_cpu_seconds() - cpu.start);
    cpu.done = true;
  }
  const std::uint32_t r = shared.read_count.load();
  if (r < kMaxMessages) {
    shared.read[r] = to_ns(t1 - t0);
    shared.read_count.store(r + 1);
  }
  const std::uint32_t l = shared.latency_count.load();
  if (l < kMaxMessages) {
    shared.latency[l] = to_ns(t1) - m.echo_client_time_ns;
    shared.latency_count.store(l + 1);
  }
}

void reader_main(PeerTransport& transport, const RunConfig& config, int cpu, int priority,
                 Shared& shared) {
  // A polling reader spins: at SCHED_FIFO it lost 50 ms of every second to RT throttling, and
  // starved iceoryx's own runtime thread until RouDi dropped its subscriber after ~1.5 s (30 % of
  // the messages delivered, 2026-12-02). Polling readers therefore spin at SCHED_OTHER.
  rt_core::place_current_thread(
      {.fifo_priority = config.mode == ReadMode::kPoll ? 0 : priority, .cpu = cpu});
  std::unique_ptr<PeerReader> reader = transport.make_reader(config.mode);
  const std::uint32_t last = std::min(config.messages, kMaxMessages);
  ReaderCpu account;
  Message m{};
  while (!shared.stop_reader.load(std::memory_order_relaxed)) {
    if (config.mode == ReadMode::kWake && !reader->wait(std::chrono::milliseconds(50))) {
      continue;
    }
    const TimePoint t0 = MonotonicClock::now();
    if (reader->read(m)) {
      record(shared, m, t0, MonotonicClock::now(), last, account);
    }
  }
  if (!account.done && account.start >= 0.0) {  // the last message never came: up to the stop
    shared.reader_cpu_s.store(own_cpu_seconds() - account.start);
  }
}

/// Runs `body` in a child process; returns its pid (-1: fork failed).
template <typename Body>
pid_t spawn(Shared& shared, Body body) {
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    int code = 0;
    try {
      body();
    } catch (const std::exception& e) {
      say_error(shared, e.what());
      code = 2;
    }
    _exit(code);
  }
  return pid;
}

/// Waits for `pid` (bounded); a child that outlives the bound is killed.
void reap(pid_t pid, Duration bound) {
  int status = 0;
  const TimePoint until = MonotonicClock::now() + bound;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (MonotonicClock::now() > until) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

void collect(const Shared& shared, std::int64_t clock_ns, RunResult& out) {
  const auto less_clock = [clock_ns](std::int64_t v) {
    return std::max<std::int64_t>(0, v - clock_ns);
  };
  for (std::uint32_t i = 0; i < shared.latency_count.load(); ++i) {
    out.latency_ns.push_back(shared.latency[i]);
  }
  for (std::uint32_t i = 0; i < shared.read_count.load(); ++i) {
    out.read_ns.push_back(less_clock(shared.read[i]));
  }
  for (std::uint32_t i = 0; i < shared.publish_count.load(); ++i) {
    out.publish_ns.push_back(less_clock(shared.publish[i]));
    out.publish_phase.push_back(shared.phase[i]);
  }
  out.failed_publishes = shared.failed_publishes.load();
  out.writer_cpu_s = shared.writer_cpu_s.load();
  out.reader_cpu_s = shared.reader_cpu_s.load();
  out.error = shared.error.data();
}

}  // namespace

std::int64_t clock_read_ns() {
  std::array<std::int64_t, 2001> pairs{};
  for (auto& d : pairs) {
    const TimePoint t0 = MonotonicClock::now();
    d = to_ns(MonotonicClock::now() - t0);
  }
  std::nth_element(pairs.begin(), pairs.begin() + pairs.size() / 2, pairs.end());
  return pairs[pairs.size() / 2];
}

RunResult run_peers(PeerTransport& transport, const RunConfig& config, const Placement& placement) {
  RunResult result;
  void* at =
      mmap(nullptr, sizeof(Shared), PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (at == MAP_FAILED) {
    result.error = "mmap of the result area failed";
    return result;
  }
  auto* shared = new (at) Shared();
  try {
    transport.setup(config.mode);
  } catch (const std::exception& e) {
    result.error = e.what();
    munmap(at, sizeof(Shared));
    return result;
  }
  const pid_t reader = spawn(*shared, [&] {
    reader_main(transport, config, placement.reader_cpu, placement.priority, *shared);
  });
  shared->reader_pid.store(reader);
  const pid_t writer = spawn(*shared, [&] {
    writer_main(transport, config, placement.writer_cpu, placement.priority, *shared);
  });
  const Duration run = from_seconds(config.messages / config.rate_hz);
  reap(writer, run + 2 * kWarmUpLimit);
  shared->stop_reader.store(true);
  if (config.stall_reader) {
    kill(reader, SIGCONT);  // a reader stopped for good would never see the flag
  }
  reap(reader, std::chrono::seconds(1));
  transport.teardown();
  collect(*shared, clock_read_ns(), result);
  shared->~Shared();
  munmap(at, sizeof(Shared));
  return result;
}

}  // namespace hapticctrl::bench
