// hapticctrl-lcm with the real core: telemetry rates, HMI commands, bad input, and the
// remote-command switch. Each test has its own LCM port (ttl=0: nothing leaves the host).
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "support/controller_stack.hpp"
#include "support/lcm_monitor.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;
using test::SpawnedProcess;
using Command = hapticctrl_lcm::hmi_command_t;
using test::unique_lcm_url;

struct LcmStack {
  ControllerStack controller;
  std::string url = unique_lcm_url();
  SpawnedProcess bridge;
  test::LcmMonitor monitor;

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
