#include "hapticctrl/demo/demo_options.hpp"

#include <cmath>
#include <stdexcept>

namespace hapticctrl::demo {
namespace {

double number_of(const std::string& text, const std::string& option, double lo, double hi) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (text.empty() || used != text.size() || !std::isfinite(value) || value < lo || value > hi) {
    throw std::invalid_argument(option + " must be a number within [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "] (got '" + text + "')");
  }
  return value;
}

}  // namespace

const char* DemoOptions::usage() noexcept {
  return "usage: hapticctrl-demo [--server HOST:PORT] [--headless] [--duration S]\n"
         "         [--script FILE] [--log CSV] [--json] [--status-ms MS] [--no-power]\n"
         "         [--mass KG] [--radius M] [--gap M] [--contact-stiffness N/M]\n"
         "         [--contact-damping NS/M] [--friction MU] [--gravity]\n"
         "         [--lcm-url URL] [--instance NAME] [--scene-rate HZ] [--no-lcm]\n"
         "         [--no-reconnect]\n"
         "The seeds' test client: a mobile sphere coupled to the arm (VIRTMECH) next to a fixed\n"
         "one. Keys (with a terminal): x y z / X Y Z push the sphere along +/-, u v w / U V W\n"
         "twist it, 0 releases, q quits. Script lines: 't push fx fy fz', 't twist tx ty tz',\n"
         "'t release', 't quit'. The scene goes out on LCM (hapticctrl.<instance>.scene,\n"
         "default 30 Hz, local-only URL) for the web view. A lost session or a controller that\n"
         "failed safe is reconnected (the sphere starts again at the handle) unless\n"
         "--no-reconnect. Exit: 0 done (or the controller stopped), 1 error, 2 (--no-reconnect)\n"
         "the controller ended the session abnormally (fail-safe), 64 usage.\n";
}

DemoOptions DemoOptions::parse(const std::vector<std::string>& args) {
  DemoOptions o;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& a = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) {
        throw std::invalid_argument(a + " needs a value");
      }
      return args[++i];
    };
    if (a == "--help" || a == "-h") {
      o.help = true;
    } else if (a == "--server") {
      o.server = value();
    } else if (a == "--headless") {
      o.headless = true;
    } else if (a == "--duration") {
      o.duration_s = number_of(value(), a, 0.0, 86400.0);
    } else if (a == "--script") {
      o.script_path = value();
    } else if (a == "--log") {
      o.log_path = value();
    } else if (a == "--json") {
      o.json = true;
    } else if (a == "--status-ms") {
      o.status_ms = static_cast<int>(number_of(value(), a, 0.0, 60000.0));
    } else if (a == "--no-power") {
      o.power_on = false;
    } else if (a == "--mass") {
      o.scene.mass = number_of(value(), a, 0.01, 20.0);
    } else if (a == "--radius") {
      o.scene.mobile_radius = o.scene.fixed_radius = number_of(value(), a, 0.001, 0.5);
    } else if (a == "--gap") {
      o.gap = number_of(value(), a, 0.0, 0.5);
    } else if (a == "--contact-stiffness") {
      o.scene.contact_stiffness = number_of(value(), a, 1.0, 100000.0);
    } else if (a == "--contact-damping") {
      o.scene.contact_damping = number_of(value(), a, 0.0, 1000.0);
    } else if (a == "--friction") {
      o.scene.friction = number_of(value(), a, 0.0, 2.0);
    } else if (a == "--gravity") {
      o.scene.gravity = true;
    } else if (a == "--lcm-url") {
      o.lcm_url = value();
    } else if (a == "--instance") {
      o.instance = value();
      if (o.instance.empty() || o.instance.find_first_of(". \t") != std::string::npos) {
        throw std::invalid_argument("--instance must be a non-empty name without dots or spaces");
      }
    } else if (a == "--scene-rate") {
      o.scene_rate_hz = number_of(value(), a, 1.0, 1000.0);
    } else if (a == "--no-reconnect") {
      o.reconnect = false;
    } else if (a == "--no-lcm") {
      o.publish_scene = false;
    } else {
      throw std::invalid_argument("unknown option '" + a + "'");
    }
  }
  return o;
}

}  // namespace hapticctrl::demo
