// hapticctrl-lcm with the real core: telemetry rates, HMI commands, bad input, and the
// remote-command switch. Each test has its own LCM port (ttl=0: nothing leaves the host).
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "support/controller_stack.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::SpawnedProcess;
using Command = hapticctrl_lcm::hmi_command_t;

std::string unique_url() {
  static int counter = 0;
  return "udpm://239.255.76.67:" + std::to_string(7700 + (getpid() % 200) * 4 + counter++ % 4) +
         "?ttl=0";
}

/// A monitor on the test side: counts and keeps what hapticctrl-lcm publishes.
struct Monitor {
  lcm::LCM lcm;
  std::string prefix;
  std::atomic<int> arm_states{0};
  std::atomic<int> cycle_stats{0};
  std::atomic<std::int32_t> last_state_word{0};
  std::vector<hapticctrl_lcm::event_t> events;
  std::mutex events_mutex;

  Monitor(const std::string& url, const std::string& instance)
      : lcm(url), prefix("hapticctrl." + instance + ".") {
    // Raw subscriptions decoded here: Debian LCM 1.3.1's typed member-function subscription
    // trips UBSan inside its own header.
    lcm.subscribeFunction(prefix + "arm_state",
                          &Monitor::raw<hapticctrl_lcm::arm_state_t, &Monitor::on_arm>, this);
    lcm.subscribeFunction(prefix + "cycle_stats",
                          &Monitor::raw<hapticctrl_lcm::cycle_stats_t, &Monitor::on_stats>, this);
    lcm.subscribeFunction(prefix + "events",
                          &Monitor::raw<hapticctrl_lcm::event_t, &Monitor::on_event>, this);
  }
  template <typename M,
            void (Monitor::*Handler)(const lcm::ReceiveBuffer*, const std::string&, const M*)>
  static void raw(const lcm::ReceiveBuffer* rbuf, const std::string& channel, Monitor* self) {
    M m{};
    if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0) {
      (self->*Handler)(rbuf, channel, &m);
    }
  }
  void on_arm(const lcm::ReceiveBuffer*, const std::string&, const hapticctrl_lcm::arm_state_t* m) {
    ++arm_states;
    last_state_word = m->state_word;
  }
  void on_stats(const lcm::ReceiveBuffer*, const std::string&,
                const hapticctrl_lcm::cycle_stats_t*) {
    ++cycle_stats;
  }
  void on_event(const lcm::ReceiveBuffer*, const std::string&, const hapticctrl_lcm::event_t* m) {
    const std::lock_guard lock(events_mutex);
    events.push_back(*m);
  }
  /// Handles incoming messages for `duration`.
  void pump(std::chrono::milliseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
      lcm.handleTimeout(10);
    }
  }
  template <typename Predicate>
  bool pump_until(Predicate p, std::chrono::milliseconds timeout = 3s) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end && !p()) {
      lcm.handleTimeout(10);
    }
    return p();
  }
  void send(std::int32_t code) {
    Command c{};
    c.command = code;
    c.origin = "lcm_bridge_process_test";
    lcm.publish(prefix + "hmi_command", &c);
  }
  bool saw_event(const std::string& text) {
    const std::lock_guard lock(events_mutex);
    for (const auto& e : events) {
      if (e.text == text) {
        return true;
      }
    }
    return false;
  }
};

struct LcmStack {
  ControllerStack controller;
  std::string url = unique_url();
  SpawnedProcess bridge;
  Monitor monitor;

  LcmStack(const std::string& tag, const std::vector<std::string>& extra)
      : controller(tag),
        bridge(HAPTICCTRL_LCM_BINARY, args(extra)),
        monitor(url, controller.instance()) {}
  std::vector<std::string> args(const std::vector<std::string>& extra) const {
    std::vector<std::string> a{"--instance", controller.instance(), "--lcm-url", url, "--json"};
    a.insert(a.end(), extra.begin(), extra.end());
    return a;
  }
  /// Stops the bridge (SIGTERM) and returns its final JSON counters.
  std::string stop_bridge() {
    bridge.signal(SIGTERM);
    EXPECT_EQ(bridge.wait(5s), 0) << bridge.err();
    return bridge.out();
  }
};

TEST(LcmBridgeProcess, TelemetryArrivesAtTheConfiguredRates) {
  LcmStack s("lcmrates", {"--arm-rate-hz", "50", "--stats-rate-hz", "10"});
  ASSERT_TRUE(s.controller.ready()) << s.controller.diagnostics();
  ASSERT_TRUE(s.monitor.pump_until([&] { return s.monitor.cycle_stats > 0; })) << s.bridge.err();
  s.monitor.arm_states = 0;
  s.monitor.cycle_stats = 0;
  s.monitor.pump(2s);
  // 50 Hz on a 100 Hz controller (10 ms cycles): every other cycle; stats at 10 Hz.
  EXPECT_NEAR(s.monitor.arm_states.load(), 100, 15);
  EXPECT_NEAR(s.monitor.cycle_stats.load(), 20, 4);
  EXPECT_TRUE(s.monitor.saw_event("running")) << "the events ring is read from its start";
}

TEST(LcmBridgeProcess, HmiPowerOnPowersTheArmAndIsAnEvent) {
  LcmStack s("lcmpower", {"--allow-remote-commands"});
  ASSERT_TRUE(s.controller.ready()) << s.controller.diagnostics();
  ASSERT_TRUE(s.monitor.pump_until([&] { return s.monitor.arm_states > 0; })) << s.bridge.err();
  s.monitor.send(Command::POWER_ON);
  EXPECT_TRUE(s.monitor.pump_until([&] { return (s.monitor.last_state_word & 1) != 0; }));
  EXPECT_TRUE(s.monitor.pump_until([&] { return s.monitor.saw_event("power on"); }));
  hapticctrl_lcm::hmi_force_t f{};
  f.wrench[0] = 500.0;  // beyond the 100 N the simulated handle accepts
  s.monitor.lcm.publish(s.monitor.prefix + "hmi_force", &f);
  const std::vector<std::uint8_t> junk{9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9, 9};
  s.monitor.lcm.publish(s.monitor.prefix + "hmi_command", junk.data(),
                        static_cast<unsigned>(junk.size()));
  s.monitor.pump(300ms);
  const std::string json = s.stop_bridge();
  EXPECT_NE(json.find("\"commands_applied\":1"), std::string::npos) << json;
  EXPECT_NE(json.find("\"forces_invalid\":1"), std::string::npos) << json;
  EXPECT_NE(json.find("\"malformed\":1"), std::string::npos) << json;
}

TEST(LcmBridgeProcess, WithoutRemoteCommandsOnlyTheEmergencyStopActs) {
  LcmStack s("lcmestop", {});
  ASSERT_TRUE(s.controller.ready()) << s.controller.diagnostics();
  ASSERT_TRUE(s.monitor.pump_until([&] { return s.monitor.arm_states > 0; })) << s.bridge.err();
  s.monitor.send(Command::POWER_ON);
  s.monitor.pump(300ms);
  EXPECT_EQ(s.monitor.last_state_word & 1, 0) << "power-on refused";
  s.monitor.send(Command::EMERGENCY_STOP);
  EXPECT_TRUE(s.monitor.pump_until([&] { return (s.monitor.last_state_word & 2) != 0; }))
      << "the emergency stop is always accepted";
  EXPECT_TRUE(s.monitor.pump_until([&] { return s.monitor.saw_event("emergency stop latched"); }));
  const std::string json = s.stop_bridge();
  EXPECT_NE(json.find("\"commands_refused\":1"), std::string::npos) << json;
}

}  // namespace
}  // namespace hapticctrl
