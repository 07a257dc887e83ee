// Tests of names.hpp: ROS 2 namespaces, DDS topic names, frames and stamps.
#include "hapticctrl/ros2types/names.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>

namespace hapticctrl::ros2types {
namespace {

TEST(Ros2Names, NamespacesFollowRos2Rules) {
  for (const char* ok : {"/", "/arm", "/lab/arm1", "/hapticctrl/default", "/_x/y_2"}) {
    EXPECT_TRUE(valid_namespace(ok)) << ok;
  }
  for (const char* bad :
       {"", "arm", "/arm/", "//arm", "/a//b", "/1arm", "/lab/2", "/a-b", "/a b", "/a.b", "/ä"}) {
    EXPECT_FALSE(valid_namespace(bad)) << bad;
  }
}

TEST(Ros2Names, CheckedNamespacesSayWhatANamespaceIs) {
  EXPECT_EQ(checked_namespace("/lab/arm1"), "/lab/arm1");
  try {
    (void)checked_namespace("lab");
    ADD_FAILURE() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), testing::HasSubstr("'lab' is not a ROS 2 namespace")) << e.what();
  }
}

TEST(Ros2Names, TheDefaultNamespaceIsValidForAnyInstance) {
  EXPECT_EQ(default_namespace("default"), "/hapticctrl/default");
  EXPECT_EQ(default_namespace("arm-1"), "/hapticctrl/arm_1");
  EXPECT_EQ(default_namespace("2nd"), "/hapticctrl/_2nd");
  EXPECT_EQ(default_namespace(""), "/hapticctrl/_");
  for (const char* instance : {"t123-4-dds", "a.b", "x y", "9"}) {
    EXPECT_TRUE(valid_namespace(default_namespace(instance))) << instance;
  }
}

TEST(Ros2Names, DdsTopicsCarryRos2sPrefix) {
  EXPECT_EQ(dds_topic("/hapticctrl/default", topic::kHandlePose),
            "rt/hapticctrl/default/handle_pose");
  EXPECT_EQ(dds_topic("/", topic::kJointStates), "rt/joint_states");
  EXPECT_THROW((void)dds_topic("no/slash", topic::kCommand), std::invalid_argument);
}

TEST(Ros2Names, FramesAreTheNamespaceWithoutItsLeadingSlash) {
  EXPECT_EQ(base_frame("/hapticctrl/default"), "hapticctrl/default/base");
  EXPECT_EQ(base_frame("/"), "base");
}

TEST(Ros2Names, StampsSplitNanosecondsAsRos2Does) {
  const auto t = stamp_of(12'345'678'901);
  EXPECT_EQ(t.sec_, 12);
  EXPECT_EQ(t.nanosec_, 345'678'901U);
  const auto before = stamp_of(-1);  // nanosec is always in [0, 1e9)
  EXPECT_EQ(before.sec_, -1);
  EXPECT_EQ(before.nanosec_, 999'999'999U);
  EXPECT_EQ(stamp_of(0).sec_, 0);
  EXPECT_EQ(stamp_of(0).nanosec_, 0U);
}

}  // namespace
}  // namespace hapticctrl::ros2types
