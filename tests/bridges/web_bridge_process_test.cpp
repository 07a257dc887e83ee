// hapticctrl-web as a process on loopback: LCM telemetry in, state frames out to a page;
// page requests out as LCM HMI messages; malformed input from both sides counted, never fatal.
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>

#include "hapticctrl/lcmtypes/channels.hpp"
#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "support/child_process.hpp"
#include "support/spawned_process.hpp"
#include "support/websocket_client.hpp"

namespace hapticctrl {
namespace {

using namespace std::chrono_literals;
using Json = nlohmann::json;
using test::SpawnedProcess;
using test::WebSocketClient;

/// A web bridge for a fresh instance, and an LCM endpoint on the same local bus.
class WebBridgeProcess : public ::testing::Test {
 protected:
  void start(bool allow_remote_commands) {
    std::vector<std::string> args{"--listen", "127.0.0.1:0", "--instance", instance_,
                                  "--rate",   "60",          "--json"};
    if (allow_remote_commands) {
      args.emplace_back("--allow-remote-commands");
    }
    bridge_.emplace(HAPTICCTRL_WEB_BINARY, args);
    const std::string marker = "listening on http://127.0.0.1:";
    for (int i = 0; i < 1000 && port_ == 0; ++i) {
      const std::string err = bridge_->err();
      const auto at = err.find(marker);
      if (at != std::string::npos && err.find('\n', at) != std::string::npos) {
        port_ = static_cast<std::uint16_t>(std::stoi(err.substr(at + marker.size())));
      }
      std::this_thread::sleep_for(5ms);
    }
    ASSERT_NE(port_, 0) << bridge_->err();
  }

  /// Publishes arm states (cycle = `cycle`) until the page's frame shows it.
  bool page_sees_cycle(WebSocketClient& page, std::int64_t cycle) {
    hapticctrl_lcm::arm_state_t arm{};
    arm.cycle = cycle;
    arm.handle_pose[6] = 1.0;
    for (int i = 0; i < 100; ++i) {
      lcm_.publish(channels_.arm_state, &arm);
      if (page.receive_containing("\"cycle\":" + std::to_string(cycle), 50)) {
        return true;
      }
    }
    return false;
  }

  /// Records the hmi_command_t messages on the bus from now on.
  void record_commands() {
    command_sub_ = lcm_.subscribeFunction(
        channels_.hmi_command,
        +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*ch*/,
            std::vector<hapticctrl_lcm::hmi_command_t>* out) {
          hapticctrl_lcm::hmi_command_t m{};
          if (m.decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0) {
            out->push_back(m);
          }
        },
        &commands_);
  }
  /// What was recorded, after listening for `timeout` more.
  std::vector<hapticctrl_lcm::hmi_command_t> commands_after(std::chrono::milliseconds timeout) {
    const auto end = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < end) {
      lcm_.handleTimeout(20);
    }
    lcm_.unsubscribe(command_sub_);
    return commands_;
  }

  Json stats() const {
    const std::string response = test::http_get(port_, "/api/stats");
    const auto body = response.find("\r\n\r\n");
    return body == std::string::npos ? Json()
                                     : Json::parse(response.substr(body + 4), nullptr, false);
  }

  std::string instance_ = test::unique_instance("web");
  lcmtypes::Channels channels_ = lcmtypes::Channels::of(instance_);
  lcm::LCM lcm_{lcmtypes::kDefaultLcmUrl};
  std::optional<SpawnedProcess> bridge_;
  std::uint16_t port_ = 0;
  lcm::Subscription* command_sub_ = nullptr;
  std::vector<hapticctrl_lcm::hmi_command_t> commands_;
};

TEST_F(WebBridgeProcess, GreetsThePageAndPushesTheTelemetryItHears) {
  ASSERT_NO_FATAL_FAILURE(start(false));
  WebSocketClient page(port_);
  ASSERT_EQ(page.status(), 101);
  const auto hello = page.receive_containing("\"type\":\"hello\"");
  ASSERT_TRUE(hello);
  EXPECT_FALSE(Json::parse(*hello)["remote_commands"].get<bool>());
  const auto model = page.receive_containing("\"type\":\"model\"");
  ASSERT_TRUE(model);
  EXPECT_EQ(Json::parse(*model)["joints"].size(), 6U);
  ASSERT_TRUE(page_sees_cycle(page, 4242));
  EXPECT_NE(test::http_get(port_, "/").find("hapticctrl"), std::string::npos);
  EXPECT_NE(test::http_get(port_, "/vendor/three/three.module.js").find("200 OK"),
            std::string::npos);
}

TEST_F(WebBridgeProcess, ForwardsOnlyTheEmergencyStopWithoutRemoteCommands) {
  ASSERT_NO_FATAL_FAILURE(start(false));
  WebSocketClient page(port_);
  ASSERT_TRUE(page.receive_containing("\"type\":\"history\""));
  record_commands();
  page.send_text(R"({"type":"command","command":"power_on"})");
  EXPECT_TRUE(page.receive_containing("remote commands are disabled"));
  page.send_text(R"({"type":"command","command":"emergency_stop"})");
  const auto got = commands_after(500ms);
  ASSERT_EQ(got.size(), 1U);
  EXPECT_EQ(got[0].command, hapticctrl_lcm::hmi_command_t::EMERGENCY_STOP);
  EXPECT_EQ(got[0].origin.rfind("web 127.0.0.1:", 0), 0U) << got[0].origin;
}

TEST_F(WebBridgeProcess, ForwardsPowerAndForceWhenAllowed) {
  ASSERT_NO_FATAL_FAILURE(start(true));
  WebSocketClient page(port_);
  ASSERT_TRUE(page.receive_containing("\"type\":\"history\""));
  hapticctrl_lcm::hmi_force_t force{};
  bool force_seen = false;
  struct Sink {
    hapticctrl_lcm::hmi_force_t* m;
    bool* seen;
  } sink{&force, &force_seen};
  auto* sub = lcm_.subscribeFunction(
      channels_.hmi_force,
      +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*ch*/, Sink* s) {
        *s->seen = s->m->decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0;
      },
      &sink);
  page.send_text(R"({"type":"force","wrench":[0,4.5,0,0,0,0.1]})");
  for (int i = 0; i < 50 && !force_seen; ++i) {
    lcm_.handleTimeout(20);
  }
  lcm_.unsubscribe(sub);
  ASSERT_TRUE(force_seen);
  EXPECT_EQ(force.wrench[1], 4.5);
  EXPECT_EQ(force.wrench[5], 0.1);
  page.send_text(R"({"type":"command","command":"power_on"})");
  EXPECT_TRUE(page.receive_containing("\"ok\":true"));
}

TEST_F(WebBridgeProcess, CountsMalformedInputFromPagesAndTheBusAndKeepsServing) {
  ASSERT_NO_FATAL_FAILURE(start(true));
  {
    WebSocketClient page(port_);
    ASSERT_TRUE(page.receive_containing("\"type\":\"history\""));
    page.send_text("{not json");
    page.send_text(R"({"type":"force","wrench":[1e9,0,0,0,0,0]})");
    page.send_frame(0x82, "binary");
    page.send_raw(std::string("\x81\xfe\xff\xff", 4));  // 64 KiB announced, then gone
    page.vanish();
  }
  // An event whose first string claims INT32_MIN bytes: the decoder must never see it.
  hapticctrl_lcm::event_t e{};
  e.kind = "k";
  e.text = "t";
  std::string bytes(static_cast<std::size_t>(e.getEncodedSize()), '\0');
  e.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  bytes.replace(8 + 32, 4, std::string("\x80\x00\x00\x00", 4));
  lcm_.publish(channels_.events, bytes.data(), static_cast<unsigned>(bytes.size()));
  lcm_.publish(channels_.arm_state, "short", 5);
  // Every counter reaches its count (the page may be registered only after its greeting).
  Json s;
  for (int i = 0; i < 150; ++i) {
    s = stats();
    if (s.is_object() && s["bridge"]["lcm_malformed"] == 2 && s["bridge"]["malformed"] == 1 &&
        s["bridge"]["out_of_range"] == 1 && s["server"]["dropped_binary"] == 1 &&
        s["server"]["pages"] == 0) {
      break;
    }
    std::this_thread::sleep_for(20ms);
  }
  ASSERT_TRUE(s.is_object());
  EXPECT_EQ(s["bridge"]["lcm_malformed"], 2);
  EXPECT_EQ(s["bridge"]["malformed"], 1);
  EXPECT_EQ(s["bridge"]["out_of_range"], 1);
  EXPECT_EQ(s["server"]["dropped_binary"], 1);
  EXPECT_EQ(s["server"]["pages"], 0);
  WebSocketClient page(port_);
  ASSERT_EQ(page.status(), 101);
  EXPECT_TRUE(page_sees_cycle(page, 77));
}

TEST_F(WebBridgeProcess, StopsCleanlyOnSigtermWithPagesOpen) {
  ASSERT_NO_FATAL_FAILURE(start(false));
  WebSocketClient a(port_);
  WebSocketClient b(port_);
  ASSERT_TRUE(a.receive_containing("\"type\":\"history\""));
  ASSERT_TRUE(b.receive_containing("\"type\":\"history\""));
  bridge_->signal(SIGTERM);
  EXPECT_EQ(bridge_->wait(10s), 0) << bridge_->err();
  const Json final_counters = Json::parse(bridge_->out(), nullptr, false);
  ASSERT_TRUE(final_counters.is_object()) << bridge_->out();
  EXPECT_EQ(final_counters["server"]["pages_opened"], 2);
}

TEST(WebBridgeProcessOptions, RefusesBadOptionsWithUsage) {
  SpawnedProcess bad(HAPTICCTRL_WEB_BINARY, {"--listen", "nowhere"});
  EXPECT_EQ(bad.wait(), 64);
  EXPECT_NE(bad.err().find("--listen"), std::string::npos);
  SpawnedProcess missing_model(HAPTICCTRL_WEB_BINARY,
                               {"--listen", "127.0.0.1:0", "--arm-model", "/nonexistent.arm"});
  EXPECT_EQ(missing_model.wait(), 1);
  EXPECT_NE(missing_model.err().find("/nonexistent.arm"), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl
