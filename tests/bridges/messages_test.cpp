// Tests of messages.hpp: shared-memory payloads to LCM messages (lcmtypes/), and the instance's
// channel names.
#include "hapticctrl/lcm_bridge/messages.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::lcm_bridge {
namespace {

TEST(Messages, ArmStateCopiesEveryField) {
  shm::PositionPayload p;
  p.cycle = 7;
  p.state_word = shm::state_bits::kPowered;
  p.joint_position[2] = 0.5;
  p.joint_torque[5] = -1.0;
  p.handle_pose = {0.1, 0.2, 0.3, 0, 0, 0, 1};
  p.operator_wrench[1] = 3.0;
  p.rendered_wrench[0] = -2.0;
  const auto m = to_arm_state(p, 99);
  EXPECT_EQ(m.utime, 99);
  EXPECT_EQ(m.cycle, 7);
  EXPECT_EQ(m.state_word, 1);
  EXPECT_EQ(m.joint_position[2], 0.5);
  EXPECT_EQ(m.joint_torque[5], -1.0);
  EXPECT_EQ(m.handle_pose[1], 0.2);
  EXPECT_EQ(m.operator_wrench[1], 3.0);
  EXPECT_EQ(m.rendered_wrench[0], -2.0);
}

TEST(Messages, CouplingCarriesLinkQuality) {
  shm::VpPayload vp;
  vp.cycle = 10;
  vp.state_word = shm::state_bits::kClientStale;
  vp.echo_client_sequence = 55;
  vp.object_wrench[0] = 1.5;
  shm::VprPayload vpr;
  vpr.session_id = 3;
  vpr.flags = shm::vpr_flags::kObjectAttached;
  vpr.received_time_ns = 1'000'000;
  shm::TelemetryPayload t;
  t.vpr_stale = 12;
  vp.sample_age_ns = 7'500'000;
  vp.loop_delay_ns = 12'000'000;
  vpr.link_delay_ns = 5'000'000;  // the bridge's measure, as the core took it
  vpr.link_jitter_ns = 250'000;
  vpr.link_loss_ppm = 100'000;
  vp.gains = {868.0, 20.0, 0.3, 0.01};
  vp.channel_energy_in = 0.25;
  vp.channel_energy_out = 1.5;
  vpr.client_energy_in = 1.75;
  const auto m = to_coupling(vp, vpr, t, 3'500'000, 0);
  EXPECT_DOUBLE_EQ(m.sample_age_ms, 7.5);
  EXPECT_DOUBLE_EQ(m.loop_delay_ms, 12.0);
  EXPECT_DOUBLE_EQ(m.link_delay_ms, 5.0);
  EXPECT_DOUBLE_EQ(m.link_jitter_ms, 0.25);
  EXPECT_DOUBLE_EQ(m.link_loss, 0.1);
  EXPECT_EQ(m.gains[0], 868.0);
  EXPECT_EQ(m.channel_energy_in, 0.25);
  EXPECT_EQ(m.channel_energy_out, 1.5);
  EXPECT_EQ(m.client_energy_in, 1.75);
  EXPECT_EQ(m.session_id, 3);
  EXPECT_TRUE(m.object_attached);
  EXPECT_TRUE(m.client_stale);
  EXPECT_DOUBLE_EQ(m.client_age_ms, 2.5);
  EXPECT_EQ(m.client_sequence, 55);
  EXPECT_EQ(m.vpr_stale_cycles, 12);
  EXPECT_EQ(m.object_wrench[0], 1.5);
}

TEST(Messages, CouplingCarriesTheSurfaceRenderedOnTheHandle) {
  shm::VpPayload vp;
  vp.contacts = 2;
  vp.surface_point = {0.5, 0.0, 0.2};
  vp.surface_normal = {-1.0, 0.0, 0.0};
  vp.surface_depth = 0.005;
  vp.surface_force = 10.0;
  vp.surface_hidden = 0.002;
  vp.surface_withheld = 0.004;
  vp.contact_age_ns = 3'000'000;
  auto m = to_coupling(vp, shm::VprPayload{}, shm::TelemetryPayload{}, 0, 0);
  EXPECT_EQ(m.contacts, 2);
  EXPECT_EQ(m.surface_point[0], 0.5);
  EXPECT_EQ(m.surface_normal[0], -1.0);
  EXPECT_DOUBLE_EQ(m.surface_depth_mm, 5.0);
  EXPECT_EQ(m.surface_force, 10.0);
  EXPECT_DOUBLE_EQ(m.surface_hidden_mm, 2.0);
  EXPECT_EQ(m.surface_withheld, 0.004);
  EXPECT_DOUBLE_EQ(m.contact_age_ms, 3.0);
  vp.contact_age_ns = -1;
  m = to_coupling(vp, shm::VprPayload{}, shm::TelemetryPayload{}, 0, 0);
  EXPECT_EQ(m.contact_age_ms, -1.0) << "no contact in force";
}

TEST(Messages, CycleStatsCarryLatenciesAndTheHistogram) {
  shm::TelemetryPayload t;
  t.cycle = 1000;
  t.misses_total = 4;
  t.wake_latency.p99_ns = 90'000;
  t.wake_histogram[5] = 17;
  const auto m = to_cycle_stats(t, 0);
  EXPECT_EQ(m.cycle, 1000);
  EXPECT_EQ(m.misses_total, 4);
  EXPECT_EQ(m.wake_latency.p99_ns, 90'000);
  EXPECT_EQ(m.wake_histogram[5], 17);
  EXPECT_EQ(m.histogram_edges_us[11], 10000);
}

TEST(Messages, BridgeStatsNameEveryDropReason) {
  shm::LinkStatsPayload s;
  s.session_id = 2;
  s.peer_ipv4 = 0x7F000001;
  s.peer_port = 40000;
  s.dropped[static_cast<std::size_t>(shm::LinkDrop::kCrc)] = 5;
  const auto m = to_bridge_stats(s, 0);
  EXPECT_EQ(m.peer, "127.0.0.1:40000");
  ASSERT_EQ(m.drop_reasons, static_cast<std::int32_t>(shm::kLinkDropCount));
  EXPECT_EQ(m.drop_names[3], "crc");
  EXPECT_EQ(m.dropped[3], 5);
}

TEST(Messages, EventsAreDescribed) {
  shm::Event e;
  e.index = 4;
  e.cycle = 9;
  e.kind = shm::EventKind::kCoreState;
  e.code = static_cast<std::uint32_t>(shm::CoreState::kFailSafe);
  e.value = static_cast<std::uint64_t>(shm::StopReason::kConsecutiveMisses);
  const auto m = to_event(e, 2, e.time_ns + 3'000'000, 1'700'000'000'000'000);
  EXPECT_EQ(m.utime, 1'700'000'000'000'000 - 3'000) << "when the core recorded it, wall clock";
  EXPECT_EQ(m.kind, "core_state");
  EXPECT_EQ(m.text, "fail-safe: 5 consecutive deadline misses");
  EXPECT_EQ(m.lost_before, 2);
}

}  // namespace
}  // namespace hapticctrl::lcm_bridge
