// Tests of participant.hpp: a DDS participant, its writers and readers, on loopback.
#include "hapticctrl/ros2types/participant.hpp"

#include <gmock/gmock.h>
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
  sent.header_ = {stamp_of(1'500'000'000), frame.data()};
  sent.pose_.position_ = {0.1, 0.2, 0.3};
  sent.pose_.orientation_ = {0, 0, 0, 1};
  ASSERT_EQ(dds_write(writer, &sent), 0);
  const dds_entity_t waitset = p.waitset_for({reader});
  ASSERT_GT(dds_waitset_wait(waitset, nullptr, 0, DDS_SECS(2)), 0) << "woken by the sample";
  int taken = 0;
  take_each<geometry_msgs_msg_dds__PoseStamped_>(reader, [&](const auto& got) {
    ++taken;
    EXPECT_EQ(got.header_.stamp_.sec_, 1);
    EXPECT_EQ(got.header_.stamp_.nanosec_, 500'000'000U);
    EXPECT_STREQ(got.header_.frame_id_, "f");
    EXPECT_DOUBLE_EQ(got.pose_.position_.z_, 0.3);
  });
  EXPECT_EQ(taken, 1);
  take_each<geometry_msgs_msg_dds__PoseStamped_>(reader, [&](const auto&) { ++taken; });
  EXPECT_EQ(taken, 1) << "taken once";
}

TEST(Ros2Participant, EveryEndpointOfAHashedTypeCarriesItsTypeHashToItsPeers) {
  // REP-2016's user data, as a peer discovers it (the built-in publication topic of another
  // participant), and on a reader.
  Participant p(test::use_loopback_dds());
  Participant peer(test::use_loopback_dds());
  const dds_entity_t discovered =
      dds_create_reader(peer.handle(), DDS_BUILTIN_TOPIC_DCPSPUBLICATION, nullptr, nullptr);
  ASSERT_GT(discovered, 0);
  const Qos qos = sensor_data_qos();
  const std::string topic = dds_topic("/participant_test_hash", topic::kJointStates);
  const dds_entity_t writer = p.writer(sensor_msgs_msg_dds__JointState__desc, topic, qos.get());
  const std::string expected =
      "typehash=RIHS01_a13ee3a330e346c9d87b5aa18d24e11690752bd33a0350f11c5882bc9179260e;";
  std::string seen;
  for (int i = 0; i < 200 && seen.empty(); ++i) {
    void* sample = nullptr;
    dds_sample_info_t info;
    while (dds_take(discovered, &sample, &info, 1, 1) == 1) {
      const auto* pub = static_cast<const dds_builtintopic_endpoint_t*>(sample);
      void* data = nullptr;
      size_t size = 0;
      if (info.valid_data && std::string(pub->topic_name) == topic &&
          dds_qget_userdata(pub->qos, &data, &size)) {
        seen.assign(static_cast<const char*>(data), size);
        dds_free(data);
      }
      dds_return_loan(discovered, &sample, 1);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(seen, expected) << "what a peer discovered of the writer";
  EXPECT_GT(writer, 0);
  const dds_entity_t reader =
      p.reader(std_msgs_msg_dds__String__desc, dds_topic("/participant_test_hash", topic::kCommand),
               command_qos().get());
  Qos own(dds_create_qos());
  ASSERT_EQ(dds_get_qos(reader, own.get()), DDS_RETCODE_OK);
  void* data = nullptr;
  size_t size = 0;
  ASSERT_TRUE(dds_qget_userdata(own.get(), &data, &size));
  EXPECT_EQ(std::string(static_cast<const char*>(data), size),
            "typehash=RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18;");
  dds_free(data);
}

TEST(Ros2Participant, FailuresThrowWithDdsReason) {
  EXPECT_THROW((void)checked(DDS_RETCODE_BAD_PARAMETER, "thing"), std::runtime_error);
  try {
    (void)checked(DDS_RETCODE_BAD_PARAMETER, "thing");
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("thing: ")) << e.what();
  }
  EXPECT_EQ(checked(7, "fine"), 7);
}

}  // namespace
}  // namespace hapticctrl::ros2types
