// Tests of participant.hpp: a DDS participant, its writers and readers, on loopback.
#include "hapticctrl/ros2types/participant.hpp"

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "hapticctrl/ros2types/names.hpp"
#include "hapticctrl/ros2types/qos.hpp"
#include "support/dds_loopback.hpp"

namespace hapticctrl::ros2types {
namespace {

TEST(Ros2Participant, ASampleWrittenIsTakenWithItsRos2TypeName) {
  Participant p(test::use_loopback_dds());
  const Qos qos = command_qos();
  const std::string topic = dds_topic("/participant_test", topic::kHandlePose);
  const dds_entity_t reader = p.reader(geometry_msgs_msg_dds__PoseStamped__desc, topic, qos.get());
  const dds_entity_t writer = p.writer(geometry_msgs_msg_dds__PoseStamped__desc, topic, qos.get());
  std::array<char, 64> type{};
  ASSERT_GT(dds_get_type_name(dds_get_topic(writer), type.data(), type.size()), 0);
  EXPECT_STREQ(type.data(), "geometry_msgs::msg::dds_::PoseStamped_");
  std::array<char, 64> name{};
  ASSERT_GT(dds_get_name(dds_get_topic(reader), name.data(), name.size()), 0);
  EXPECT_STREQ(name.data(), "rt/participant_test/handle_pose");

  std::string frame = "f";
  geometry_msgs_msg_dds__PoseStamped_ sent{};
  sent.header = {stamp_of(1'500'000'000), frame.data()};
  sent.pose.position = {0.1, 0.2, 0.3};
  sent.pose.orientation = {0, 0, 0, 1};
  ASSERT_EQ(dds_write(writer, &sent), 0);
  std::array<void*, 1> samples{};
  std::array<dds_sample_info_t, 1> infos{};
  dds_return_t n = 0;
  for (int i = 0; i < 200 && n <= 0; ++i) {  // bounded: 2 s
    n = dds_take(reader, samples.data(), infos.data(), 1, 1);
    if (n <= 0) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  ASSERT_EQ(n, 1);
  const auto& got = *static_cast<const geometry_msgs_msg_dds__PoseStamped_*>(samples[0]);
  EXPECT_EQ(got.header.stamp.sec, 1);
  EXPECT_EQ(got.header.stamp.nanosec, 500'000'000U);
  EXPECT_STREQ(got.header.frame_id, "f");
  EXPECT_DOUBLE_EQ(got.pose.position.z, 0.3);
  dds_return_loan(reader, samples.data(), n);
}

TEST(Ros2Participant, FailuresThrowWithDdsReason) {
  EXPECT_THROW((void)checked(DDS_RETCODE_BAD_PARAMETER, "thing"), std::runtime_error);
  try {
    (void)checked(DDS_RETCODE_BAD_PARAMETER, "thing");
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("thing: "), std::string::npos) << e.what();
  }
  EXPECT_EQ(checked(7, "fine"), 7);
}

}  // namespace
}  // namespace hapticctrl::ros2types
