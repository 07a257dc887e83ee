#pragma once
/// @file estop_latch.hpp
/// The latched emergency stop kept as a file in the core's state directory, so that it outlives
/// the process: a core killed, crashed or stopped while the stop was latched leaves the file, and
/// the next core of the instance starts with the stop latched and refuses power-on until an
/// operator resets it (ISO 13850, IEC 60204-1: latched until a deliberate reset). Before
/// 2026-12-04 a restarted core forgot it (9 of 9, J4 review).
///
/// Not for the cycle (file I/O): the core's latch keeper, a thread of its own, follows the state
/// the cycle publishes (docs/rt_core.md).

#include <string>

#include "hapticctrl/program/private_directory.hpp"

namespace hapticctrl::rt_core {

using program::PrivateDirectory;

class EstopLatchFile {
 public:
  /// The latch of `instance` in `directory` (`hapticctrl-estop.<instance>`), which must outlive
  /// this object. Reads whether an earlier core left it latched. Throws std::runtime_error.
  EstopLatchFile(const PrivateDirectory& directory, const std::string& instance);

  /// True when the stop was latched when this object was made (an earlier core left it so).
  [[nodiscard]] bool left_latched() const noexcept { return left_latched_; }
  /// What the earlier core wrote in it (when, which pid); empty if nothing was readable.
  [[nodiscard]] const std::string& left_note() const noexcept { return left_note_; }

  /// Makes the file agree with `latched`: creates it (saying when, UTC, and by which pid) when
  /// the stop latches, removes it when an operator reset it. Does nothing when it already
  /// agrees, so it may be called on every poll. Throws std::runtime_error when the file cannot
  /// be written or removed (the next call tries again).
  void follow(bool latched);

 private:
  const PrivateDirectory* directory_;
  std::string name_;
  bool on_file_ = false;
  bool left_latched_ = false;
  std::string left_note_;
};

}  // namespace hapticctrl::rt_core
