#include "hapticctrl/web_bridge/web_config.hpp"

#include <charconv>
#include <stdexcept>

namespace hapticctrl::web_bridge {
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

/// "ADDRESS:PORT" with a dotted IPv4 address and a port 0-65535.
void check_listen(const std::string& text) {
  const auto colon = text.rfind(':');
  const std::string address = colon == std::string::npos ? "" : text.substr(0, colon);
  const std::string port = colon == std::string::npos ? "" : text.substr(colon + 1);
  int dots = 0;
  bool digits_only = !address.empty();
  for (const char c : address) {
    dots += c == '.' ? 1 : 0;
    digits_only = digits_only && (c == '.' || (c >= '0' && c <= '9'));
  }
  if (!digits_only || dots != 3) {
    throw std::invalid_argument(
        "--listen: expected IPV4-ADDRESS:PORT such as 127.0.0.1:8080, got '" + text + "'");
  }
  (void)number("--listen port", port, 0, 65535);
}

}  // namespace

const char* WebConfig::usage() noexcept {
  return "usage: hapticctrl-web [options]\n"
         "The operator's web view: serves the page, pushes the controller's LCM telemetry to it\n"
         "over WebSocket and forwards its commands as LCM HMI messages.\n"
         "  --listen ADDR:PORT       HTTP/WebSocket address (default: 127.0.0.1:8080; port 0:\n"
         "                           any free port)\n"
         "  --allow-remote           required with a --listen address beyond loopback, such as\n"
         "                           0.0.0.0:8080 (every machine that reaches it sees the arm and\n"
         "                           can press its emergency stop)\n"
         "  --www DIR                the page's files (default: the build's bridges/web/www)\n"
         "  --arm-model FILE         the arm model the page draws (default: the shipped one;\n"
         "                           give the core's if it runs another)\n"
         "  --instance NAME          controller instance (default: default)\n"
         "  --lcm-url URL            LCM provider (default: udpm://239.255.76.67:7667?ttl=0)\n"
         "  --rate HZ                state frames per second to each page, 1-60 (default: 30)\n"
         "  --max-pages N            WebSocket connections at once, 1-64 (default: 8)\n"
         "  --allow-remote-commands  forward the page's power, reset and force requests (the\n"
         "                           LCM bridge must allow them too); the emergency stop is\n"
         "                           always forwarded\n"
         "  --duration S             exit after S seconds\n"
         "  --json                   print the final counters as one JSON line\n";
}

WebConfig WebConfig::parse(const std::vector<std::string>& args) {
  WebConfig c;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    const auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) {
        throw std::invalid_argument(a + ": missing value");
      }
      return args[++i];
    };
    if (a == "--listen") {
      c.listen = value();
      check_listen(c.listen);
    } else if (a == "--allow-remote") {
      c.allow_remote = true;
    } else if (a == "--www") {
      c.www_dir = value();
    } else if (a == "--arm-model") {
      c.arm_model_path = value();
    } else if (a == "--instance") {
      c.instance = value();
    } else if (a == "--lcm-url") {
      c.lcm_url = value();
    } else if (a == "--rate") {
      c.push_rate_hz = number(a, value(), 1.0, 60.0);
    } else if (a == "--max-pages") {
      c.max_pages = static_cast<int>(number(a, value(), 1.0, 64.0));
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
  if (c.listen.rfind("127.", 0) != 0 && !c.allow_remote) {
    throw std::invalid_argument("--listen " + c.listen +
                                " serves the web view beyond this host: add --allow-remote to "
                                "mean it");
  }
  return c;
}

}  // namespace hapticctrl::web_bridge
