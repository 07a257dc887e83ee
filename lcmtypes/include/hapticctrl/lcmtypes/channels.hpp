#pragma once
/// @file channels.hpp
/// The channel names of one controller instance and LCM's local-only default URL, shared by
/// every process that publishes or subscribes (LCM bridge, web bridge, demo client, tests).
/// Setup code (allocates); not for a real-time cycle.
#include <string>

namespace hapticctrl::lcmtypes {

/// LCM's default multicast group with ttl=0: nothing leaves this host.
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// Channel names: "hapticctrl.<instance>.<topic>", so several controllers share one network.
struct Channels {
  std::string arm_state, coupling, cycle_stats, bridge_stats, events, hmi_command, hmi_force, scene,
      world;

  static Channels of(const std::string& instance) {
    const std::string p = "hapticctrl." + instance + ".";
    return {p + "arm_state",   p + "coupling",  p + "cycle_stats", p + "bridge_stats", p + "events",
            p + "hmi_command", p + "hmi_force", p + "scene",       p + "world"};
  }
};

}  // namespace hapticctrl::lcmtypes
