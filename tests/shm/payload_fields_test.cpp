// Tests of payload_fields.hpp: each region's field table names every byte of its struct, once,
// in declaration order, with a unit and a frame where the quantity has them.
#include "hapticctrl/shm/payload_fields.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <set>
#include <string>

#include "support/payload_leaves.hpp"

namespace hapticctrl::shm {
namespace {

/// Bytes the table's leaves cover, and whether each leaf lies after the one before (declaration
/// order, no overlap).
template <typename P>
std::pair<std::size_t, bool> covered_bytes() {
  const P p{};
  const auto* base = reinterpret_cast<const char*>(&p);  // NOLINT: byte offsets of the fields
  std::size_t bytes = 0;
  std::ptrdiff_t end = 0;
  bool ordered = true;
  for_each_leaf(p, [&](const std::string&, const Field&, const auto& value) {
    const std::ptrdiff_t at = reinterpret_cast<const char*>(&value) - base;  // NOLINT
    ordered = ordered && at >= end;
    end = at + static_cast<std::ptrdiff_t>(sizeof value);
    bytes += sizeof value;
  });
  return {bytes, ordered};
}

template <typename P>
void expect_whole_table(std::size_t reserved_bytes) {
  const auto [bytes, ordered] = covered_bytes<P>();
  EXPECT_EQ(bytes + reserved_bytes, sizeof(P))
      << "a field of the struct is missing from its table in payload_fields.hpp";
  EXPECT_TRUE(ordered) << "the table lists the fields in declaration order, each once";
  const auto columns = test::leaf_columns<P>();
  EXPECT_EQ(std::set<std::string>(columns.begin(), columns.end()).size(), columns.size())
      << "two columns share a name";
}

TEST(PayloadFields, EveryTableNamesEveryByteOfItsStructOnce) {
  expect_whole_table<VprPayload>(4);  // `reserved`
  expect_whole_table<VpPayload>(0);
  expect_whole_table<ForcePayload>(0);
  expect_whole_table<PositionPayload>(0);
  expect_whole_table<TelemetryPayload>(0);
  expect_whole_table<LinkStatsPayload>(4);  // `reserved`
}

TEST(PayloadFields, ArraysNameTheirComponents) {
  const auto columns = test::leaf_columns<PositionPayload>();
  EXPECT_THAT(columns, testing::Contains("handle_pose_qw"));
  EXPECT_THAT(columns, testing::Contains("rendered_wrench_rz"));
  EXPECT_THAT(columns, testing::Contains("joint_position_6"));
  EXPECT_THAT(test::leaf_columns<TelemetryPayload>(),
              testing::Contains("wake_histogram_10000us_plus"));
  EXPECT_THAT(test::leaf_columns<TelemetryPayload>(), testing::Contains("wake_latency_p99_ns"));
  EXPECT_THAT(test::leaf_columns<LinkStatsPayload>(), testing::Contains("dropped_rate_limited"));
  EXPECT_THAT(test::leaf_columns<VprPayload>(), testing::Contains("contacts_7_object_pose_qw"));
  EXPECT_THAT(test::leaf_columns<ForcePayload>(), testing::Contains("hand_anchor_velocity_z"));
}

TEST(PayloadFields, SpatialFieldsSayTheirFrameAndUnit) {
  int spatial = 0;
  const auto check = [&](const auto& payload) {
    for_each_field(payload, [&](const Field& f, const auto&) {
      const std::string name = f.name;
      if (name.find("wrench") != std::string::npos || name.find("pose") != std::string::npos) {
        ++spatial;
        EXPECT_STRNE(f.frame, "") << name;
        EXPECT_STRNE(f.unit, "") << name;
      }
    });
  };
  check(VprPayload{});
  check(VpPayload{});
  check(ForcePayload{});
  check(PositionPayload{});
  EXPECT_EQ(spatial, 8);
  // The two wrenches that once shared a name: one in the client's frame, one in the base frame.
  const auto frame_of = [](const auto& payload, const char* field) {
    std::string frame;
    for_each_field(payload, [&](const Field& f, const auto&) {
      if (std::strcmp(f.name, field) == 0) {
        frame = f.frame;
      }
    });
    return frame;
  };
  EXPECT_EQ(frame_of(VpPayload{}, "object_wrench"), "client");
  EXPECT_EQ(frame_of(PositionPayload{}, "rendered_wrench"), "base");
  EXPECT_EQ(frame_of(VpPayload{}, "client_handle_pose"), "client");
  EXPECT_EQ(frame_of(PositionPayload{}, "handle_pose"), "base");
}

TEST(PayloadFields, AVisitWritesThroughAMutablePayload) {
  const auto columns = test::leaf_columns<PositionPayload>();
  const auto at = std::find(columns.begin(), columns.end(), "operator_wrench_y") - columns.begin();
  const auto p = test::with_leaf<PositionPayload>(static_cast<std::size_t>(at));
  EXPECT_EQ(p.operator_wrench[1], 0.75);
  EXPECT_EQ(p.operator_wrench[0], 0.0);
}

}  // namespace
}  // namespace hapticctrl::shm
