// Tests of dds_bridge/endpoints.hpp: one instance's DDS writers and readers, with ROS 2's names,
// types and QoS.
#include "hapticctrl/dds_bridge/endpoints.hpp"

#include <gtest/gtest.h>

#include <array>
#include <string>

#include "support/dds_loopback.hpp"

namespace hapticctrl::dds_bridge {
namespace {

std::string topic_of(dds_entity_t endpoint) {
  std::array<char, 128> name{};
  EXPECT_GT(dds_get_name(dds_get_topic(endpoint), name.data(), name.size()), 0);
  return name.data();
}

std::string type_of(dds_entity_t endpoint) {
  std::array<char, 128> name{};
  EXPECT_GT(dds_get_type_name(dds_get_topic(endpoint), name.data(), name.size()), 0);
  return name.data();
}

dds_reliability_kind_t reliability_of(dds_entity_t endpoint) {
  dds_qos_t* qos = dds_create_qos();
  EXPECT_EQ(dds_get_qos(endpoint, qos), 0);
  dds_reliability_kind_t kind{};
  dds_duration_t blocking = 0;
  EXPECT_TRUE(dds_qget_reliability(qos, &kind, &blocking));
  dds_delete_qos(qos);
  return kind;
}

TEST(DdsEndpoints, EveryTopicHasItsRos2NameTypeAndQos) {
  ros2types::Participant p(test::use_loopback_dds());
  const Endpoints e(p, "/lab/arm1");
  EXPECT_EQ(topic_of(e.handle_pose), "rt/lab/arm1/handle_pose");
  EXPECT_EQ(type_of(e.handle_pose), "geometry_msgs::msg::dds_::PoseStamped_");
  EXPECT_EQ(topic_of(e.rendered_wrench), "rt/lab/arm1/rendered_wrench");
  EXPECT_EQ(topic_of(e.operator_wrench), "rt/lab/arm1/operator_wrench");
  EXPECT_EQ(type_of(e.operator_wrench), "geometry_msgs::msg::dds_::WrenchStamped_");
  EXPECT_EQ(topic_of(e.joint_states), "rt/lab/arm1/joint_states");
  EXPECT_EQ(type_of(e.joint_states), "sensor_msgs::msg::dds_::JointState_");
  EXPECT_EQ(topic_of(e.diagnostics), "rt/lab/arm1/diagnostics");
  EXPECT_EQ(type_of(e.diagnostics), "diagnostic_msgs::msg::dds_::DiagnosticArray_");
  EXPECT_EQ(topic_of(e.command), "rt/lab/arm1/command");
  EXPECT_EQ(type_of(e.command), "std_msgs::msg::dds_::String_");
  EXPECT_EQ(topic_of(e.operator_wrench_command), "rt/lab/arm1/operator_wrench_command");
  for (const dds_entity_t out :
       {e.handle_pose, e.rendered_wrench, e.operator_wrench, e.joint_states, e.diagnostics}) {
    EXPECT_EQ(reliability_of(out), DDS_RELIABILITY_BEST_EFFORT) << topic_of(out);
  }
  EXPECT_EQ(reliability_of(e.command), DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(reliability_of(e.operator_wrench_command), DDS_RELIABILITY_RELIABLE);
}

}  // namespace
}  // namespace hapticctrl::dds_bridge
