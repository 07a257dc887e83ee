#pragma once
/// @file endpoints.hpp
/// The DDS writers and readers of one hapticctrl instance, with ROS 2's topic names under its
/// namespace (ros2types/names.hpp) and ROS 2's QoS: sensor data for what it publishes, the
/// default profile for commands. Setup code: allocates, throws std::runtime_error.
#include <string>

#include "hapticctrl/ros2types/participant.hpp"

namespace hapticctrl::dds_bridge {

struct Endpoints {
  Endpoints(ros2types::Participant& participant, const std::string& ros_namespace);

  // Out: geometry_msgs/PoseStamped, WrenchStamped (x2), sensor_msgs/JointState,
  // diagnostic_msgs/DiagnosticArray.
  dds_entity_t handle_pose{};
  dds_entity_t rendered_wrench{};
  dds_entity_t operator_wrench{};
  dds_entity_t joint_states{};
  dds_entity_t diagnostics{};
  // In: std_msgs/String, geometry_msgs/WrenchStamped.
  dds_entity_t command{};
  dds_entity_t operator_wrench_command{};
};

}  // namespace hapticctrl::dds_bridge
