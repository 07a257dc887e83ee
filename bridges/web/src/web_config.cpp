// Implements web_config.hpp: command line of hapticctrl-web.
#include "hapticctrl/web_bridge/web_config.hpp"

#include <stdexcept>

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::web_bridge {
namespace {

constexpr const char* kProgram = "hapticctrl-web";
constexpr const char* kDescription =
    "The operator's web view: serves the page, pushes the controller's LCM telemetry to it over "
    "WebSocket and forwards its commands as LCM HMI messages.";

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
    throw std::invalid_argument("expected IPV4-ADDRESS:PORT such as 127.0.0.1:8080, got '" + text +
                                "'");
  }
  (void)program::number_in<int>("--listen port", port, 0, 65535);
}

/// Every option, once: parse() and usage() both read these declarations.
void declare(program::Options& o, WebConfig& c) {
  o.custom(
      "--listen", "ADDR:PORT",
      [&c](const std::string& v) {
        check_listen(v);
        c.listen = v;
      },
      "HTTP/WebSocket address (default: 127.0.0.1:8080; port 0: any free port)");
  o.flag("--allow-remote", c.allow_remote,
         "required with a --listen address beyond loopback, such as 0.0.0.0:8080 (every machine "
         "that reaches it sees the arm and can press its emergency stop)");
  o.text("--www", c.www_dir, "the page's files (default: the build's bridges/web/www)");
  o.text("--arm-model", c.arm_model_path,
         "the arm model the page draws (default: the shipped one; give the core's if it runs "
         "another)");
  o.text("--instance", c.instance, "controller instance (default: default)");
  o.text("--lcm-url", c.lcm_url, "LCM provider (default: udpm://239.255.76.67:7667?ttl=0)");
  o.number("--rate", c.push_rate_hz, 1.0, 60.0,
           "state frames per second to each page (default: 30)");
  o.number("--max-pages", c.max_pages, 1, 64, "WebSocket connections at once (default: 8)");
  o.flag("--allow-remote-commands", c.allow_remote_commands,
         "forward the page's power, reset and force requests (the LCM bridge must allow them "
         "too); the emergency stop is always forwarded");
  o.number("--duration", c.duration_s, 0.0, 1e6, "exit after S seconds");
  o.flag("--json", c.json, "print the final counters as one JSON line");
}

}  // namespace

std::string WebConfig::usage() {
  return program::help_of<WebConfig>(kProgram, kDescription, declare);
}

WebConfig WebConfig::parse(const std::vector<std::string>& args) {
  WebConfig c;
  c.help = !program::parse_into(c, args, kProgram, kDescription, declare);
  if (c.listen.rfind("127.", 0) != 0 && !c.allow_remote) {
    throw std::invalid_argument("--listen " + c.listen +
                                " serves the web view beyond this host: add --allow-remote to "
                                "mean it");
  }
  return c;
}

}  // namespace hapticctrl::web_bridge
