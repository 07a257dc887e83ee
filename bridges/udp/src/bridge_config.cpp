// Implements bridge_config.hpp: command line of hapticctrl-udp.
#include "hapticctrl/udp_bridge/bridge_config.hpp"

#include <arpa/inet.h>

#include <stdexcept>

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::udp_bridge {
namespace {

bool is_loopback(const std::string& address) {
  in_addr a{};
  return address == "localhost" ||
         (::inet_pton(AF_INET, address.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24U) == 127U);
}

/// Every option, once: parse() and usage() both read these declarations.
void declare(program::Options& o, BridgeConfig& c) {
  o.text("--instance", c.instance, "controller instance to serve (default: default)");
  o.text("--bind", c.bind_address, "IPv4 address to listen on (default: 127.0.0.1)");
  o.number<std::uint16_t>("--port", c.port, 0, 65535,
                          "UDP port (default: 5125; 0: any free port, printed)");
  o.flag("--allow-remote", c.allow_remote, "required to bind an address other than loopback");
  o.custom(
      "--allow-client", "NET",
      [&c](const std::string& v) { c.allowed_clients.push_back(Ipv4Network::parse(v)); },
      "serve only this client address or network (a.b.c.d[/n]); repeat for more (default: any "
      "address that reaches the port)",
      /*repeat=*/true);
  o.number("--hello-rate", c.hello_rate, 1.0, 10000.0,
           "handshakes (HELLO) answered per second per source, and the burst allowed "
           "(default: 20); 5 times that from all sources together");
  o.number<std::uint32_t>("--watchdog-ms", c.watchdog_ms, 10, 60000,
                          "default session watchdog, ms (default: 3000)");
  o.number<std::uint32_t>("--max-watchdog-ms", c.max_watchdog_ms, 10, 600000,
                          "the longest watchdog a client may ask for, ms (default: 10000, at "
                          "least --watchdog-ms)");
  o.number("--priority", c.priority, 1, 98,
           "SCHED_FIFO priority for both threads (below the core's)");
  o.text("--state-dir", c.state_dir,
         "where the last cycles of a lost controller (killed, crashed) are written: the core's "
         "--state-dir (default: the instance's runtime directory)");
  o.number("--duration", c.duration_s, 0.0, 1e6,
           "exit after S seconds (default: run until SIGINT/SIGTERM)");
  o.flag("--json", c.json, "print the final counters as one JSON line");
}

constexpr const char* kProgram = "hapticctrl-udp";
constexpr const char* kDescription =
    "The UDP bridge: serves one client session of the hapticctrl protocol for a controller.";

}  // namespace

std::string BridgeConfig::usage() {
  return program::help_of<BridgeConfig>(kProgram, kDescription, declare);
}

BridgeConfig BridgeConfig::parse(const std::vector<std::string>& args) {
  BridgeConfig c;
  c.help = !program::parse_into(c, args, kProgram, kDescription, declare);
  if (!c.allow_remote && !is_loopback(c.bind_address)) {
    throw std::invalid_argument("--bind " + c.bind_address +
                                ": not a loopback address; a client elsewhere could then command "
                                "forces, so say so with --allow-remote");
  }
  if (c.max_watchdog_ms < c.watchdog_ms) {
    throw std::invalid_argument("--max-watchdog-ms " + std::to_string(c.max_watchdog_ms) +
                                " is below the default watchdog " + std::to_string(c.watchdog_ms));
  }
  return c;
}

}  // namespace hapticctrl::udp_bridge
