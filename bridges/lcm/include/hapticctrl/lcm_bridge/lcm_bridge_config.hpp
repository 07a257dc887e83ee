#pragma once
/// @file lcm_bridge_config.hpp
/// Command line of hapticctrl-lcm. Setup code: parse() throws std::invalid_argument naming the
/// bad option.
#include <string>
#include <vector>

#include "hapticctrl/lcmtypes/channels.hpp"

namespace hapticctrl::lcm_bridge {

using lcmtypes::kDefaultLcmUrl;

struct LcmBridgeConfig {
  std::string instance = "default";
  std::string lcm_url = kDefaultLcmUrl;
  double arm_rate_hz = 100.0;   ///< arm_state and coupling; 0: every controller cycle
  double stats_rate_hz = 10.0;  ///< cycle_stats and bridge_stats
  bool allow_remote_commands = false;
  double duration_s = 0.0;  ///< 0: until SIGINT/SIGTERM
  bool json = false;
  bool help = false;

  static LcmBridgeConfig parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::lcm_bridge
