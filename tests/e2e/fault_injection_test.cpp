// Fault injection with every process real on loopback: processes killed at random moments and
// restarted, the core killed under its bridges, and a bridge frozen longer than the watchdog
// (a shared-memory writer that breaks every rule: shared_memory_abuse_test.cpp). Throughout, the
// forces on the handle may change by no more than their rate limits allow, and the core keeps its
// cycle.
#include <fcntl.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/arm_model/arm_model.hpp"
#include "hapticctrl/base/time.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/rendezvous.hpp"
#include "hapticctrl/shm/segment_handoff.hpp"
#include "support/controller_stack.hpp"
#include "support/force_step_watch.hpp"
#include "support/lcm_monitor.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

/// The behaviour tests' 10 ms cycle. At 4 ms, with five processes started and killed around it,
/// this VM failed the core safe in one run of four (a wake-up 19.9 ms late, 2026-12-01): its
/// vCPUs stall whenever the guest is busy, even with the core alone on its CPU (wake p99
/// 2.6 ms then, against 0.3 ms quiet).
constexpr int kPeriodUs = ControllerStack::kDefaultPeriodUs;
constexpr double kPeriodS = kPeriodUs * 1e-6;
/// The share of cycles that may miss during the soft-RT kills. Plain builds run the core
/// SCHED_FIFO: what misses is the VM's (5 %). Sanitizer builds run it SCHED_OTHER beside
/// instrumented bridges and demo, its SERVO taking 5.5-6.8 ms of the 10 ms period (p99, ASan,
/// 2026-12-01), so the VM's busy moments cost more: 3 to 54 misses in ~550 cycles in six local
/// runs that evening, 28 and 34 in CI; 20 % there still catches a core the kills disturb.
#ifdef HAPTICCTRL_SANITIZED
constexpr std::uint64_t kMissDivisor = 5;
#else
constexpr std::uint64_t kMissDivisor = 20;
#endif
/// How soon a client hears that its core was killed (median of three). Plain builds: 4.0-4.4 ms
/// measured (2026-12-02); under TSan the bridge, the client and the core run instrumented and the
/// median was 8.4-10.9 ms in six runs that afternoon, over a 10 ms bound in two.
#ifdef HAPTICCTRL_SANITIZED
constexpr double kNoticeMs = 20.0;
#else
constexpr double kNoticeMs = 10.0;
#endif

double operator_rate_limit() {
  return shm::ForceLimits{}.force_rate;
}
constexpr double kRounding = 1e-9;

std::string cycle_health(const shm::TelemetryPayload& t) {
  char text[256];  // NOLINT(*-avoid-c-arrays)
  std::snprintf(text, sizeof text,
                "wake p99 %.0f / max %.0f us, SERVO execution p99 %.0f / max %.0f us, degraded "
                "cycles %llu, skipped slots %llu",
                static_cast<double>(t.wake_latency.p99_ns) * 1e-3,
                static_cast<double>(t.wake_latency.max_ns) * 1e-3,
                static_cast<double>(t.servo_execution.p99_ns) * 1e-3,
                static_cast<double>(t.servo_execution.max_ns) * 1e-3,
                static_cast<unsigned long long>(t.degraded_cycles),
                static_cast<unsigned long long>(t.skipped_slots));
  return text;
}

bool coupled(const ControllerStack& stack) {
  return (stack.vp().state_word & shm::state_bits::kCoupled) != 0;
}

/// The number after `marker` in the last line of `text` that has it (NaN if none).
double last_number_after(const std::string& text, const std::string& marker) {
  const auto at = text.rfind(marker);
  return at == std::string::npos ? std::nan("") : std::stod(text.substr(at + marker.size()));
}

std::size_t count_of(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) {
    ++n;
  }
  return n;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? std::nan("") : v[v.size() / 2];
}

// Each start_* (re)starts a process in `p` (killing the one it held, if any).
void start_lcm_bridge(std::optional<SpawnedProcess>& p, const ControllerStack& stack,
                      const std::string& url) {
  p.reset();
  p.emplace(HAPTICCTRL_LCM_BINARY,
            std::vector<std::string>{"--instance", stack.instance(), "--lcm-url", url});
}

void start_demo(std::optional<SpawnedProcess>& p, const ControllerStack& stack) {
  p.reset();
  p.emplace(HAPTICCTRL_DEMO_BINARY,
            std::vector<std::string>{"--server", "127.0.0.1:" + std::to_string(stack.port()),
                                     "--headless", "--instance", stack.instance()});
}

/// A minute of operator force changing every 0.25 s to a random push of up to 6 N per axis.
std::string write_random_force_sequence(std::mt19937& rng) {
  std::string path = "/tmp/hapticctrl-fault-" + std::to_string(getpid()) + ".seq";
  std::ofstream out(path);
  std::uniform_real_distribution<double> force(-6.0, 6.0);
  for (int i = 0; i < 240; ++i) {
    out << i * 0.25 << ' ' << force(rng) << ' ' << force(rng) << ' ' << force(rng) << " 0 0 0\n";
  }
  return path;
}

void start_player(std::optional<SpawnedProcess>& p, const ControllerStack& stack,
                  const std::string& sequence) {
  p.reset();
  p.emplace(HAPTICCTRL_HMI_BINARY, std::vector<std::string>{"--instance", stack.instance(), "play",
                                                            sequence, "--log", "/dev/null"});
}

TEST(FaultInjection, SoftRealTimeProcessesKilledAtRandomMomentsComeBackWithoutAForceStep) {
  ControllerStack stack("fi-soft", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string url = unique_lcm_url();
  LcmMonitor monitor(url, stack.instance());
  const unsigned seed = 20261201;
  std::mt19937 rng(seed);
  const std::string sequence = write_random_force_sequence(rng);
  std::optional<SpawnedProcess> lcm;
  std::optional<SpawnedProcess> demo;
  std::optional<SpawnedProcess> player;
  start_lcm_bridge(lcm, stack, url);
  start_demo(demo, stack);
  ASSERT_TRUE(ControllerStack::eventually([&] { return coupled(stack); }, 10s)) << demo->err();
  start_player(player, stack, sequence);
  ForceStepWatch watch(stack.segment(), arm_limits(), kPeriodS);
  const std::uint64_t misses_before = stack.telemetry().misses_total;

  // Each victim comes back by being started again. The demo reconnects on its own when its
  // bridge was killed (after its 4 s answer timeout: the new bridge does not know its session);
  // a restarted demo waits for the dead one's session to expire (the bridge's 3 s watchdog).
  const auto recoupled = [&] {
    EXPECT_TRUE(ControllerStack::eventually([&] { return coupled(stack); }, 12s)) << demo->err();
  };
  const auto restart_demo = [&] {
    start_demo(demo, stack);
    recoupled();
  };
  const std::array<const char*, 4> names{"hapticctrl-udp", "hapticctrl-lcm", "hapticctrl-demo",
                                         "hapticctrl-hmi play"};
  std::uniform_int_distribution<std::size_t> victim_of(0, 3);
  std::uniform_int_distribution<int> pause_ms(100, 600);
  for (int round = 0; round < 8; ++round) {
    // A core that failed safe (a VM stall of five periods) ends the test at once, saying so.
    ASSERT_FALSE(watch.left_running()) << "before round " << round << ": " << stack.diagnostics();
    std::this_thread::sleep_for(std::chrono::milliseconds(pause_ms(rng)));
    const std::size_t victim = victim_of(rng);
    SCOPED_TRACE(std::string("round ") + std::to_string(round) + ": SIGKILL " + names[victim] +
                 " (seed " + std::to_string(seed) + ")");
    switch (victim) {
      case 0:
        stack.bridge().signal(SIGKILL);
        stack.bridge().wait(5s);
        stack.start_bridge();
        recoupled();
        break;
      case 1: {
        lcm->signal(SIGKILL);
        lcm->wait(5s);
        start_lcm_bridge(lcm, stack, url);
        const int seen = monitor.arm_states;
        EXPECT_TRUE(monitor.pump_until([&] { return monitor.arm_states > seen + 10; }, 5s))
            << lcm->err();
        break;
      }
      case 2:
        demo->signal(SIGKILL);
        restart_demo();
        break;
      default: {
        player->signal(SIGKILL);
        player->wait(5s);
        start_player(player, stack, sequence);
        const std::int64_t restarted_at = hapticctrl::to_ns(hapticctrl::MonotonicClock::now());
        EXPECT_TRUE(ControllerStack::eventually([&] {
          return watch.last_force_sample_ns() > restarted_at;
        })) << "the new player writes the operator force: "
            << player->err();
        break;
      }
    }
  }
  watch.stop();
  std::remove(sequence.c_str());
  const shm::TelemetryPayload t = stack.telemetry();
  const std::uint64_t misses = t.misses_total - misses_before;
  std::printf(
      "%llu cycles watched; largest coupling step %.4f N per cycle (rate limit %.4f, "
      "beyond the law's allowance by %.4f N); fastest operator force change %.1f N/s "
      "(limit %.1f); deadline misses %llu; %s\n",
      static_cast<unsigned long long>(watch.cycles()), watch.largest_coupling_step(),
      arm_limits().force_rate * kPeriodS, watch.largest_coupling_excess(),
      watch.fastest_operator_rate(), operator_rate_limit(), static_cast<unsigned long long>(misses),
      cycle_health(t).c_str());
  EXPECT_GT(watch.cycles(), 100U);
  EXPECT_LE(watch.largest_coupling_excess(), kRounding);
  EXPECT_LE(watch.fastest_operator_rate(), operator_rate_limit() * (1.0 + 1e-9));
  EXPECT_FALSE(watch.left_running()) << stack.diagnostics();
  EXPECT_EQ(t.core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));
  // Misses here come from the VM (see kMissDivisor), with or without kills; the printed cycle
  // health shows them. Five in a row would have failed the core safe (left_running()).
  EXPECT_LE(misses, watch.cycles() / kMissDivisor);
  EXPECT_GT(t.ctrl_accepted, 0U);
}

TEST(FaultInjection, AKilledCoreIsToldToClientAndLcmWithinMillisecondsAndTheNextCoreIsServed) {
  ControllerStack stack("fi-core", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string url = unique_lcm_url();
  LcmMonitor monitor(url, stack.instance());
  std::optional<SpawnedProcess> lcm;
  start_lcm_bridge(lcm, stack, url);
  std::vector<double> client_ms;
  std::vector<double> udp_heartbeat_ms;
  std::vector<double> lcm_heartbeat_ms;
  for (int round = 0; round < 3; ++round) {
    SCOPED_TRACE("round " + std::to_string(round));
    client::ConnectOptions options;
    options.connect_timeout = 5s;  // the bridge attaches to a new core within 100 ms
    client::Connection c({"127.0.0.1", stack.port()}, options);
    client::StateSnapshot s;
    ASSERT_TRUE(c.wait_for_answer(0, 2s, s));
    // The LCM bridge serves this core once an arm state comes after the last round's core-lost
    // event (which followed that core's last arm state): it looks for a new core every 100 ms,
    // and a core killed before it attached would go unreported (CI, 2026-12-01, round 2).
    const int arm_states_before = monitor.arm_states.load();
    ASSERT_TRUE(monitor.pump_until([&] { return monitor.arm_states > arm_states_before; }, 5s))
        << lcm->err();
    const std::size_t events_before = monitor.events_copy().size();

    const std::int64_t killed_at = hapticctrl::to_ns(hapticctrl::MonotonicClock::now());
    stack.core().signal(SIGKILL);
    stack.core().wait(5s);
    ASSERT_TRUE(ControllerStack::eventually([&] { return !c.is_open(); }, 2s));
    s = c.snapshot();
    EXPECT_EQ(s.core_state, static_cast<std::uint32_t>(shm::CoreState::kStopped));
    EXPECT_EQ(s.stop_reason, static_cast<std::uint32_t>(shm::StopReason::kCoreLost));
    EXPECT_FALSE(s.powered());
    client_ms.push_back(static_cast<double>(s.received_ns - killed_at) * 1e-6);
    EXPECT_THROW(c.set_power(true), client::ClientError);

    ASSERT_TRUE(monitor.pump_until(
        [&] {
          const auto events = monitor.events_copy();
          return events.size() > events_before && events.back().index == 0;
        },
        2s));
    const auto gone = monitor.events_copy().back();
    EXPECT_EQ(gone.kind, "core_state");
    EXPECT_EQ(gone.value, static_cast<std::int64_t>(shm::StopReason::kCoreLost)) << gone.text;
    lcm_heartbeat_ms.push_back(last_number_after(gone.text, "bridge "));
    const std::string said = "noticed ";
    ASSERT_TRUE(ControllerStack::eventually([&] {
      return count_of(stack.bridge().err(), said) == static_cast<std::size_t>(round) + 1;
    })) << stack.bridge().err();
    udp_heartbeat_ms.push_back(last_number_after(stack.bridge().err(), said));

    stack.start_core();  // replaces the segment the killed core left
    ASSERT_TRUE(stack.ready()) << stack.diagnostics();
    EXPECT_EQ(stack.core().err().find("already running"), std::string::npos);
  }
  const auto print = [](const char* what, const std::vector<double>& v) {
    std::printf("%s:", what);
    for (const double x : v) {
      std::printf(" %.2f", x);
    }
    std::printf(" ms\n");
  };
  print("SIGKILL to the client's last answer", client_ms);
  print("last heartbeat to the UDP bridge noticing", udp_heartbeat_ms);
  print("last heartbeat to the LCM bridge noticing", lcm_heartbeat_ms);
  // The median: one VM stall of several milliseconds (seen on this machine) must not decide.
  // Heartbeat ages include up to one period (the core beats once per cycle).
  EXPECT_LE(median(client_ms), kNoticeMs);
  EXPECT_LE(median(udp_heartbeat_ms), kNoticeMs + kPeriodUs * 1e-3);
  EXPECT_LE(median(lcm_heartbeat_ms), kNoticeMs + kPeriodUs * 1e-3);
}

TEST(FaultInjection, AKilledCoresLastCyclesAreWrittenOutByTheBridge) {
  // J4: only a fail-safe wrote a black box; a core killed or crashed left none. Its last cycles
  // are kept in the segment's blackbox region as well, and the UDP bridge, which maps it, writes
  // them out when it finds the core lost.
  ControllerStack stack("bblost", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  ASSERT_TRUE(ControllerStack::eventually([&] { return stack.vp().cycle > 50; }));
  const int core_pid = stack.core().pid();
  const std::uint64_t seen = stack.vp().cycle;
  stack.core().signal(SIGKILL);
  ASSERT_GE(stack.core().wait(5s), 0);
  const std::string path = shm::creator_runtime_directory() + "/hapticctrl-blackbox-" +
                           stack.instance() + "." + std::to_string(core_pid) + ".lost.csv";
  ASSERT_TRUE(ControllerStack::eventually([&] { return std::filesystem::exists(path); }, 5s))
      << stack.bridge().err();
  EXPECT_TRUE(ControllerStack::eventually([&] {
    return stack.bridge().err().find("the lost controller's last ") != std::string::npos;
  })) << stack.bridge().err();
  EXPECT_EQ(std::filesystem::status(path).permissions(),
            std::filesystem::perms::owner_read | std::filesystem::perms::owner_write);
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("cycle,scheduled_ns,wake_latency_ns", 0), 0U) << line;
  std::size_t records = 0;
  std::uint64_t last_cycle = 0;
  while (std::getline(in, line)) {
    ++records;
    last_cycle = std::stoull(line.substr(0, line.find(',')));
  }
  // A cycle's record is made at its deadline check, after its VP went out: the last cycle seen
  // may have died before its check.
  EXPECT_GE(records + 1, seen) << "every cycle from the start (fewer than the ring holds)";
  EXPECT_GE(last_cycle + 1, seen) << "it ends with the core's last cycles, not before";
}

TEST(FaultInjection, AFrozenBridgeIsStaleInputTheCouplingFadesAndResumesOnContinue) {
  ControllerStack stack("fi-stop", kPeriodUs);
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  // Couples an object 3 cm from the handle and streams it on every answer.
  SpawnedProcess client(HAPTICCTRL_STREAMING_CLIENT, {std::to_string(stack.port())});
  ASSERT_TRUE(ControllerStack::eventually([&] { return coupled(stack); }, 10s)) << client.err();
  ForceStepWatch watch(stack.segment(), arm_limits(), kPeriodS);
  const auto stale = [&] { return (stack.vp().state_word & shm::state_bits::kClientStale) != 0; };

  stack.bridge().signal(SIGSTOP);  // longer than the session watchdog (100 ms)
  EXPECT_TRUE(ControllerStack::eventually([&] { return stale() && !coupled(stack); }, 1s))
      << "the core sees the client's data go stale and fades the coupling out";
  std::this_thread::sleep_for(300ms);
  stack.bridge().signal(SIGCONT);
  EXPECT_TRUE(ControllerStack::eventually([&] { return coupled(stack) && !stale(); }, 2s))
      << "the queued frames bring the same session back: " << client.err();
  EXPECT_EQ(stack.link_stats().sessions_opened, 1U);
  EXPECT_EQ(stack.link_stats().watchdog_expiries, 0U) << "the frozen bridge's clock did not run";
  watch.stop();
  EXPECT_LE(watch.largest_coupling_excess(), kRounding);
  EXPECT_FALSE(watch.left_running());
}

}  // namespace
}  // namespace hapticctrl::test
