#pragma once
/// @file raw_keyboard.hpp
/// The terminal as a raw, non-blocking keyboard for an interactive program's lifetime (no line
/// buffering, no echo); the terminal's settings come back when it goes. Not for the cycle.
#include <termios.h>

namespace hapticctrl::program {

class RawKeyboard {
 public:
  /// Raw mode on standard input, if it is a terminal (otherwise poll() always gives -1).
  RawKeyboard();
  ~RawKeyboard();
  RawKeyboard(const RawKeyboard&) = delete;
  RawKeyboard& operator=(const RawKeyboard&) = delete;
  RawKeyboard(RawKeyboard&&) = delete;
  RawKeyboard& operator=(RawKeyboard&&) = delete;
  /// The next key pressed, or -1; never waits.
  [[nodiscard]] int poll() const;

 private:
  termios saved_{};
  bool active_ = false;
};

}  // namespace hapticctrl::program
