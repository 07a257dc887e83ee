// Tests of payload_text.hpp: a payload's CSV columns and JSON object, from its field table.
#include "hapticctrl/shm/payload_text.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <string>

namespace hapticctrl::shm {
namespace {

using testing::HasSubstr;
using testing::Not;

long commas(const std::string& s) {
  return std::count(s.begin(), s.end(), ',');
}

TEST(PayloadText, TheCsvRowHasAValuePerColumn) {
  PositionPayload p;
  p.cycle = 42;
  p.joint_position[1] = -0.5;
  p.rendered_wrench[2] = 1.25;
  const std::string header = csv_header<PositionPayload>();
  const std::string row = csv_row(p);
  EXPECT_EQ(header.rfind("cycle,state_word,core_state,joint_position_1,", 0), 0U) << header;
  EXPECT_THAT(header, HasSubstr(",handle_pose_x,handle_pose_y,handle_pose_z,handle_pose_qx,"));
  EXPECT_EQ(commas(header), 3 + 6 * 3 + 7 + 6 * 3 - 1);
  EXPECT_EQ(commas(row), commas(header));
  EXPECT_EQ(row.rfind("42,0,0,0,-0.5,", 0), 0U) << row;
  EXPECT_THAT(row, HasSubstr(",1.25,0,0,0"));
}

TEST(PayloadText, NestedStructsAndNamedBinsUnroll) {
  TelemetryPayload t;
  t.wake_latency.p99_ns = 90'000;
  t.wake_histogram.back() = 3;
  const std::string header = csv_header<TelemetryPayload>();
  EXPECT_THAT(header, HasSubstr(",wake_latency_p99_ns,"));
  EXPECT_THAT(header, HasSubstr(",wake_histogram_0_2us,"));
  EXPECT_EQ(header.substr(header.size() - 27), "wake_histogram_10000us_plus");
  EXPECT_EQ(commas(csv_row(t)), commas(header));
  EXPECT_EQ(csv_row(t).back(), '3');
}

TEST(PayloadText, JsonKeepsArraysAndNestsStructs) {
  TelemetryPayload t;
  t.cycle = 7;
  t.wake_latency.max_ns = 12;
  const std::string json = fields_json(t);
  EXPECT_EQ(json.rfind("{\"cycle\":7,\"period_ns\":0,", 0), 0U) << json;
  EXPECT_THAT(json, HasSubstr("\"wake_latency\":{\"min_ns\":0,\"avg_ns\":0,\"max_ns\":12,"));
  EXPECT_THAT(json, HasSubstr("\"wake_histogram\":[0,0,0,0,0,0,0,0,0,0,0,0,0]}"));
  VprPayload vpr;
  vpr.contacts[1].stiffness = 2000;
  EXPECT_THAT(fields_json(vpr), HasSubstr("\"contacts\":[{\"point\":[0,0,0],"));
  EXPECT_THAT(fields_json(vpr), HasSubstr("\"stiffness\":2000,"));
}

TEST(PayloadText, WhatJsonCannotCarryIsNullAndAnEmptyCsvCell) {
  VpPayload vp;
  vp.channel_energy_out = std::numeric_limits<double>::quiet_NaN();
  vp.object_wrench[2] = std::numeric_limits<double>::infinity();
  const std::string json = fields_json(vp);
  EXPECT_THAT(json, HasSubstr("\"object_wrench\":[0,0,null,0,0,0]"));
  EXPECT_THAT(json, HasSubstr("\"channel_energy_out\":null"));
  EXPECT_THAT(json, Not(HasSubstr("nan")));
  EXPECT_THAT(json, Not(HasSubstr("inf")));
  EXPECT_THAT(csv_row(vp), HasSubstr(",0,0,,0,0,0,"));
}

TEST(PayloadText, AnAddressIsDottedText) {
  LinkStatsPayload s;
  s.peer_ipv4 = 0x7F000001;
  s.peer_port = 40000;
  EXPECT_THAT(fields_json(s), HasSubstr("\"peer_ipv4\":\"127.0.0.1\",\"peer_port\":40000"));
  EXPECT_THAT(csv_row(s), HasSubstr(",127.0.0.1,40000,"));
}

}  // namespace
}  // namespace hapticctrl::shm
