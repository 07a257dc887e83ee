// Implements lcm_bridge_config.hpp: command line of hapticctrl-lcm.
#include "hapticctrl/lcm_bridge/lcm_bridge_config.hpp"

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

constexpr const char* kProgram = "hapticctrl-lcm";
constexpr const char* kDescription =
    "The LCM bridge: the controller's telemetry out, the operator's HMI commands in.";

/// Every option, once: parse() and usage() both read these declarations.
void declare(program::Options& o, LcmBridgeConfig& c) {
  o.text("--instance", c.instance, "controller instance (default: default)");
  o.text("--lcm-url", c.lcm_url,
         "LCM provider (default: udpm://239.255.76.67:7667?ttl=0, which stays on this host)");
  o.number("--arm-rate-hz", c.arm_rate_hz, 0.0, 10000.0,
           "arm_state and coupling rate; 0: every cycle (default: 100)");
  o.number("--stats-rate-hz", c.stats_rate_hz, 0.1, 100.0,
           "cycle_stats and bridge_stats rate (default: 10)");
  o.flag("--allow-remote-commands", c.allow_remote_commands,
         "accept HMI power/reset/stop commands and forces over LCM (the emergency stop is always "
         "accepted)");
  o.number("--duration", c.duration_s, 0.0, 1e6, "exit after S seconds");
  o.flag("--json", c.json, "print the final counters as one JSON line");
}

}  // namespace

std::string LcmBridgeConfig::usage() {
  return program::help_of<LcmBridgeConfig>(kProgram, kDescription, declare);
}

LcmBridgeConfig LcmBridgeConfig::parse(const std::vector<std::string>& args) {
  LcmBridgeConfig c;
  c.help = !program::parse_into(c, args, kProgram, kDescription, declare);
  return c;
}

}  // namespace hapticctrl::lcm_bridge
