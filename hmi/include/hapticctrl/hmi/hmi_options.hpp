#pragma once
/// @file hmi_options.hpp
/// Command line of hapticctrl-hmi. Not for the cycle; parse() throws std::invalid_argument.
#include <chrono>
#include <string>
#include <vector>

#include "hapticctrl/hmi/hand_motion.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::hmi {

enum class HmiCommand {
  kPanel,  ///< no command: the full-screen panel
  kStatus,
  kPowerOn,
  kPowerOff,
  kEmergencyStop,
  kEmergencyReset,
  kStop,
  kForce,
  kZeroForce,
  kPlay,
};

struct HmiOptions {
  std::string instance = "default";
  HmiCommand command = HmiCommand::kPanel;
  shm::Vector6 wrench{};       ///< kForce
  std::string sequence_path;   ///< kPlay
  std::string log_path;        ///< kPlay: CSV log ("-": stdout; empty: hapticctrl-sequence.csv)
  bool json = false;           ///< kStatus
  bool offer_restart = false;  ///< kPanel: offer R (exit 75) once the controller has ended
  bool power_on = false;       ///< kPlay: power on first
  bool with_hand = false;      ///< kPlay: a simulated hand grips the handle (--hand)
  HandOptions hand;            ///< kPlay with_hand: grip and wander
  std::chrono::milliseconds timeout{2000};  ///< how long a command waits for its effect
  bool help = false;

  static HmiOptions parse(const std::vector<std::string>& args);
  /// The --help text, generated from the same declarations.
  static std::string usage();
};

}  // namespace hapticctrl::hmi
