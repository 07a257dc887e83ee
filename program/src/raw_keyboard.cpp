// Implements raw_keyboard.hpp: termios raw mode on standard input, restored on destruction.
#include "hapticctrl/program/raw_keyboard.hpp"

#include <unistd.h>

namespace hapticctrl::program {

RawKeyboard::RawKeyboard() {
  if (tcgetattr(STDIN_FILENO, &saved_) != 0) {
    return;
  }
  termios raw = saved_;
  raw.c_lflag &= ~static_cast<tcflag_t>(ICANON | ECHO);
  raw.c_cc[VMIN] = 0;
  raw.c_cc[VTIME] = 0;
  active_ = tcsetattr(STDIN_FILENO, TCSANOW, &raw) == 0;
}

RawKeyboard::~RawKeyboard() {
  if (active_) {
    tcsetattr(STDIN_FILENO, TCSANOW, &saved_);
  }
}

int RawKeyboard::poll() const {
  unsigned char c = 0;
  return active_ && read(STDIN_FILENO, &c, 1) == 1 ? c : -1;
}

}  // namespace hapticctrl::program
