#pragma once
/// @file web_config.hpp
/// Command line of hapticctrl-web. Setup code: parse() throws std::invalid_argument naming the
/// bad option.
#include <string>
#include <vector>

#include "hapticctrl/lcmtypes/channels.hpp"

namespace hapticctrl::web_bridge {

struct WebConfig {
  /// Where the HTTP/WebSocket server listens: "ADDRESS:PORT", loopback by default (port 0: any
  /// free port, printed at start). Another address also needs `allow_remote` (docs/security.md).
  std::string listen = "127.0.0.1:8080";
  bool allow_remote = false;   ///< --allow-remote: a --listen address beyond loopback is meant
  std::string www_dir;         ///< the page's files; empty: the build's bridges/web/www
  std::string arm_model_path;  ///< the model the page draws; empty: the shipped default
  std::string instance = "default";
  std::string lcm_url = lcmtypes::kDefaultLcmUrl;
  double push_rate_hz = 30.0;  ///< state frames to each page, 1-60 (display rate)
  int max_pages = 8;           ///< WebSocket connections at once (each holds a server thread)
  bool allow_remote_commands = false;  ///< forward power/reset and forces; e-stop always
  double duration_s = 0.0;             ///< 0: until SIGINT/SIGTERM
  bool json = false;
  bool help = false;

  static WebConfig parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::web_bridge
