// Tests of type_hash.hpp: the REP-2011 hashes of the bridge's types, by DDS type name. The
// hashes themselves are checked against those ROS 2 shows by `type_hashes.py --check`
// (ros2types.type_hashes).
#include "hapticctrl/ros2types/type_hash.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::ros2types {
namespace {

TEST(TypeHash, EachTopicTypeHasItsHashAndOthersNone) {
  for (const char* type :
       {"geometry_msgs::msg::dds_::PoseStamped_", "geometry_msgs::msg::dds_::WrenchStamped_",
        "sensor_msgs::msg::dds_::JointState_", "diagnostic_msgs::msg::dds_::DiagnosticArray_",
        "std_msgs::msg::dds_::String_"}) {
    const std::string_view hash = type_hash(type);
    EXPECT_EQ(hash.size(), 71U) << type;
    EXPECT_EQ(hash.substr(0, 7), "RIHS01_") << type;
  }
  EXPECT_TRUE(type_hash("rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_").empty());
  EXPECT_TRUE(type_hash_user_data("no::such::Type_").empty());
  EXPECT_EQ(type_hash_user_data("std_msgs::msg::dds_::String_"),
            "typehash=RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18;");
}

}  // namespace
}  // namespace hapticctrl::ros2types
