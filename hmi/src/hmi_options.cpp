// Implements hmi_options.hpp: command line of hapticctrl-hmi.
#include "hapticctrl/hmi/hmi_options.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "hapticctrl/program/options.hpp"
#include "number_text.hpp"

namespace hapticctrl::hmi {
namespace {

double number_of(const std::string& text, const std::string& what) {
  double value = 0.0;
  if (!parse_finite(text, value)) {
    throw std::invalid_argument(what + " must be a finite number (got '" + text + "')");
  }
  return value;
}

const std::map<std::string, HmiCommand>& commands() {
  static const std::map<std::string, HmiCommand> table{
      {"status", HmiCommand::kStatus},
      {"power-on", HmiCommand::kPowerOn},
      {"power-off", HmiCommand::kPowerOff},
      {"estop", HmiCommand::kEmergencyStop},
      {"reset", HmiCommand::kEmergencyReset},
      {"stop", HmiCommand::kStop},
      {"force", HmiCommand::kForce},
      {"zero-force", HmiCommand::kZeroForce},
      {"play", HmiCommand::kPlay},
  };
  return table;
}

constexpr const char* kProgram = "hapticctrl-hmi";
constexpr const char* kDescription =
    "The operator's tool on the shared memory. Commands:\n"
    "  (none)                  full-screen operator panel (needs a terminal); when the\n"
    "                          controller ends it says why and waits for a new one\n"
    "                          (--offer-restart: or for R, then exits 75)\n"
    "  status [--json]         one reading of the controller's state\n"
    "  power-on | power-off    switch the motor supply\n"
    "  estop | reset           latch / reset the emergency stop\n"
    "  stop                    stop the controller (fail-safe order) and wait for it\n"
    "  force FX FY FZ TX TY TZ operator wrench on the handle [N, N.m], base frame, ramped\n"
    "  zero-force              release the handle (and let go of a simulated hand)\n"
    "  play FILE               play a force sequence (t fx fy fz tx ty tz per line) and log\n"
    "                          the arm's response per cycle (--log, default\n"
    "                          hapticctrl-sequence.csv); --hand K,B[,KA,BA]: a spring-damper\n"
    "                          hand grips the handle meanwhile (a wrist holding its rotation),\n"
    "                          its anchor wandering at random up to --wander M per axis\n"
    "                          (0.2-2 Hz, --seed N)\n"
    "Exit status: 0 done, 1 error or no effect within the timeout, 64 usage, 75 the\n"
    "operator asked for a new controller (--offer-restart).";

/// Every option, once: parse() and usage() both read these declarations. The command and its
/// arguments are positional (negative numbers included); parse() checks them.
void declare(program::Options& o, HmiOptions& h, std::vector<std::string>& positional,
             std::vector<std::string>& play_only) {
  o.text("--instance", h.instance, "controller instance (default: default)");
  o.custom(
      "--timeout-ms", "MS",
      [&h](const std::string& v) {
        h.timeout = std::chrono::milliseconds(
            program::number_in<std::int64_t>("--timeout-ms", v, 1, 600'000));
      },
      "how long a command waits for its effect [1..600000] (default 2000)");
  o.flag("--json", h.json, "status: as one JSON line");
  o.flag("--offer-restart", h.offer_restart, "panel: offer R when the controller ends");
  o.custom(
      "--log", "CSV|-",
      [&h, &play_only](const std::string& v) {
        h.log_path = v;
        play_only.emplace_back("--log");
      },
      "play: the per-cycle log");
  o.flag("--power-on", h.power_on, "play: power on first");
  o.custom(
      "--hand", "K,B[,KA,BA]",
      [&h, &play_only](const std::string& text) {
        std::vector<std::string> parts;
        for (std::size_t from = 0;;) {
          const auto comma = text.find(',', from);
          parts.push_back(text.substr(from, comma - from));
          if (comma == std::string::npos) {
            break;
          }
          from = comma + 1;
        }
        if (parts.size() != 2 && parts.size() != 4) {
          throw std::invalid_argument(
              "needs K,B (stiffness N/m, damping N.s/m) or K,B,KA,BA (and the wrist's N.m/rad, "
              "N.m.s/rad)");
        }
        h.hand.stiffness = number_of(parts[0], "the stiffness");
        h.hand.damping = number_of(parts[1], "the damping");
        if (parts.size() == 4) {
          h.hand.angular_stiffness = number_of(parts[2], "the wrist's stiffness");
          h.hand.angular_damping = number_of(parts[3], "the wrist's damping");
        }
        h.with_hand = true;
        play_only.emplace_back("--hand");
      },
      "play: a spring-damper hand grips the handle (N/m, N.s/m), its wrist holding the "
      "handle's rotation (N.m/rad, N.m.s/rad)");
  o.custom(
      "--wander", "M",
      [&h, &play_only](const std::string& v) {
        h.hand.wander = number_of(v, "the distance");
        play_only.emplace_back("--wander");
      },
      "play: the hand's anchor wanders up to M per axis");
  o.custom(
      "--seed", "N",
      [&h, &play_only](const std::string& v) {
        h.hand.seed = program::number_in<std::uint64_t>("--seed", v, 0, 1'000'000'000'000'000ULL);
        play_only.emplace_back("--seed");
      },
      "play: the wander's random seed");
  o.positional("command", positional, "the command and its arguments (see above)");
}

}  // namespace

std::string HmiOptions::usage() {
  HmiOptions h;
  std::vector<std::string> positional;
  std::vector<std::string> play_only;
  program::Options o(kProgram, kDescription);
  declare(o, h, positional, play_only);
  return o.help();
}

HmiOptions HmiOptions::parse(const std::vector<std::string>& args) {
  HmiOptions o;
  std::vector<std::string> positional;
  std::vector<std::string> play_only;  // the play options given
  program::Options options(kProgram, kDescription);
  declare(options, o, positional, play_only);
  o.help = !options.parse(args);
  if (o.help) {
    return o;
  }
  if (!positional.empty()) {
    const auto found = commands().find(positional.front());
    if (found == commands().end()) {
      throw std::invalid_argument("unknown command '" + positional.front() + "'");
    }
    o.command = found->second;
    positional.erase(positional.begin());
  }
  if (o.command == HmiCommand::kForce) {
    if (positional.size() != 6) {
      throw std::invalid_argument("force needs 6 numbers: FX FY FZ TX TY TZ");
    }
    for (std::size_t k = 0; k < 6; ++k) {
      o.wrench[k] = number_of(positional[k], "force component " + std::to_string(k + 1));
    }
  } else if (o.command == HmiCommand::kPlay) {
    if (positional.size() != 1) {
      throw std::invalid_argument("play needs one sequence file");
    }
    o.sequence_path = positional[0];
    if (o.log_path.empty()) {
      o.log_path = "hapticctrl-sequence.csv";
    }
    if (o.with_hand) {
      HandMotion(o.hand, {});  // range check now, with the operator's words, not mid-run
    }
  } else if (!positional.empty()) {
    throw std::invalid_argument("unexpected argument '" + positional[0] + "'");
  }
  if (o.command != HmiCommand::kPlay &&
      std::any_of(play_only.begin(), play_only.end(), [](const std::string& a) {
        return a == "--hand" || a == "--wander" || a == "--seed";
      })) {
    throw std::invalid_argument("--hand, --wander and --seed go with the play command");
  }
  if (!o.with_hand &&
      (o.hand.wander != HandOptions{}.wander || o.hand.seed != HandOptions{}.seed)) {
    throw std::invalid_argument("--wander and --seed need --hand K,B");
  }
  if (o.json && o.command != HmiCommand::kStatus) {
    throw std::invalid_argument("--json goes with the status command");
  }
  return o;
}

}  // namespace hapticctrl::hmi
