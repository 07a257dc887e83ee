#pragma once
/// @file dds_bridge_config.hpp
/// Command line of hapticctrl-dds. Setup code: parse() throws std::invalid_argument naming the
/// bad option (an invalid ROS 2 namespace included).
#include <cstdint>
#include <string>
#include <vector>

namespace hapticctrl::dds_bridge {

struct DdsBridgeConfig {
  std::string instance = "default";
  std::string ros_namespace;  ///< empty: ros2types::default_namespace(instance)
  /// DDS domain; -1: $ROS_DOMAIN_ID, or 0 without it (as a ROS 2 node chooses).
  std::int32_t domain_id = -1;
  double rate_hz = 100.0;            ///< pose, wrenches and joint states; 0: every cycle
  double diagnostics_rate_hz = 1.0;  ///< the diagnostics array (ROS 2's usual 1 Hz)
  bool allow_remote_commands = false;
  double duration_s = 0.0;  ///< 0: until SIGINT/SIGTERM
  bool json = false;
  bool help = false;

  static DdsBridgeConfig parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
  /// The domain to join: domain_id, else $ROS_DOMAIN_ID (0..232, or std::invalid_argument),
  /// else 0.
  [[nodiscard]] std::uint32_t domain() const;
};

}  // namespace hapticctrl::dds_bridge
