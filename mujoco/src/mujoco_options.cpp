// Implements mujoco_options.hpp: command line of hapticctrl-mujoco.
#include "hapticctrl/mujoco/mujoco_options.hpp"

#include <stdexcept>

#include "hapticctrl/program/options.hpp"

namespace hapticctrl::mujoco {
namespace {

constexpr const char* kProgram = "hapticctrl-mujoco";
constexpr const char* kDescription =
    "A MuJoCo scene as the client: one free body of the model (--body, or the model's custom "
    "text 'hapticctrl_body') is held by the arm's handle through VIRTMECH (its mass and inertia "
    "from the model); the engine steps in real time at the model's time step with the coupling "
    "wrench on the body, and sends the body's pose and twist; the body's contacts go to the "
    "controller as its local contact model (protocol 1.3), so they feel hard at any delay. "
    "Keys (with a terminal): r puts the scene back to its start, g switches the grip (a model's "
    "adhesion actuator on the body), q quits. The scene's geoms and the body's contacts go out "
    "on LCM (hapticctrl.<instance>.world, 30 Hz, local-only) for the web view. A lost session or "
    "a "
    "controller that failed safe is reconnected (the scene is held where the handle is) unless "
    "--no-reconnect. Exit: 0 done, 1 error, 2 (--no-reconnect) the controller ended the session "
    "abnormally, 64 usage or a model MuJoCo refuses (its own error text).";

void declare(program::Options& o, MujocoOptions& m) {
  o.text("--model", m.model_path, "the MJCF scene (required)");
  o.text("--body", m.body,
         "the free body the hand holds (default: the model's custom text 'hapticctrl_body')");
  o.number("--timestep", m.timestep_s, 0.0, 0.05, "the engine's time step, s (0: the model's own)");
  o.text("--server", m.server, "the controller's UDP bridge, HOST:PORT (default: 127.0.0.1:5125)");
  o.flag("--headless", m.headless, "no keyboard");
  o.number("--duration", m.duration_s, 0.0, 86400.0, "stop after S seconds (0: until q)");
  o.flag("--json", m.json, "print the final summary as JSON");
  o.number("--status-ms", m.status_ms, 0, 60000, "status line period, ms (0: none)");
  o.flag(
      "--no-power", [&m] { m.power_on = false; }, "do not ask for power on");
  o.flag(
      "--no-reconnect", [&m] { m.reconnect = false; },
      "exit when the session ends instead of reconnecting");
  o.flag(
      "--no-contacts", [&m] { m.report_contacts = false; },
      "do not report the body's contacts to the controller (the coupling alone renders them)");
  o.instance(m.instance, "controller instance, for the world's LCM channel (default: default)");
  o.text("--lcm-url", m.lcm_url, "LCM provider for the world");
  o.number("--world-rate", m.world_rate_hz, 1.0, 120.0, "world messages per second");
  o.flag(
      "--no-lcm", [&m] { m.publish_world = false; },
      "publish no world on LCM (hapticctrl.<instance>.world, for the web view)");
}

}  // namespace

std::string MujocoOptions::usage() {
  return program::help_of<MujocoOptions>(kProgram, kDescription, declare);
}

MujocoOptions MujocoOptions::parse(const std::vector<std::string>& args) {
  MujocoOptions m;
  m.help = !program::parse_into(m, args, kProgram, kDescription, declare);
  if (!m.help && m.model_path.empty()) {
    throw std::invalid_argument("--model: an MJCF scene is required (see scenes/ beside it)");
  }
  return m;
}

}  // namespace hapticctrl::mujoco
