#include "hapticctrl/udp_bridge/bridge_config.hpp"

#include <arpa/inet.h>

#include <charconv>
#include <stdexcept>

namespace hapticctrl::udp_bridge {
namespace {

template <typename T>
T number(const std::string& option, const std::string& text, T lo, T hi) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || !(value >= lo && value <= hi)) {
    throw std::invalid_argument(option + ": expected a number from " + std::to_string(lo) + " to " +
                                std::to_string(hi) + ", got '" + text + "'");
  }
  return value;
}

bool is_loopback(const std::string& address) {
  in_addr a{};
  return address == "localhost" ||
         (::inet_pton(AF_INET, address.c_str(), &a) == 1 && (ntohl(a.s_addr) >> 24U) == 127U);
}

}  // namespace

const char* BridgeConfig::usage() noexcept {
  return "usage: hapticctrl-udp [options]\n"
         "  --instance NAME     controller instance to serve (default: default)\n"
         "  --bind ADDRESS      IPv4 address to listen on (default: 127.0.0.1)\n"
         "  --port N            UDP port (default: 5125; 0: any free port, printed)\n"
         "  --allow-remote      required to bind an address other than loopback\n"
         "  --allow-client NET  serve only this client address or network (a.b.c.d[/n]);\n"
         "                      repeat for more (default: any address that reaches the port)\n"
         "  --hello-rate N      handshakes (HELLO) answered per second per source, and the\n"
         "                      burst allowed, 1..10000 (default: 20); 5 times that from\n"
         "                      all sources together\n"
         "  --watchdog-ms N     default session watchdog, 10..60000 ms (default: 3000)\n"
         "  --max-watchdog-ms N the longest watchdog a client may ask for, 10..600000 ms\n"
         "                      (default: 10000, at least --watchdog-ms)\n"
         "  --priority N        SCHED_FIFO priority 1..98 for both threads (below the core's)\n"
         "  --duration S        exit after S seconds (default: run until SIGINT/SIGTERM)\n"
         "  --json              print the final counters as one JSON line\n";
}

BridgeConfig BridgeConfig::parse(const std::vector<std::string>& args) {
  BridgeConfig c;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) {
        throw std::invalid_argument(a + ": missing value");
      }
      return args[++i];
    };
    if (a == "--instance") {
      c.instance = value();
    } else if (a == "--bind") {
      c.bind_address = value();
    } else if (a == "--port") {
      c.port = number<std::uint16_t>(a, value(), 0, 65535);
    } else if (a == "--allow-remote") {
      c.allow_remote = true;
    } else if (a == "--allow-client") {
      try {
        c.allowed_clients.push_back(Ipv4Network::parse(value()));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument(a + ": " + e.what());
      }
    } else if (a == "--hello-rate") {
      c.hello_rate = number<double>(a, value(), 1.0, 10000.0);
    } else if (a == "--max-watchdog-ms") {
      c.max_watchdog_ms = number<std::uint32_t>(a, value(), 10, 600000);
    } else if (a == "--watchdog-ms") {
      c.watchdog_ms = number<std::uint32_t>(a, value(), 10, 60000);
    } else if (a == "--priority") {
      c.priority = number<int>(a, value(), 1, 98);
    } else if (a == "--duration") {
      c.duration_s = number<double>(a, value(), 0.0, 1e6);
    } else if (a == "--json") {
      c.json = true;
    } else if (a == "--help" || a == "-h") {
      c.help = true;
    } else {
      throw std::invalid_argument("unknown option '" + a + "'");
    }
  }
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
