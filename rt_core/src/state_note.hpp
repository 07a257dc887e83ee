#pragma once
// The notes the core leaves in its state directory (the emergency stop's latch, the restart
// marker): when, in UTC, and their text read back. Internal to rt_core; setup code only.
#include <unistd.h>

#include <array>
#include <ctime>
#include <string>

#include "hapticctrl/program/private_directory.hpp"

namespace hapticctrl::rt_core {

/// "`what` at YYYY-MM-DD HH:MM:SS UTC (core pid N)\n".
inline std::string state_note(const std::string& what) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%d %H:%M:%S UTC", &utc);
  return what + " " + text.data() + " (core pid " + std::to_string(getpid()) + ")\n";
}

/// The note `name` in `directory` without its line end; empty if it cannot be read.
inline std::string read_state_note(const program::PrivateDirectory& directory,
                                   const std::string& name) {
  std::string note = directory.read_file(name);
  while (!note.empty() && (note.back() == '\n' || note.back() == '\r')) {
    note.pop_back();
  }
  return note;
}

}  // namespace hapticctrl::rt_core
