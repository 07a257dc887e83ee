// Implements dds_bridge_config.hpp: command line of hapticctrl-dds.
#include "hapticctrl/dds_bridge/dds_bridge_config.hpp"

#include <cstdlib>

#include "hapticctrl/program/options.hpp"
#include "hapticctrl/ros2types/names.hpp"

namespace hapticctrl::dds_bridge {
namespace {

constexpr const char* kProgram = "hapticctrl-dds";
constexpr const char* kDescription =
    "The DDS bridge: the controller's arm state as ROS 2 topics (no ROS 2 package needed on this "
    "host), and commands from ROS 2 in.";
// ROS 2's highest domain id on Linux (ports 7400 + 250 * id must stay below 65536).
constexpr std::int32_t kMaxDomain = 232;

/// Every option, once: parse() and usage() both read these declarations.
void declare(program::Options& o, DdsBridgeConfig& c) {
  o.text("--instance", c.instance, "controller instance (default: default)");
  o.custom(
      "--namespace", "NS",
      [&c](const std::string& v) { c.ros_namespace = ros2types::checked_namespace(v); },
      "ROS 2 namespace of the topics (default: /hapticctrl/<instance>)");
  o.number("--domain-id", c.domain_id, std::int32_t{0}, kMaxDomain,
           "DDS domain (default: $ROS_DOMAIN_ID, else 0)");
  o.number("--rate-hz", c.rate_hz, 0.0, 10000.0,
           "handle pose, wrenches and joint states rate; 0: every cycle (default: 100)");
  o.number("--diagnostics-rate-hz", c.diagnostics_rate_hz, 0.1, 100.0,
           "diagnostics rate (default: 1)");
  o.flag("--allow-remote-commands", c.allow_remote_commands,
         "accept power/reset/stop commands and the operator wrench from DDS (the emergency stop "
         "is always accepted)");
  o.number("--duration", c.duration_s, 0.0, 1e6, "exit after S seconds");
  o.flag("--json", c.json, "print the final counters as one JSON line");
}

}  // namespace

std::string DdsBridgeConfig::usage() {
  return program::help_of<DdsBridgeConfig>(kProgram, kDescription, declare);
}

DdsBridgeConfig DdsBridgeConfig::parse(const std::vector<std::string>& args) {
  DdsBridgeConfig c;
  c.help = !program::parse_into(c, args, kProgram, kDescription, declare);
  if (c.ros_namespace.empty()) {
    c.ros_namespace = ros2types::default_namespace(c.instance);
  }
  return c;
}

std::uint32_t DdsBridgeConfig::domain() const {
  if (domain_id >= 0) {
    return static_cast<std::uint32_t>(domain_id);
  }
  const char* env = std::getenv("ROS_DOMAIN_ID");  // NOLINT(concurrency-mt-unsafe): setup
  if (env == nullptr || *env == '\0') {
    return 0;
  }
  return static_cast<std::uint32_t>(
      program::number_in<std::int32_t>("ROS_DOMAIN_ID", env, 0, kMaxDomain));
}

}  // namespace hapticctrl::dds_bridge
