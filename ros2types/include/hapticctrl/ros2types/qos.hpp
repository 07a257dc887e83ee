#pragma once
/// @file qos.hpp
/// The QoS of ROS 2's two standard profiles, as hapticctrl's DDS participants use them (rmw's
/// rmw_qos_profile_sensor_data and rmw_qos_profile_default). Setup code: allocates.
#include <dds/dds.h>

#include <memory>

namespace hapticctrl::ros2types {

struct QosDeleter {
  void operator()(dds_qos_t* qos) const noexcept { dds_delete_qos(qos); }
};
using Qos = std::unique_ptr<dds_qos_t, QosDeleter>;

/// Sensor data: best effort, volatile, keep last 5. What the bridge publishes: a late sample is
/// worth less than the next one, and no subscriber can slow the publisher down.
[[nodiscard]] Qos sensor_data_qos();
/// Default: reliable, volatile, keep last 10. Commands: an emergency stop is not to be dropped.
[[nodiscard]] Qos command_qos();
/// ROS 2's graph topic (ros_discovery_info): reliable, transient local, keep last 1, so that a
/// tool started later gets each participant's last announcement.
[[nodiscard]] Qos discovery_qos();

}  // namespace hapticctrl::ros2types
