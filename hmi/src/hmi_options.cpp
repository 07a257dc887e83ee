#include "hapticctrl/hmi/hmi_options.hpp"

#include <algorithm>
#include <cstdint>
#include <map>
#include <stdexcept>

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

}  // namespace

const char* HmiOptions::usage() noexcept {
  return "usage: hapticctrl-hmi [--instance NAME] [--timeout-ms MS] [COMMAND]\n"
         "  (no command)            full-screen operator panel (needs a terminal); when the\n"
         "                          controller ends it says why and waits for a new one\n"
         "    --offer-restart       ... or for R, then exits 75 (for the script that starts\n"
         "                          the controller: scripts/run.sh)\n"
         "  status [--json]         one reading of the controller's state\n"
         "  power-on | power-off    switch the motor supply\n"
         "  estop | reset           latch / reset the emergency stop\n"
         "  stop                    stop the controller (fail-safe order) and wait for it\n"
         "  force FX FY FZ TX TY TZ operator wrench on the handle [N, N.m], base frame, ramped\n"
         "  zero-force              release the handle (and let go of a simulated hand)\n"
         "  play FILE [--log CSV|-] [--power-on] [--hand K,B] [--wander M] [--seed N]\n"
         "                          play a force sequence (t fx fy fz tx ty tz per line) and log\n"
         "                          the arm's response per cycle (default "
         "hapticctrl-sequence.csv);\n"
         "                          --hand: a spring-damper hand (K N/m, B N.s/m) grips the\n"
         "                          handle meanwhile, its anchor wandering at random up to M m\n"
         "                          per axis (0.2-2 Hz, seeded)\n"
         "Exit status: 0 done, 1 error or no effect within the timeout, 64 usage, 75 the\n"
         "operator asked for a new controller (--offer-restart).\n";
}

HmiOptions HmiOptions::parse(const std::vector<std::string>& args) {
  HmiOptions o;
  bool have_command = false;
  std::vector<std::string> positional;
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
    } else if (a == "--instance") {
      o.instance = value();
    } else if (a == "--timeout-ms") {
      const double ms = number_of(value(), "--timeout-ms");
      if (ms < 1 || ms > 600'000) {
        throw std::invalid_argument("--timeout-ms must be within 1..600000");
      }
      o.timeout = std::chrono::milliseconds(static_cast<long>(ms));
    } else if (a == "--json") {
      o.json = true;
    } else if (a == "--offer-restart") {
      o.offer_restart = true;
    } else if (a == "--log") {
      o.log_path = value();
    } else if (a == "--power-on") {
      o.power_on = true;
    } else if (a == "--hand") {
      const std::string& text = value();
      const auto comma = text.find(',');
      if (comma == std::string::npos) {
        throw std::invalid_argument("--hand needs K,B (stiffness N/m, damping N.s/m)");
      }
      o.hand.stiffness = number_of(text.substr(0, comma), "--hand stiffness");
      o.hand.damping = number_of(text.substr(comma + 1), "--hand damping");
      o.with_hand = true;
    } else if (a == "--wander") {
      o.hand.wander = number_of(value(), "--wander");
    } else if (a == "--seed") {
      const double seed = number_of(value(), "--seed");
      if (seed < 0 || seed > 1e15 || seed != static_cast<double>(static_cast<std::int64_t>(seed))) {
        throw std::invalid_argument("--seed must be a whole number within 0..1e15");
      }
      o.hand.seed = static_cast<std::uint64_t>(seed);
    } else if (!a.empty() && a[0] == '-' && !(have_command && o.command == HmiCommand::kForce)) {
      throw std::invalid_argument("unknown option '" + a + "'");
    } else if (!have_command) {
      const auto found = commands().find(a);
      if (found == commands().end()) {
        throw std::invalid_argument("unknown command '" + a + "'");
      }
      o.command = found->second;
      have_command = true;
    } else {
      positional.push_back(a);
    }
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
      std::any_of(args.begin(), args.end(), [](const std::string& a) {
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
