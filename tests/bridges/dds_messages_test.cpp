// Tests of dds_bridge/messages.hpp: the controller's regions as ROS 2 messages, filled in place.
#include "hapticctrl/dds_bridge/messages.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "hapticctrl/shm/names.hpp"
#include "support/allocation_counter.hpp"
#include "support/payload_leaves.hpp"

namespace hapticctrl::dds_bridge {
namespace {

shm::PositionPayload sample_position() {
  shm::PositionPayload p;
  p.cycle = 42;
  p.handle_pose = {0.5, -0.1, 0.25, 0.0, 0.0, 0.7071067811865476, 0.7071067811865476};
  for (std::size_t i = 0; i < 6; ++i) {
    p.joint_position[i] = 0.1 * static_cast<double>(i);
    p.joint_velocity[i] = -0.2 * static_cast<double>(i);
    p.joint_torque[i] = 1.5 + static_cast<double>(i);
  }
  p.rendered_wrench = {1, 2, 3, 0.1, 0.2, 0.3};
  p.operator_wrench = {-4, -5, -6, -0.4, -0.5, -0.6};
  return p;
}

TEST(DdsMessages, ArmMessagesCarryThePositionSampleAndTheControllersStamp) {
  ArmMessages m("hapticctrl/default/base");
  m.fill(sample_position(), 7'250'000'000);
  EXPECT_EQ(m.pose.header_.stamp_.sec_, 7);
  EXPECT_EQ(m.pose.header_.stamp_.nanosec_, 250'000'000U);
  EXPECT_STREQ(m.pose.header_.frame_id_, "hapticctrl/default/base");
  EXPECT_DOUBLE_EQ(m.pose.pose_.position_.x_, 0.5);
  EXPECT_DOUBLE_EQ(m.pose.pose_.position_.y_, -0.1);
  EXPECT_DOUBLE_EQ(m.pose.pose_.orientation_.z_, 0.7071067811865476);  // x y z w, as ROS 2
  EXPECT_DOUBLE_EQ(m.pose.pose_.orientation_.w_, 0.7071067811865476);
  EXPECT_DOUBLE_EQ(m.rendered_wrench.wrench_.force_.y_, 2.0);
  EXPECT_DOUBLE_EQ(m.rendered_wrench.wrench_.torque_.z_, 0.3);
  EXPECT_DOUBLE_EQ(m.operator_wrench.wrench_.force_.x_, -4.0);
  EXPECT_DOUBLE_EQ(m.operator_wrench.wrench_.torque_.y_, -0.5);
  ASSERT_EQ(m.joints.name_._length, 6U);
  ASSERT_EQ(m.joints.position_._length, 6U);
  ASSERT_EQ(m.joints.velocity_._length, 6U);
  ASSERT_EQ(m.joints.effort_._length, 6U);
  EXPECT_STREQ(m.joints.name_._buffer[0], "joint1");
  EXPECT_STREQ(m.joints.name_._buffer[5], "joint6");
  EXPECT_DOUBLE_EQ(m.joints.position_._buffer[3], 0.3);
  EXPECT_DOUBLE_EQ(m.joints.velocity_._buffer[2], -0.4);
  EXPECT_DOUBLE_EQ(m.joints.effort_._buffer[4], 5.5);
  EXPECT_FALSE(m.joints.position_._release) << "DDS must not free the holder's storage";
}

TEST(DdsMessages, FillingAllocatesNothing) {
  ArmMessages arm("f");
  DiagnosticsMessage diagnostics("hapticctrl-core", "default", "f");
  const shm::PositionPayload p = sample_position();
  shm::TelemetryPayload t;
  t.core_state = static_cast<std::uint32_t>(shm::CoreState::kRunning);
  test::allocations = 0;
  test::counting = true;
  for (int i = 0; i < 100; ++i) {
    arm.fill(p, i);
    diagnostics.fill(t, true, i);
  }
  test::counting = false;
  EXPECT_EQ(test::allocations.load(), 0U);
}

std::string value_of(const DiagnosticsMessage& m, const std::string& key) {
  const auto& s = m.array.status_._buffer[0];
  for (std::uint32_t i = 0; i < s.values_._length; ++i) {
    if (key == s.values_._buffer[i].key_) {
      return s.values_._buffer[i].value_;
    }
  }
  return "<absent>";
}

TEST(DdsMessages, DiagnosticsSayTheStateAndTheCycleStatistics) {
  DiagnosticsMessage m("hapticctrl-core", "arm1", "hapticctrl/arm1/base");
  shm::TelemetryPayload t;
  t.core_state = static_cast<std::uint32_t>(shm::CoreState::kRunning);
  t.cycle = 1234;
  t.period_ns = 1'000'000;
  t.wake_latency.p99_ns = 61'500;
  t.misses_total = 3;
  m.fill(t, true, 0);
  ASSERT_EQ(m.array.status_._length, 1U);
  const auto& s = m.array.status_._buffer[0];
  EXPECT_EQ(s.level_, static_cast<std::uint8_t>(DiagnosticLevel::kOk));
  EXPECT_STREQ(s.name_, "hapticctrl-core");
  EXPECT_STREQ(s.hardware_id_, "arm1");
  EXPECT_STREQ(s.message_, "running");
  EXPECT_EQ(s.values_._length, DiagnosticsMessage::kValues);
  EXPECT_EQ(value_of(m, "cycle"), "1234");
  EXPECT_EQ(value_of(m, "period_us"), "1000.0");
  EXPECT_EQ(value_of(m, "wake_latency_p99_us"), "61.5");
  EXPECT_EQ(value_of(m, "misses_total"), "3");
  EXPECT_STREQ(m.array.header_.frame_id_, "hapticctrl/arm1/base");
}

/// The position fields the ROS 2 topics do not carry, and why: the rest must reach them.
TEST(DdsMessages, TheArmTopicsCarryEveryPositionFieldButTheseListed) {
  const auto seen = [](const shm::PositionPayload& p) {
    ArmMessages m("f");
    m.fill(p, 0);
    const auto& pose = m.pose.pose_;
    std::vector<double> v{pose.position_.x_,    pose.position_.y_,    pose.position_.z_,
                          pose.orientation_.x_, pose.orientation_.y_, pose.orientation_.z_,
                          pose.orientation_.w_};
    for (const auto* w : {&m.rendered_wrench.wrench_, &m.operator_wrench.wrench_}) {
      v.insert(v.end(), {w->force_.x_, w->force_.y_, w->force_.z_, w->torque_.x_, w->torque_.y_,
                         w->torque_.z_});
    }
    for (const auto* q : {&m.joints.position_, &m.joints.velocity_, &m.joints.effort_}) {
      v.insert(v.end(), q->_buffer, q->_buffer + q->_length);
    }
    return v;
  };
  EXPECT_THAT(test::uncarried<shm::PositionPayload>(seen),
              testing::UnorderedElementsAreArray(std::vector<std::string>{
                  // the cycle and the state: on /diagnostics, from telemetry
                  "cycle", "state_word", "core_state",
                  // on LCM's arm_state only (docs/ros2.md, Not published over DDS)
                  "handle_twist_x", "handle_twist_y", "handle_twist_z", "handle_twist_rx",
                  "handle_twist_ry", "handle_twist_rz"}));
}

/// /diagnostics carries these telemetry fields (its 14 values, level and message); the rest
/// (histogram, full latency summaries, counters of the bridges' inputs) is on LCM.
TEST(DdsMessages, DiagnosticsCarryTheseTelemetryFields) {
  const auto seen = [](const shm::TelemetryPayload& t) {
    DiagnosticsMessage m("n", "h", "f");
    m.fill(t, true, 0);
    const auto& s = m.array.status_._buffer[0];
    std::vector<std::string> v{std::to_string(s.level_), s.message_};
    for (std::uint32_t i = 0; i < s.values_._length; ++i) {
      v.emplace_back(s.values_._buffer[i].value_);
    }
    return v;
  };
  EXPECT_THAT(
      test::carried<shm::TelemetryPayload>(seen),
      testing::UnorderedElementsAreArray(std::vector<std::string>{
          "cycle", "period_ns", "rt_mode", "core_state", "stop_reason", "consecutive_misses",
          "misses_total", "degraded_cycles", "window_miss_ppm", "wake_latency_p99_ns",
          "servo_start_delay_p99_ns", "servo_execution_p99_ns", "vpr_stale", "force_rejected"}));
}

TEST(DdsMessages, DiagnosticLevelsFollowTheController) {
  DiagnosticsMessage m("hapticctrl-core", "arm1", "f");
  const auto level = [&] { return m.array.status_._buffer[0].level_; };
  shm::TelemetryPayload t;
  t.core_state = static_cast<std::uint32_t>(shm::CoreState::kRunning);
  t.window_miss_ppm = 1000;
  m.fill(t, true, 0);
  EXPECT_EQ(level(), static_cast<std::uint8_t>(DiagnosticLevel::kWarn));
  t.core_state = static_cast<std::uint32_t>(shm::CoreState::kFailSafe);
  t.stop_reason = static_cast<std::uint32_t>(shm::StopReason::kConsecutiveMisses);
  m.fill(t, true, 0);
  EXPECT_EQ(level(), static_cast<std::uint8_t>(DiagnosticLevel::kError));
  EXPECT_EQ(std::string(m.array.status_._buffer[0].message_),
            std::string("fail-safe: ") + shm::stop_reason_name(t.stop_reason));
  m.fill(t, false, 0);
  EXPECT_EQ(level(), static_cast<std::uint8_t>(DiagnosticLevel::kStale));
  EXPECT_EQ(value_of(m, "core_state"), "gone");
}

}  // namespace
}  // namespace hapticctrl::dds_bridge
