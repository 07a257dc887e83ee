// Tests of regions.hpp: position, telemetry and link_stats as LCM messages and back. Every field
// of each payload's table survives the round trip, so the log's CSV and the web page (which read
// the messages back through the tables) carry every field.
#include "hapticctrl/lcmtypes/regions.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "hapticctrl/shm/payload_text.hpp"
#include "support/payload_leaves.hpp"

namespace hapticctrl::lcmtypes {
namespace {

/// The columns of P that do not come back from `to` then `from`; `real` makes the payload one a
/// writer can produce.
template <typename P, typename To, typename From>
std::vector<std::string> lost_in_round_trip(
    To to, From from, P (*real)(P) = [](P p) { return p; }) {
  std::vector<std::string> lost;
  const auto columns = test::leaf_columns<P>();
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const P p = real(test::with_leaf<P>(i));
    if (shm::csv_row(from(to(p, 0))) != shm::csv_row(p)) {
      lost.push_back(columns[i]);
    }
  }
  return lost;
}

TEST(Regions, EveryFieldOfPositionTelemetryAndLinkStatsComesBack) {
  EXPECT_THAT((lost_in_round_trip<shm::PositionPayload>(to_arm_state, from_arm_state)),
              testing::IsEmpty());
  EXPECT_THAT((lost_in_round_trip<shm::TelemetryPayload>(to_cycle_stats, from_cycle_stats)),
              testing::IsEmpty());
  // The peer is text "a.b.c.d:port" while a session is open, and a port has 16 bits.
  const auto with_session = [](shm::LinkStatsPayload s) {
    s.session_id = s.session_id != 0 ? s.session_id : 1;
    s.peer_port = std::min(s.peer_port, 65535U);
    return s;
  };
  EXPECT_THAT(
      (lost_in_round_trip<shm::LinkStatsPayload>(to_bridge_stats, from_bridge_stats, with_session)),
      testing::IsEmpty());
}

TEST(Regions, ArmStateCopiesEveryField) {
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

TEST(Regions, CycleStatsCarryLatenciesAndTheHistogram) {
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

TEST(Regions, BridgeStatsNameEveryDropReason) {
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

TEST(Regions, ALogWithOtherDropReasonsOrNoPeerStillReads) {
  hapticctrl_lcm::bridge_stats_t m{};
  m.peer = "not an address";
  m.drop_reasons = 2;
  m.drop_names = {"crc", "a reason of a later version"};
  m.dropped = {4, 9};
  const shm::LinkStatsPayload s = from_bridge_stats(m);
  EXPECT_EQ(s.peer_ipv4, 0U);
  EXPECT_EQ(s.peer_port, 0U);
  EXPECT_EQ(s.dropped[static_cast<std::size_t>(shm::LinkDrop::kCrc)], 4U);
  m.peer = "10.0.0.2:99999";
  EXPECT_EQ(from_bridge_stats(m).peer_port, 0U) << "a port out of range is no port";
}

}  // namespace
}  // namespace hapticctrl::lcmtypes
