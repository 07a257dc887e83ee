// Soak (label `soak`, opt-in: ctest -L soak --timeout 4000): an hour of coupled running at 1 kHz
// with the demo client and random operator forces, then every counter must balance and no
// process may have grown. HAPTICCTRL_SOAK_SECONDS shortens it (a 60 s run checks the test
// itself), HAPTICCTRL_SOAK_PERIOD_US changes the rate.
//
// Balances: control frames the client sent = accepted by the bridge + dropped by it (counted)
// + dropped by the kernel at the bridge's socket (/proc/net/udp); answers the bridge sent =
// received + counted lost or late by the client + those still in flight when it closed (a few);
// events the LCM bridge published = events this test received = the core's last event index.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "support/controller_stack.hpp"
#include "support/json_fields.hpp"
#include "support/lcm_monitor.hpp"
#include "support/spawned_process.hpp"

namespace hapticctrl::test {
namespace {

using namespace std::chrono_literals;

double soak_seconds() {
  const char* text = std::getenv("HAPTICCTRL_SOAK_SECONDS");
  return text != nullptr ? std::stod(text) : 3600.0;
}

/// The controller period, and so the client's rate: 1 kHz unless HAPTICCTRL_SOAK_PERIOD_US says
/// otherwise. (On the 2-vCPU VM this project is developed on, vCPU stalls of 4-5 ms come every
/// few seconds even idle, cyclictest max 3.8 ms in 5 s on 2026-12-01; at 1 ms five of them in a
/// row fail the core safe within a second or two, and the soak rightly fails. It was run there
/// at 4 ms.)
int soak_period_us() {
  const char* text = std::getenv("HAPTICCTRL_SOAK_PERIOD_US");
  return text != nullptr ? std::stoi(text) : 1000;
}

/// Resident memory of a process [KiB].
long rss_kib(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) {
      return std::stol(line.substr(6));
    }
  }
  return -1;
}

/// Datagrams the kernel dropped at the UDP socket bound to `port` (/proc/net/udp, last column).
long socket_drops(std::uint16_t port) {
  std::ifstream udp("/proc/net/udp");
  std::string line;
  std::getline(udp, line);  // header
  char local[16];           // NOLINT(*-avoid-c-arrays): "%X" of the port
  std::snprintf(local, sizeof local, ":%04X", port);
  while (std::getline(udp, line)) {
    std::istringstream fields(line);
    std::string slot;
    std::string local_address;
    fields >> slot >> local_address;
    if (local_address.size() > 5 && local_address.substr(local_address.size() - 5) == local) {
      std::string last;
      for (std::string field; fields >> field;) {
        last = field;
      }
      return std::stol(last);
    }
  }
  return -1;
}

/// Random operator pushes of up to 4 N per axis, a new one every 0.25 s, for `seconds`.
std::string write_sequence(double seconds) {
  std::string path = "/tmp/hapticctrl-soak-" + std::to_string(getpid()) + ".seq";
  std::ofstream out(path);
  std::mt19937 rng(20261201);
  std::uniform_real_distribution<double> force(-4.0, 4.0);
  for (int i = 0; i * 0.25 <= seconds; ++i) {
    out << i * 0.25 << ' ' << force(rng) << ' ' << force(rng) << ' ' << force(rng) << " 0 0 0\n";
  }
  return path;
}

TEST(Soak, AnHourOfCoupledRunningBalancesEveryCounterAndGrowsNothing) {
  const double seconds = soak_seconds();
  const int period_us = soak_period_us();
  // The client answers every cycle. A 1 s session watchdog: an hour on a VM sees the odd
  // 100 ms stall of an ordinary process, which the default 100 ms would (rightly) end the
  // session for; the soak is about counters and memory, not that.
  ControllerStack stack("soak", period_us, {"--json", "--watchdog-ms", "1000"});
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  const std::string url = unique_lcm_url();
  LcmMonitor monitor(url, stack.instance());
  SpawnedProcess lcm(HAPTICCTRL_LCM_BINARY, {"--instance", stack.instance(), "--lcm-url", url,
                                             "--arm-rate-hz", "100", "--json"});
  SpawnedProcess demo(
      HAPTICCTRL_DEMO_BINARY,
      {"--server", "127.0.0.1:" + std::to_string(stack.port()), "--headless", "--json",
       "--duration", std::to_string(seconds), "--instance", stack.instance(), "--lcm-url", url});
  ASSERT_TRUE(ControllerStack::eventually(
      [&] { return (stack.vp().state_word & shm::state_bits::kCoupled) != 0; }, 10s))
      << demo.err();
  const std::string sequence = write_sequence(seconds);
  SpawnedProcess player(HAPTICCTRL_HMI_BINARY,
                        {"--instance", stack.instance(), "play", sequence, "--log", "/dev/null"});

  // Memory after a warm-up (a tenth of the run, at least 5 s), and at the end.
  const auto warm_up = std::chrono::duration<double>(std::max(5.0, seconds / 10));
  monitor.pump(std::chrono::duration_cast<std::chrono::milliseconds>(warm_up));
  const std::map<std::string, pid_t> pids{{"core", stack.core().pid()},
                                          {"udp", stack.bridge().pid()},
                                          {"lcm", lcm.pid()},
                                          {"demo", demo.pid()},
                                          {"hmi", player.pid()}};
  std::map<std::string, long> rss_before;
  for (const auto& [name, pid] : pids) {
    rss_before[name] = rss_kib(pid);
  }
  std::map<std::string, long> rss_after;
  ASSERT_TRUE(monitor.pump_until(
      [&] {
        for (const auto& [name, pid] : pids) {  // the last reading while each still runs
          if (const long r = rss_kib(pid); r > 0) {
            rss_after[name] = r;
          }
        }
        return demo.out().find('}') != std::string::npos;
      },
      std::chrono::milliseconds(static_cast<long>(seconds * 1000) + 30'000)))
      << demo.err();
  ASSERT_EQ(demo.wait(5s), 0) << demo.err() << stack.diagnostics();
  const shm::TelemetryPayload t = stack.telemetry();
  monitor.pump(300ms);  // the last events
  const long kernel_drops = socket_drops(stack.port());
  lcm.signal(SIGTERM);
  ASSERT_EQ(lcm.wait(10s), 0) << lcm.err();
  stack.bridge().signal(SIGTERM);
  ASSERT_EQ(stack.bridge().wait(10s), 0) << stack.bridge().err();
  player.signal(SIGTERM);
  std::remove(sequence.c_str());
  const std::string client = demo.out();
  const std::string bridge = stack.bridge().out();
  const std::string publisher = lcm.out();

  const auto dropped = [&](const char* reason) {
    return json_number(bridge.substr(bridge.find("\"dropped\"")), reason);
  };
  const double control_sent = json_number(client, "control_sent");
  const double control_accounted = json_number(bridge, "control_accepted") + dropped("sequence") +
                                   dropped("range") + static_cast<double>(kernel_drops);
  const double answers_sent = json_number(bridge, "answers_sent");
  const double answers_seen = json_number(client, "answers_received") +
                              json_number(client, "answers_lost") +
                              json_number(client, "answers_late");
  const auto events_published = static_cast<std::size_t>(json_number(publisher, "events"));
  const auto events_received = monitor.events_copy().size();
  const auto last_event_index = events_received == 0 ? 0 : monitor.events_copy().back().index;

  std::printf("soak: %.0f s at %.0f Hz, %llu cycles, core %s\n", seconds, 1e6 / period_us,
              static_cast<unsigned long long>(t.cycle), shm::core_state_name(t.core_state));
  std::printf(
      "  deadline misses %llu: %llu slots skipped after late wake-ups (wake max %.0f us), "
      "%llu cycles the degraded SERVO ran (SERVO start max %.0f us, execution max %.0f "
      "us)\n",
      static_cast<unsigned long long>(t.misses_total),
      static_cast<unsigned long long>(t.skipped_slots),
      static_cast<double>(t.wake_latency.max_ns) * 1e-3,
      static_cast<unsigned long long>(t.degraded_cycles),
      static_cast<double>(t.servo_start_delay.max_ns) * 1e-3,
      static_cast<double>(t.servo_execution.max_ns) * 1e-3);
  std::printf("  control frames: sent %.0f = accepted %.0f + dropped %.0f + kernel %ld\n",
              control_sent, json_number(bridge, "control_accepted"),
              dropped("sequence") + dropped("range"), kernel_drops);
  std::printf(
      "  answers: sent %.0f, received %.0f + lost %.0f + late %.0f (in flight at the "
      "end %.0f)\n",
      answers_sent, json_number(client, "answers_received"), json_number(client, "answers_lost"),
      json_number(client, "answers_late"), answers_sent - answers_seen);
  std::printf("  events: core %llu, published %zu, received %zu\n",
              static_cast<unsigned long long>(last_event_index), events_published, events_received);
  for (const auto& [name, before] : rss_before) {
    std::printf("  %s RSS %ld -> %ld KiB\n", name.c_str(), before, rss_after[name]);
  }

  EXPECT_EQ(t.core_state, static_cast<std::uint32_t>(shm::CoreState::kRunning));
  EXPECT_NE(client.find("\"ended\":\"duration\""), std::string::npos)
      << "the client ran its whole duration: " << client << demo.err();
  EXPECT_EQ(control_sent, control_accounted) << client << "\n" << bridge;
  EXPECT_GE(answers_sent - answers_seen, 0.0);
  EXPECT_LE(answers_sent - answers_seen, 10.0) << "only the answers in flight at the close";
  EXPECT_EQ(events_published, events_received);
  EXPECT_EQ(json_number(publisher, "events_lost"), 0.0);
  EXPECT_EQ(last_event_index, events_published);
  for (const auto& [name, before] : rss_before) {
    EXPECT_GT(before, 0) << name << " was not running after the warm-up";
    EXPECT_LE(rss_after[name] - before, 256) << name << " grew (KiB)";
  }
}

}  // namespace
}  // namespace hapticctrl::test
