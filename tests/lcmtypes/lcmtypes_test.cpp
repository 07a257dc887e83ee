// Every LCM type survives a publish/subscribe round trip, in-process (memq://) and over loopback
// multicast with ttl=0 (nothing leaves the host).
#include <gtest/gtest.h>

#include <lcm/lcm-cpp.hpp>
#include <string>
#include <vector>

#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/bridge_stats_t.hpp"
#include "hapticctrl_lcm/coupling_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"
#include "hapticctrl_lcm/latency_t.hpp"
#include "hapticctrl_lcm/scene_t.hpp"

namespace hapticctrl {
namespace {

template <typename T>
std::vector<std::uint8_t> bytes_of(const T& m) {
  std::vector<std::uint8_t> b(static_cast<std::size_t>(m.getEncodedSize()));
  EXPECT_EQ(m.encode(b.data(), 0, static_cast<int>(b.size())), static_cast<int>(b.size()));
  return b;
}

/// Publishes `sent` on a fresh channel and returns what a subscriber decoded.
template <typename T>
T round_trip(lcm::LCM& lcm, const T& sent) {
  static int counter = 0;
  const std::string channel = "test." + std::to_string(getpid()) + "." + std::to_string(++counter);
  T got{};
  bool received = false;
  struct Sink {
    T* out;
    bool* flag;
  } sink{&got, &received};
  // The raw subscription (decoded here), as hapticctrl-lcm uses: Debian LCM 1.3.1's typed
  // member-function subscription trips UBSan inside its own header.
  lcm::Subscription* sub = lcm.subscribeFunction(
      channel,
      +[](const lcm::ReceiveBuffer* rbuf, const std::string& /*ch*/, Sink* s) {
        *s->flag = s->out->decode(rbuf->data, 0, static_cast<int>(rbuf->data_size)) >= 0;
      },
      &sink);
  lcm.publish(channel, &sent);
  for (int i = 0; i < 100 && !received; ++i) {
    lcm.handleTimeout(20);
  }
  lcm.unsubscribe(sub);
  EXPECT_TRUE(received) << channel;
  return got;
}

/// One message of every type with distinctive values.
struct Samples {
  hapticctrl_lcm::latency_t latency{};
  hapticctrl_lcm::cycle_stats_t stats{};
  hapticctrl_lcm::arm_state_t arm{};
  hapticctrl_lcm::coupling_t coupling{};
  hapticctrl_lcm::bridge_stats_t bridge{};
  hapticctrl_lcm::event_t event{};
  hapticctrl_lcm::hmi_command_t command{};
  hapticctrl_lcm::hmi_force_t force{};
  hapticctrl_lcm::scene_t scene{};

  Samples() {
    latency = {1, 2, 3, 4, 5, 6, 7, 8};
    stats = {};
    stats.cycle = 123456789012LL;
    stats.wake_latency = latency;
    stats.wake_histogram[12] = 3;
    stats.histogram_edges_us[11] = 10000;
    arm = {};
    arm.cycle = 42;
    arm.handle_pose[6] = 1.0;
    arm.joint_torque[5] = -0.25;
    coupling = {};
    coupling.session_id = 9;
    coupling.object_attached = true;
    coupling.client_age_ms = 1.5;
    bridge = {};
    bridge.peer = "127.0.0.1:5000";
    bridge.drop_reasons = 2;
    bridge.drop_names = {"crc", "token"};
    bridge.dropped = {3, 4};
    event = {};
    event.kind = "power";
    event.text = "power on";
    event.index = 17;
    command = {};
    command.command = hapticctrl_lcm::hmi_command_t::EMERGENCY_STOP;
    command.origin = "test";
    force = {};
    force.wrench[2] = -5.5;
    force.origin = "test";
    scene = {};
    scene.steps = 1234;
    scene.mobile_pose[6] = 1.0;
    scene.penetration = 0.002;
    scene.rtt_last_us = 850.5;
  }
};

void expect_every_type_round_trips(lcm::LCM& lcm) {
  ASSERT_TRUE(lcm.good());
  const Samples s;
  EXPECT_EQ(bytes_of(round_trip(lcm, s.latency)), bytes_of(s.latency));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.stats)), bytes_of(s.stats));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.arm)), bytes_of(s.arm));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.coupling)), bytes_of(s.coupling));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.bridge)), bytes_of(s.bridge));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.event)), bytes_of(s.event));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.command)), bytes_of(s.command));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.force)), bytes_of(s.force));
  EXPECT_EQ(bytes_of(round_trip(lcm, s.scene)), bytes_of(s.scene));
  EXPECT_EQ(round_trip(lcm, s.bridge).drop_names[1], "token");
  EXPECT_EQ(round_trip(lcm, s.stats).cycle, 123456789012LL);
}

TEST(LcmTypes, EveryTypeRoundTripsInProcess) {
  lcm::LCM lcm("memq://");
  expect_every_type_round_trips(lcm);
}

TEST(LcmTypes, EveryTypeRoundTripsOverLoopbackMulticast) {
  lcm::LCM lcm("udpm://239.255.76.67:7667?ttl=0");
  expect_every_type_round_trips(lcm);
}

TEST(LcmTypes, TruncatedBytesFailToDecode) {
  const Samples s;
  const auto b = bytes_of(s.event);
  hapticctrl_lcm::event_t back;
  EXPECT_LT(back.decode(b.data(), 0, static_cast<int>(b.size()) - 3), 0);
  EXPECT_GT(back.decode(b.data(), 0, static_cast<int>(b.size())), 0);
}

}  // namespace
}  // namespace hapticctrl
