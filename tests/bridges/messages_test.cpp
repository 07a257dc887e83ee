// Tests of messages.hpp: shared-memory payloads to LCM messages (lcmtypes/), and the instance's
// channel names.
#include "hapticctrl/lcm_bridge/messages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "support/payload_leaves.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

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
  const auto m = to_coupling(vp, vpr, t, TimePoint{std::chrono::microseconds(3500)}, 0);
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
  auto m = to_coupling(vp, shm::VprPayload{}, shm::TelemetryPayload{}, TimePoint{}, 0);
  EXPECT_EQ(m.contacts, 2);
  EXPECT_EQ(m.surface_point[0], 0.5);
  EXPECT_EQ(m.surface_normal[0], -1.0);
  EXPECT_DOUBLE_EQ(m.surface_depth_mm, 5.0);
  EXPECT_EQ(m.surface_force, 10.0);
  EXPECT_DOUBLE_EQ(m.surface_hidden_mm, 2.0);
  EXPECT_EQ(m.surface_withheld, 0.004);
  EXPECT_DOUBLE_EQ(m.contact_age_ms, 3.0);
  vp.contact_age_ns = -1;
  m = to_coupling(vp, shm::VprPayload{}, shm::TelemetryPayload{}, TimePoint{}, 0);
  EXPECT_EQ(m.contact_age_ms, -1.0) << "no contact in force";
}

/// The VP and VPr fields the coupling message does not carry, and why: the rest must reach it.
TEST(Messages, CouplingCarriesEveryFieldOfVpAndVprButTheseListed) {
  const auto encoded = [](const hapticctrl_lcm::coupling_t& m) {
    std::string bytes(static_cast<std::size_t>(m.getEncodedSize()), '\0');
    m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    return bytes;
  };
  const shm::VprPayload vpr;
  const shm::TelemetryPayload t;
  const auto vp_uncarried = test::uncarried<shm::VpPayload>(
      [&](const shm::VpPayload& vp) { return encoded(to_coupling(vp, vpr, t, TimePoint{}, 0)); });
  EXPECT_THAT(vp_uncarried,
              testing::UnorderedElementsAreArray(std::vector<std::string>{
                  // the core's echo of the client's own figures: the client's statistics
                  "echo_client_time_ns",
                  // on arm_state (position) and cycle_stats (telemetry)
                  "core_state", "stop_reason", "joint_position_1", "joint_position_2",
                  "joint_position_3", "joint_position_4", "joint_position_5", "joint_position_6",
                  "joint_velocity_1", "joint_velocity_2", "joint_velocity_3", "joint_velocity_4",
                  "joint_velocity_5", "joint_velocity_6",
                  // the client's view of the handle's speed: its pose is enough to plot
                  "client_handle_twist_x", "client_handle_twist_y", "client_handle_twist_z",
                  "client_handle_twist_rx", "client_handle_twist_ry", "client_handle_twist_rz",
                  // the contact coupling's terms: in hapticctrl-hmi status (regions.vp)
                  "contact_normal_x", "contact_normal_y", "contact_normal_z",
                  "normal_gains_stiffness", "normal_gains_damping", "limits_force", "limits_torque",
                  "max_contact_stiffness", "contacts_rejected"}));
  // What it carries of VPr: the session, the object's state, its energy in, the link and the
  // sample's age (with a session); the client's parameters and contacts are not telemetry.
  const shm::VpPayload vp;
  const auto carried = test::carried<shm::VprPayload>([&](shm::VprPayload r) {
    r.session_id = r.session_id != 0 ? r.session_id : 1;
    return encoded(to_coupling(vp, r, t, TimePoint{}, 0));
  });
  EXPECT_THAT(carried,
              testing::UnorderedElementsAreArray(std::vector<std::string>{
                  "session_id",     "received_time_ns", "link_delay_ns",   "link_jitter_ns",
                  "link_loss_ppm",  "client_energy_in", "flags",           "object_pose_x",
                  "object_pose_y",  "object_pose_z",    "object_pose_qx",  "object_pose_qy",
                  "object_pose_qz", "object_pose_qw",   "object_twist_x",  "object_twist_y",
                  "object_twist_z", "object_twist_rx",  "object_twist_ry", "object_twist_rz"}));
}

TEST(Messages, EventsAreDescribed) {
  shm::Event e;
  e.index = 4;
  e.cycle = 9;
  e.kind = shm::EventKind::kCoreState;
  e.code = static_cast<std::uint32_t>(shm::CoreState::kFailSafe);
  e.value = static_cast<std::uint64_t>(shm::StopReason::kConsecutiveMisses);
  const auto m = to_event(e, 2, time_point_from_ns(e.time_ns) + std::chrono::milliseconds(3),
                          1'700'000'000'000'000);
  EXPECT_EQ(m.utime, 1'700'000'000'000'000 - 3'000) << "when the core recorded it, wall clock";
  EXPECT_EQ(m.kind, "core_state");
  EXPECT_EQ(m.text, "fail-safe: 5 consecutive deadline misses");
  EXPECT_EQ(m.lost_before, 2);
}

}  // namespace
}  // namespace hapticctrl::lcm_bridge
