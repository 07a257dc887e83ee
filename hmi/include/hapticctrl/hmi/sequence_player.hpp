#pragma once
/// @file sequence_player.hpp
/// Plays a WrenchSequence as the operator force on the simulated handle and logs the arm's
/// response, one CSV row per controller cycle (paced by the core's VP publishes).
#include <cstdint>
#include <optional>
#include <ostream>

#include "hapticctrl/hmi/hand_motion.hpp"
#include "hapticctrl/hmi/operator.hpp"
#include "hapticctrl/hmi/wrench_sequence.hpp"

namespace hapticctrl::hmi {

struct PlayResult {
  std::uint64_t rows = 0;           ///< CSV rows written (controller cycles seen)
  double played_s = 0.0;            ///< how long the sequence ran
  bool controller_stopped = false;  ///< the controller stopped or failed safe during playback
};

/// CSV header of the log (t_s, cycle, state_word, the requested and applied operator wrench -
/// the applied one includes the hand's force -, the handle pose, the joint angles, the coupling
/// wrench on the client's object (cpl_*), the wrench the controller renders on the handle
/// (ren_*: coupling, guards and walls; gravity compensation apart), and the hand's anchor and
/// stiffness, 0 without a hand).
[[nodiscard]] const char* sequence_log_header() noexcept;

/// Plays `sequence` through `op` (which must hold the force region), then ramps the force back
/// to zero. With `hand`, a simulated hand (HandMotion) grips the handle where it is at the start,
/// wanders as asked while the sequence plays (its wrench adds to the hand's), and lets go at the
/// end through its ramp. Writes the header and one row per controller cycle to `log`. Throws
/// HmiError if the operator has no force region or the controller no position,
/// std::invalid_argument for a hand out of range. Bounded: the sequence's duration plus the
/// final ramps.
PlayResult play_sequence(Operator& op, const WrenchSequence& sequence, std::ostream& log,
                         const std::optional<HandOptions>& hand = std::nullopt);

}  // namespace hapticctrl::hmi
