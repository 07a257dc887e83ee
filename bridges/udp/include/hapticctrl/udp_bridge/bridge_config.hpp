#pragma once
/// @file bridge_config.hpp
/// Command line of hapticctrl-udp. Setup code: parse() throws std::invalid_argument with a
/// message naming the bad option.
#include <cstdint>
#include <string>
#include <vector>

#include "hapticctrl/udp_bridge/client_allow_list.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace hapticctrl::udp_bridge {

struct BridgeConfig {
  std::string instance = "default";
  std::string bind_address = "127.0.0.1";
  std::uint16_t port = 5125;                       ///< 0: any free port (printed at start)
  bool allow_remote = false;                       ///< required to bind anything but loopback
  std::vector<Ipv4Network> allowed_clients;        ///< --allow-client (empty: any source)
  double hello_rate = 20.0;                        ///< HELLOs per second and burst, per source
  std::uint32_t watchdog_ms = kDefaultWatchdogMs;  ///< default session watchdog
  std::uint32_t max_watchdog_ms = kMaxWatchdogMs;  ///< the longest a client may ask for
  int priority = 0;         ///< SCHED_FIFO priority of both threads; 0: SCHED_OTHER
  double duration_s = 0.0;  ///< 0: until SIGINT/SIGTERM
  bool json = false;        ///< final counters as one JSON line on stdout
  /// Where the black box of a lost core goes (a directory only this user or root can write, as
  /// the core's --state-dir); empty: the instance's runtime directory.
  std::string state_dir;
  bool help = false;

  static BridgeConfig parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::udp_bridge
