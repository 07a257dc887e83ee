#pragma once
/// @file demo_options.hpp
/// Command line of hapticctrl-demo. parse() throws std::invalid_argument.
#include <string>
#include <vector>

#include "hapticctrl/demo/sphere_scene.hpp"
#include "hapticctrl/lcmtypes/channels.hpp"

namespace hapticctrl::demo {

struct DemoOptions {
  std::string server = "127.0.0.1:5125";
  bool headless = false;      ///< no keyboard (also without a terminal)
  double duration_s = 0.0;    ///< 0: until quit, Ctrl-C or the controller stops
  std::string script_path;    ///< timed pushes on the sphere
  std::string log_path;       ///< CSV, one row per step
  bool json = false;          ///< a JSON summary on stdout at exit
  int status_ms = 0;          ///< a status line every so many ms (0: only at the end)
  bool power_on = true;       ///< --no-power: leave power-on to the operator
  double gap = 0.01;          ///< initial gap between the spheres along +x [m]
  bool publish_scene = true;  ///< scene_t on LCM for operator views (--no-lcm: off)
  std::string lcm_url = lcmtypes::kDefaultLcmUrl;
  std::string instance = "default";
  double scene_rate_hz = 30.0;
  /// A lost session (link down past the watchdog) or a controller that failed safe: connect
  /// again (to the next controller) instead of exiting. --no-reconnect: exit as before.
  bool reconnect = true;
  /// VIRTMECH (default): the mobile sphere is coupled to the handle. IMPEDANCE: the handle is
  /// the mobile sphere, and the demo sends the fixed sphere's contact force as the wrench.
  bool impedance = false;
  /// VIRTMECH: report the spheres' contact to the controller (protocol 1.3; --no-contacts: off).
  bool report_contacts = true;
  SceneConfig scene;  ///< mass, radii, contact, gravity (fixed centre set at start)
  bool help = false;

  static DemoOptions parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::demo
