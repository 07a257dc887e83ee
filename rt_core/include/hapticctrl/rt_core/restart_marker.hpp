#pragma once
/// @file restart_marker.hpp
/// Whether the core before this one stopped in order. A running core keeps a marker file in its
/// state directory and removes it only when it stops in order; a core killed, crashed or failed
/// safe leaves it, and the next core of the instance then waits for an operator before a client
/// may power the arm on (IEC 60204-1 7.5: no restart of its own after a fault). Before
/// 2026-12-05 a client powered a restarted controller on 18 cycles after it came up (J8 review:
/// `R` in the panel, then the demo).
///
/// Not for the cycle (file I/O): made before the cycle starts, cleared after it ended.

#include <string>

#include "hapticctrl/program/private_directory.hpp"

namespace hapticctrl::rt_core {

using program::PrivateDirectory;

class RestartMarker {
 public:
  /// Reads whether an earlier core of `instance` left its marker (`hapticctrl-running.<instance>`
  /// in `directory`, which must outlive this object), then marks this core as running (when, UTC,
  /// and by which pid). Throws std::runtime_error when the marker cannot be written.
  RestartMarker(const PrivateDirectory& directory, const std::string& instance);

  /// True when the core before this one did not stop in order (anything at the marker's name
  /// counts: the safe side).
  [[nodiscard]] bool left_by_earlier() const noexcept { return left_; }
  /// What the earlier core wrote in it; empty if nothing was readable.
  [[nodiscard]] const std::string& left_note() const noexcept { return left_note_; }

  /// This core stopped in order: removes the marker. Throws std::runtime_error.
  void stopped_in_order();

 private:
  const PrivateDirectory* directory_;
  std::string name_;
  bool left_ = false;
  std::string left_note_;
};

}  // namespace hapticctrl::rt_core
