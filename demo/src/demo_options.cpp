// Implements demo_options.hpp: command line of hapticctrl-demo.
#include "hapticctrl/demo/demo_options.hpp"

#include <map>
#include <stdexcept>

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::demo {
namespace {

constexpr const char* kProgram = "hapticctrl-demo";
constexpr const char* kDescription =
    "The seeds' test client: a mobile sphere coupled to the arm (VIRTMECH) next to a fixed one, "
    "whose contact it reports to the controller; or (--command impedance) the handle as the "
    "sphere, pushed by the fixed one's contact force (IMPEDANCE). "
    "Keys (with a terminal): x y z / X Y Z push the sphere along +/-, u v w / U V W twist it, 0 "
    "releases, q quits. Script lines: 't push fx fy fz', 't twist tx ty tz', 't release', 't "
    "quit'. The scene goes out on LCM (hapticctrl.<instance>.scene, default 30 Hz, local-only "
    "URL) for the web view. A lost session or a controller that failed safe is reconnected (the "
    "sphere starts again at the handle) unless --no-reconnect. Exit: 0 done (or the controller "
    "stopped), 1 error, 2 (--no-reconnect) the controller ended the session abnormally "
    "(fail-safe), 64 usage.";

/// Every option, once: parse() and usage() both read these declarations.
void declare(program::Options& o, DemoOptions& d) {
  o.text("--server", d.server, "the controller's UDP bridge, HOST:PORT (default: 127.0.0.1:5125)");
  o.flag("--headless", d.headless, "no keyboard: a script, or nothing, drives the sphere");
  o.number("--duration", d.duration_s, 0.0, 86400.0, "stop after S seconds (0: until q)");
  o.text("--script", d.script_path, "a script of pushes and twists (see above)");
  o.text("--log", d.log_path, "per-step CSV log of the sphere and the coupling");
  o.flag("--json", d.json, "print the final summary as JSON");
  o.number("--status-ms", d.status_ms, 0, 60000, "status line period, ms (0: none)");
  o.flag(
      "--no-power", [&d] { d.power_on = false; }, "do not ask for power on");
  o.number("--mass", d.scene.mass, 0.01, 20.0, "the mobile sphere's mass, kg");
  o.custom(
      "--radius", "M",
      [&d](const std::string& v) {
        d.scene.mobile_radius = d.scene.fixed_radius =
            program::number_in(std::string("--radius"), v, 0.001, 0.5);
      },
      "both spheres' radius, m [0.001..0.5]");
  o.number("--gap", d.gap, 0.0, 0.5, "the gap between the spheres at start, m");
  o.number("--contact-stiffness", d.scene.contact_stiffness, 1.0, 100000.0,
           "sphere contact stiffness, N/m");
  o.number("--contact-damping", d.scene.contact_damping, 0.0, 1000.0,
           "sphere contact damping, N.s/m");
  o.number("--friction", d.scene.friction, 0.0, 2.0, "sphere contact friction coefficient");
  o.flag("--gravity", d.scene.gravity, "the mobile sphere has weight");
  o.text("--lcm-url", d.lcm_url, "LCM provider for the scene");
  o.instance(d.instance, "controller instance, for the scene's LCM channel (default: default)");
  o.number("--scene-rate", d.scene_rate_hz, 1.0, 1000.0, "scene messages per second");
  o.flag(
      "--no-reconnect", [&d] { d.reconnect = false; },
      "exit when the session ends instead of reconnecting");
  o.flag(
      "--no-lcm", [&d] { d.publish_scene = false; }, "publish no scene on LCM");
  o.custom(
      "--command", "virtmech|impedance",
      [&d](const std::string& v) {
        if (v != "virtmech" && v != "impedance") {
          throw std::invalid_argument("must be virtmech or impedance");
        }
        d.impedance = v == "impedance";
      },
      "virtmech (default): the sphere is coupled to the handle; impedance: the handle is the "
      "sphere and the fixed sphere's contact force is sent as a wrench");
  o.custom(
      "--obstacle", "sphere|wall",
      [&d](const std::string& v) {
        if (v != "sphere" && v != "wall") {
          throw std::invalid_argument("must be sphere or wall");
        }
        d.scene.obstacle = v == "wall" ? Obstacle::kWall : Obstacle::kSphere;
      },
      "what the mobile sphere meets --gap away (along --toward): the fixed sphere (default) or a "
      "wall (a plane facing the sphere)");
  o.custom(
      "--toward", "x|-x|y|-y|z|-z",
      [&d](const std::string& v) {
        static const std::map<std::string, Eigen::Vector3d> axes{
            {"x", Eigen::Vector3d::UnitX()}, {"-x", -Eigen::Vector3d::UnitX()},
            {"y", Eigen::Vector3d::UnitY()}, {"-y", -Eigen::Vector3d::UnitY()},
            {"z", Eigen::Vector3d::UnitZ()}, {"-z", -Eigen::Vector3d::UnitZ()}};
        const auto found = axes.find(v);
        if (found == axes.end()) {
          throw std::invalid_argument("must be one of x -x y -y z -z");
        }
        d.scene.toward = found->second;
      },
      "the direction from the sphere's start to the obstacle (default x)");
  o.flag(
      "--no-contacts", [&d] { d.report_contacts = false; },
      "do not report the spheres' contact to the controller (protocol 1.3)");
}

}  // namespace

std::string DemoOptions::usage() {
  return program::help_of<DemoOptions>(kProgram, kDescription, declare);
}

DemoOptions DemoOptions::parse(const std::vector<std::string>& args) {
  DemoOptions d;
  d.help = !program::parse_into(d, args, kProgram, kDescription, declare);
  return d;
}

}  // namespace hapticctrl::demo
