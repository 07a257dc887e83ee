#pragma once
/// @file mujoco_options.hpp
/// Command line of hapticctrl-mujoco. parse() throws std::invalid_argument (exit 64).
#include <string>
#include <vector>

#include "hapticctrl/lcmtypes/channels.hpp"

namespace hapticctrl::mujoco {

struct MujocoOptions {
  std::string model_path;   ///< --model: an MJCF file (required)
  std::string body;         ///< --body: the free body the hand holds (default: the model's
                            ///< custom text "hapticctrl_body")
  double timestep_s = 0.0;  ///< --timestep: 0: the model's
  std::string server = "127.0.0.1:5125";
  bool headless = false;             ///< no keyboard (also without a terminal)
  double duration_s = 0.0;           ///< 0: until quit, a signal or the controller stops
  bool json = false;                 ///< a JSON summary on stdout at exit
  int status_ms = 0;                 ///< a status line every so many ms (0: only at the end)
  bool power_on = true;              ///< --no-power: leave power-on to the operator
  bool reconnect = true;             ///< --no-reconnect: exit when the session ends abnormally
  bool report_contacts = true;       ///< --no-contacts: the coupling alone (no local contact model)
  bool publish_world = true;         ///< --no-lcm: no world_t for the web view
  std::string instance = "default";  ///< --instance: the LCM channel's controller instance
  std::string lcm_url = lcmtypes::kDefaultLcmUrl;  ///< --lcm-url (local-only multicast)
  double world_rate_hz = 30.0;                     ///< --world-rate: world_t messages per second
  bool help = false;

  static MujocoOptions parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::mujoco
