#pragma once
// The H1 end-to-end scenarios' rig (tests/e2e/coupling_network_test.cpp):
// the real core and bridge, hapticctrl-netem in front of the bridge, the demo client and a
// recorder of what the core renders cycle by cycle, with the retries a VM stall calls for and
// the measures taken on the records. The binaries' paths come from the including test's
// compile definitions.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "support/controller_stack.hpp"
#include "support/cycle_recorder.hpp"
#include "support/machine_retries.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {

using namespace std::chrono_literals;

#ifdef HAPTICCTRL_SANITIZED
inline constexpr int kPeriodUs = ControllerStack::kDefaultPeriodUs;  // instrumented: 10 ms
#else
inline constexpr int kPeriodUs = 1000;  // what H1 is judged at
#endif
inline constexpr std::int64_t kCyclesPerSecond = 1'000'000 / kPeriodUs;
/// Force steps allowed while the link is lost, N per cycle: 1 N/ms (H1), and at least the
/// 1 N of one cycle for cycles longer than 1 ms.
inline constexpr double kReleaseStep =
    1.0 * kPeriodUs / 1000.0 < 1.0 ? 1.0 : 1.0 * kPeriodUs / 1000.0;
inline constexpr int kAttempts = 3;

/// hapticctrl-netem in front of a bridge. With an impairment, the attempt's link is the test's
/// own: stale client samples are then its delay and losses, not the machine starving the client
/// (without this a test through a 5 or 20 ms link counted every failure as the machine's and
/// could not fail, 2026-12-07).
class Relay {
 public:
  Relay(std::uint16_t bridge_port, const std::vector<std::string>& impairment) {
    attempt_disturbance().link_impaired =
        attempt_disturbance().link_impaired || !impairment.empty();
    std::vector<std::string> args{"--to", "127.0.0.1:" + std::to_string(bridge_port), "--json"};
    args.insert(args.end(), impairment.begin(), impairment.end());
    process_.emplace(HAPTICCTRL_NETEM_BINARY, args);
    const std::string marker = "listening on 127.0.0.1:";
    ControllerStack::eventually([&] {
      const std::string out = process_->out();
      const auto at = out.find(marker);
      if (at == std::string::npos || out.find('\n', at) == std::string::npos) {
        return false;
      }
      port_ = static_cast<std::uint16_t>(std::stoi(out.substr(at + marker.size())));
      return true;
    });
  }
  [[nodiscard]] std::uint16_t port() const { return port_; }
  /// SIGUSR1: the relay drops everything, both ways, until the next toggle.
  void toggle_blackout() { process_->signal(SIGUSR1); }

 private:
  std::optional<SpawnedProcess> process_;
  std::uint16_t port_ = 0;
};

/// Core, bridge, relay, the demo (by default with a weighted sphere), and the recorder.
struct Scenario {
  explicit Scenario(const std::string& tag, const std::vector<std::string>& impairment,
                    const std::vector<std::string>& demo_extra = {"--gravity"})
      : stack(tag, kPeriodUs, {}, {"--benchmark-mode"}), relay(stack.port(), impairment) {
    if (stack.ready() && relay.port() != 0) {
      std::vector<std::string> args{"--server", "127.0.0.1:" + std::to_string(relay.port()),
                                    "--headless", "--no-lcm", "--json"};
      args.insert(args.end(), demo_extra.begin(), demo_extra.end());
      demo.emplace(HAPTICCTRL_DEMO_BINARY, args);
      recorder.emplace(stack.segment());
    }
  }
  [[nodiscard]] bool started() const { return recorder.has_value(); }

  [[nodiscard]] bool coupled() const {
    return (stack.position().state_word & shm::state_bits::kCoupled) != 0;
  }
  /// The core left its cycle on its own (a VM stall: it failed safe, and is stopped by now).
  [[nodiscard]] bool core_failed_safe() const {
    return stack.segment().header().core_state.load() !=
           static_cast<std::uint32_t>(shm::CoreState::kRunning);
  }
  Scenario(const Scenario&) = delete;
  Scenario& operator=(const Scenario&) = delete;
  /// Says how many stalls the core rode through (each would have failed it safe).
  ~Scenario() {
    if (started()) {
      std::printf("%s: the core rode through %llu VM stall(s) (benchmark mode)\n",
                  stack.instance().c_str(),
                  static_cast<unsigned long long>(stack.telemetry().would_fail_safe));
    }
  }
  /// A force step of `step` N in one cycle, above the 1 N/ms the release rate allows, that a
  /// cycle the machine stretched explains: the rate limit allows 1 N per ms of the cycle's true
  /// length, and the core's longest period since it started was at least that long (CI
  /// 2026-12-03: 1.16 N in a run whose core rode through 78 stalls). Said when true.
  [[nodiscard]] bool long_cycle_explains(double step) const {
    const double longest_ms = static_cast<double>(stack.telemetry().measured_period.max_ns) / 1e6;
    // Over the bound as the tests judge it (1e-6 N for rounding: an exact 1.00 N step was
    // retried under load, 2026-12-03), and 1 N per ms of the longest cycle.
    const bool explained = step > kReleaseStep + 1e-6 && longest_ms >= step;
    if (explained) {
      std::printf(
          "%s: a step of %.2f N in one cycle, with a cycle of up to %.2f ms: the "
          "machine's, tried again\n",
          stack.instance().c_str(), step, longest_ms);
    }
    return explained;
  }
  [[nodiscard]] std::string diagnostics() {
    return stack.diagnostics() + "\ndemo: " + (demo ? demo->err() : "not started");
  }

  ControllerStack stack;
  Relay relay;
  std::optional<SpawnedProcess> demo;
  std::optional<CycleRecorder> recorder;
};

/// Runs `body` until an attempt is judged on a machine that did not spoil it
/// (machine_retries.hpp: stalls retried, and said).
inline void with_retries(const std::string& name, const std::function<bool(int)>& body) {
#ifdef HAPTICCTRL_SANITIZED
  GTEST_SKIP() << "judged at a 1 ms cycle, which instrumented builds cannot hold";
#endif
  retry_what_the_machine_disturbed(name, kAttempts, body);
}

/// Index of the first record at or after `cycle`.
inline std::size_t index_of(const std::vector<CycleRecord>& r, std::uint64_t cycle) {
  std::size_t i = 0;
  while (i < r.size() && r[i].cycle < cycle) {
    ++i;
  }
  return i;
}

inline double max_speed(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to) {
  double m = 0.0;
  for (std::size_t i = from; i < std::min(to, r.size()); ++i) {
    m = std::max(m, r[i].speed);
  }
  return m;
}

/// The longest run of cycles in [from, to) on which the core saw the link stale (5 ms without a
/// sample flags it), counting the 5 ms before the flag, and the cycles the recorder missed
/// before a stale record (a stall that held the link up often held the recorder up too).
inline std::uint64_t longest_silence(const std::vector<CycleRecord>& r, std::size_t from,
                                     std::size_t to) {
  std::uint64_t longest = 0;
  std::uint64_t run_start = 0;
  bool in_run = false;
  for (std::size_t i = from; i < std::min(to, r.size()); ++i) {
    if (!r[i].stale()) {
      in_run = false;
      continue;
    }
    if (!in_run) {
      in_run = true;
      run_start = i > from && r[i].cycle - r[i - 1].cycle > 1 ? r[i - 1].cycle + 1 : r[i].cycle;
    }
    longest = std::max<std::uint64_t>(
        longest,
        r[i].cycle - run_start + 1 + 5 * static_cast<std::uint64_t>(kCyclesPerSecond) / 1000);
  }
  return longest;
}

/// The handle's speed as its displacement over 50 ms windows: the oscillation that H1 bounds.
/// (The per-cycle estimate is the encoder's finite difference: a one-count dither of the
/// resting handle, 0.03 mm, reads as 8 mm/s for a cycle or two.)
inline double windowed_speed(const std::vector<CycleRecord>& r, std::size_t from, std::size_t to) {
  const std::uint64_t window = 50 * static_cast<std::uint64_t>(kCyclesPerSecond) / 1000;
  double fastest = 0.0;
  std::size_t j = from;
  for (std::size_t i = from; i < std::min(to, r.size()); ++i) {
    while (r[i].cycle - r[j].cycle > window) {
      ++j;
    }
    if (r[i].cycle - r[j].cycle >= window / 2) {
      const double d =
          std::hypot(r[i].position[0] - r[j].position[0], r[i].position[1] - r[j].position[1],
                     r[i].position[2] - r[j].position[2]);
      fastest = std::max(fastest, d / (static_cast<double>(r[i].cycle - r[j].cycle) /
                                       static_cast<double>(kCyclesPerSecond)));
    }
  }
  return fastest;
}

/// The records around the fastest one in [from, to), for a failure's message.
inline std::string around_fastest(const std::vector<CycleRecord>& r, std::size_t from,
                                  std::size_t to) {
  std::size_t at = from;
  for (std::size_t i = from; i < std::min(to, r.size()); ++i) {
    at = r[i].speed > r[at].speed ? i : at;
  }
  std::string text;
  for (std::size_t i = at > 8 ? at - 8 : 0; i < std::min(r.size(), at + 8); ++i) {
    char line[160];
    std::snprintf(line, sizeof line, "\n  cycle %llu state 0x%x speed %.4f m/s force %.2f N z %.5f",
                  static_cast<unsigned long long>(r[i].cycle), r[i].state_word, r[i].speed,
                  r[i].force, r[i].position[2]);
    text += line;
  }
  return text;
}

/// Coupling on/off changes between cycles of the main SERVO on fresh data, from the first coupled
/// record on: a degraded cycle (a miss: the degraded SERVO never couples) or a stale link is not
/// chatter of the coupling.
inline int coupling_toggles(const std::vector<CycleRecord>& r, std::size_t from) {
  // From the first coupled record: the recorder may not have seen the coupling's start yet
  // when the scenario saw it in the segment, and that start is no chatter.
  while (from < r.size() && !r[from].coupled()) {
    ++from;
  }
  int n = 0;
  for (std::size_t i = from + 1; i < r.size(); ++i) {
    if (r[i].degraded() || r[i - 1].degraded() || r[i].stale() || r[i - 1].stale()) {
      continue;
    }
    if (r[i].coupled() != r[i - 1].coupled()) {
      ++n;
      std::printf("coupling %s at cycle %llu (speed %.3f m/s, force %.2f N)\n",
                  r[i].coupled() ? "on" : "off", static_cast<unsigned long long>(r[i].cycle),
                  r[i].speed, r[i].force);
    }
  }
  return n;
}

/// Waits for the coupling, notes its cycle in `coupled_at`, and records for `duration`. Nothing:
/// go on and judge; true: done (a failure was recorded); false: a VM stall, try again.
inline std::optional<bool> couple_and_record(Scenario& s, std::chrono::seconds duration,
                                             std::uint64_t& coupled_at) {
  if (!s.started()) {
    ADD_FAILURE() << "the stack did not start: " << s.diagnostics();
    return true;
  }
  if (!ControllerStack::eventually([&] { return s.coupled(); }, 10s)) {
    if (s.core_failed_safe()) {
      return false;
    }
    ADD_FAILURE() << "never coupled: " << s.diagnostics();
    return true;
  }
  coupled_at = s.recorder->newest_cycle();
  std::this_thread::sleep_for(duration);
  if (s.core_failed_safe()) {
    return false;
  }
  return std::nullopt;
}

}  // namespace hapticctrl::test
