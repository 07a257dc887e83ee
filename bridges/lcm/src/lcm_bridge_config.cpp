#include "hapticctrl/lcm_bridge/lcm_bridge_config.hpp"

#include <charconv>
#include <stdexcept>

namespace hapticctrl::lcm_bridge {
namespace {

double number(const std::string& option, const std::string& text, double lo, double hi) {
  double value = 0.0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || !(value >= lo && value <= hi)) {
    throw std::invalid_argument(option + ": expected a number from " + std::to_string(lo) + " to " +
                                std::to_string(hi) + ", got '" + text + "'");
  }
  return value;
}

}  // namespace

const char* LcmBridgeConfig::usage() noexcept {
  return "usage: hapticctrl-lcm [options]\n"
         "  --instance NAME          controller instance (default: default)\n"
         "  --lcm-url URL            LCM provider (default: udpm://239.255.76.67:7667?ttl=0,\n"
         "                           which stays on this host)\n"
         "  --arm-rate-hz R          arm_state and coupling rate; 0: every cycle (default: 100)\n"
         "  --stats-rate-hz R        cycle_stats and bridge_stats rate (default: 10)\n"
         "  --allow-remote-commands  accept HMI power/reset/stop commands and forces over LCM\n"
         "                           (the emergency stop is always accepted)\n"
         "  --duration S             exit after S seconds\n"
         "  --json                   print the final counters as one JSON line\n";
}

LcmBridgeConfig LcmBridgeConfig::parse(const std::vector<std::string>& args) {
  LcmBridgeConfig c;
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
    } else if (a == "--lcm-url") {
      c.lcm_url = value();
    } else if (a == "--arm-rate-hz") {
      c.arm_rate_hz = number(a, value(), 0.0, 10000.0);
    } else if (a == "--stats-rate-hz") {
      c.stats_rate_hz = number(a, value(), 0.1, 100.0);
    } else if (a == "--allow-remote-commands") {
      c.allow_remote_commands = true;
    } else if (a == "--duration") {
      c.duration_s = number(a, value(), 0.0, 1e6);
    } else if (a == "--json") {
      c.json = true;
    } else if (a == "--help" || a == "-h") {
      c.help = true;
    } else {
      throw std::invalid_argument("unknown option '" + a + "'");
    }
  }
  return c;
}

}  // namespace hapticctrl::lcm_bridge
