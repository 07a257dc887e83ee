// ros2types/idl/ros2_messages.idl against rosidl's form of the same messages
// (rosidl_reference.idl, compiled apart): the XTypes type information Cyclone DDS sends with
// every endpoint (type identifiers that hash each member's type and name, J6) is the same, so a
// peer that compares member names finds rosidl's (`stamp_`, not `stamp`).
#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

#include "hapticctrl/ros2types/participant.hpp"
#include "hapticctrl/ros2types/qos.hpp"
#include "ros2_messages.h"
#include "rosidl_reference_table.h"
#include "support/dds_loopback.hpp"

namespace {

struct Ours {
  const char* name;
  const dds_topic_descriptor_t* descriptor;
};

const std::vector<Ours>& ours() {
  static const std::vector<Ours> table{
#define ROSIDL_TYPE(t) {#t, &t##_desc},
#include "rosidl_types.inc"
#undef ROSIDL_TYPE
  };
  return table;
}

bool same_bytes(const dds_type_meta_ser& a, const dds_type_meta_ser& b) {
  return a.sz == b.sz && a.sz > 0 && std::memcmp(a.data, b.data, a.sz) == 0;
}

TEST(RosidlNames, EveryTypeCarriesRosidlsTypeInformation) {
  for (const Ours& o : ours()) {
    const dds_topic_descriptor_t* reference = rosidl_reference(o.name);
    ASSERT_NE(reference, nullptr) << o.name;
    EXPECT_STREQ(o.descriptor->m_typename, reference->m_typename);
    EXPECT_TRUE(same_bytes(o.descriptor->type_information, reference->type_information))
        << o.name << ": the type identifiers differ (member names, types or order)";
    EXPECT_TRUE(same_bytes(o.descriptor->type_mapping, reference->type_mapping)) << o.name;
  }
}

TEST(RosidlNames, TheComparisonSeesAMemberName) {
  // The check can fail: Header_ and String_ differ in their members, so do their identifiers.
  EXPECT_FALSE(same_bytes(std_msgs_msg_dds__String__desc.type_information,
                          rosidl_reference("std_msgs_msg_dds__Header_")->type_information));
}

TEST(RosidlNames, AReaderOfRosidlsTypeMatchesTheBridgesWriter) {
  // A subscriber built from rosidl's form (Cyclone DDS checks that its type is assignable from
  // the writer's: a long where the writer has a string is refused, measured 2026-12-06) matches
  // a writer of ros2types' on the bridge's topic.
  const std::uint32_t domain = hapticctrl::test::use_loopback_dds();
  hapticctrl::ros2types::Participant bridge(domain);
  hapticctrl::ros2types::Participant peer(domain);
  const hapticctrl::ros2types::Qos qos = hapticctrl::ros2types::sensor_data_qos();
  const std::string topic = "rt/rosidl_names_test/handle_pose";
  const dds_entity_t writer =
      bridge.writer(geometry_msgs_msg_dds__PoseStamped__desc, topic, qos.get());
  const dds_entity_t reader =
      peer.reader(*rosidl_reference("geometry_msgs_msg_dds__PoseStamped_"), topic, qos.get());
  dds_subscription_matched_status_t matched{};
  for (int i = 0; i < 500 && matched.current_count == 0; ++i) {
    ASSERT_EQ(dds_get_subscription_matched_status(reader, &matched), DDS_RETCODE_OK);
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  EXPECT_EQ(matched.current_count, 1U);
  EXPECT_GT(writer, 0);
}

}  // namespace
