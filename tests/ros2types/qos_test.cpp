// Tests of qos.hpp: ROS 2's sensor-data and default QoS profiles.
#include "hapticctrl/ros2types/qos.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::ros2types {
namespace {

struct Policies {
  dds_reliability_kind_t reliability{};
  dds_durability_kind_t durability{};
  dds_history_kind_t history{};
  int32_t depth = 0;
};

Policies of(const Qos& qos) {
  Policies p;
  dds_duration_t blocking = 0;
  EXPECT_TRUE(dds_qget_reliability(qos.get(), &p.reliability, &blocking));
  EXPECT_TRUE(dds_qget_durability(qos.get(), &p.durability));
  EXPECT_TRUE(dds_qget_history(qos.get(), &p.history, &p.depth));
  return p;
}

TEST(Ros2Qos, SensorDataIsBestEffortVolatileKeepLastFive) {
  const Policies p = of(sensor_data_qos());
  EXPECT_EQ(p.reliability, DDS_RELIABILITY_BEST_EFFORT);
  EXPECT_EQ(p.durability, DDS_DURABILITY_VOLATILE);
  EXPECT_EQ(p.history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(p.depth, 5);
}

TEST(Ros2Qos, CommandsAreReliableVolatileKeepLastTen) {
  const Policies p = of(command_qos());
  EXPECT_EQ(p.reliability, DDS_RELIABILITY_RELIABLE);
  EXPECT_EQ(p.durability, DDS_DURABILITY_VOLATILE);
  EXPECT_EQ(p.history, DDS_HISTORY_KEEP_LAST);
  EXPECT_EQ(p.depth, 10);
}

}  // namespace
}  // namespace hapticctrl::ros2types
