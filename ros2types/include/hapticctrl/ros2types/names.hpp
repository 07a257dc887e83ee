#pragma once
/// @file names.hpp
/// ROS 2 names on the DDS wire: a node's topic `/<namespace>/<name>` is the DDS topic
/// `rt/<namespace>/<name>` (ROS 2's prefix for topics), and each hapticctrl instance publishes
/// under a namespace of its own. Setup code: these functions allocate; none is for the cycle.
#include <cstdint>
#include <string>
#include <string_view>

#include "ros2_messages.h"

namespace hapticctrl::ros2types {

/// The topics of one instance, relative to its namespace.
namespace topic {
inline constexpr std::string_view kHandlePose = "handle_pose";          ///< PoseStamped
inline constexpr std::string_view kRenderedWrench = "rendered_wrench";  ///< WrenchStamped
inline constexpr std::string_view kOperatorWrench = "operator_wrench";  ///< WrenchStamped
inline constexpr std::string_view kJointStates = "joint_states";        ///< JointState
inline constexpr std::string_view kDiagnostics = "diagnostics";         ///< DiagnosticArray
/// In: "power_on", "power_off", "emergency_stop", "emergency_reset", "stop" (std_msgs/String).
inline constexpr std::string_view kCommand = "command";
/// In: the operator wrench to apply to the handle, base frame (WrenchStamped).
inline constexpr std::string_view kOperatorWrenchCommand = "operator_wrench_command";
/// ROS 2's graph topic, a DDS topic name as it is (no "rt/" prefix): rmw_dds_common's
/// ParticipantEntitiesInfo.
inline constexpr std::string_view kDiscoveryInfo = "ros_discovery_info";
}  // namespace topic

/// Whether `ns` is a valid absolute ROS 2 namespace: "/" followed by tokens of [A-Za-z0-9_]
/// that do not start with a digit, separated by single "/", no trailing "/". "/" alone is the
/// root namespace.
[[nodiscard]] bool valid_namespace(std::string_view ns);

/// `ns` itself when valid_namespace(ns); otherwise throws std::invalid_argument saying what a
/// ROS 2 namespace is.
[[nodiscard]] std::string checked_namespace(std::string_view ns);

/// "/hapticctrl/<instance>", with every character a ROS 2 name cannot hold replaced by '_'
/// (and '_' before a leading digit): "arm-1" -> "/hapticctrl/arm_1".
[[nodiscard]] std::string default_namespace(std::string_view instance);

/// The DDS topic of ROS 2 topic `<ns>/<name>`: "rt/hapticctrl/default/handle_pose".
/// Throws std::invalid_argument for an invalid namespace.
[[nodiscard]] std::string dds_topic(std::string_view ns, std::string_view name);

/// The TF frame the instance's poses and wrenches are expressed in: "hapticctrl/default/base"
/// (the namespace without its leading "/", as tf2 frame ids are written).
[[nodiscard]] std::string base_frame(std::string_view ns);

/// A controller timestamp (CLOCK_MONOTONIC of the controller's host, ns) as a ROS 2 stamp.
/// Real-time safe: noexcept, no allocation.
[[nodiscard]] builtin_interfaces_msg_dds__Time_ stamp_of(std::int64_t ns) noexcept;

}  // namespace hapticctrl::ros2types
