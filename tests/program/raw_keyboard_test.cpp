// Tests raw_keyboard.hpp: keys read without waiting from a terminal, the terminal restored, and
// nothing read when standard input is not a terminal.
#include "hapticctrl/program/raw_keyboard.hpp"

#include <fcntl.h>
#include <gtest/gtest.h>
#include <termios.h>
#include <unistd.h>

#include <cstdlib>

namespace hapticctrl::program {
namespace {

/// Standard input replaced by `fd` for the test's scope.
class StdinFrom {
 public:
  explicit StdinFrom(int fd) : saved_(dup(STDIN_FILENO)) { dup2(fd, STDIN_FILENO); }
  ~StdinFrom() {
    dup2(saved_, STDIN_FILENO);
    close(saved_);
  }
  StdinFrom(const StdinFrom&) = delete;
  StdinFrom& operator=(const StdinFrom&) = delete;

 private:
  int saved_;
};

/// A pseudo-terminal: the master writes what the program reads as typed keys.
struct PseudoTerminal {
  int master = posix_openpt(O_RDWR | O_NOCTTY);
  int slave = -1;
  PseudoTerminal() {
    if (master >= 0 && grantpt(master) == 0 && unlockpt(master) == 0) {
      slave = open(ptsname(master), O_RDWR | O_NOCTTY);
    }
  }
  ~PseudoTerminal() {
    close(slave);
    close(master);
  }
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;
};

TEST(RawKeyboard, ReadsEachKeyWithoutWaitingAndRestoresTheTerminal) {
  PseudoTerminal pty;
  ASSERT_GE(pty.slave, 0);
  const StdinFrom in(pty.slave);
  {
    const RawKeyboard keyboard;
    EXPECT_EQ(keyboard.poll(), -1);  // nothing typed: no wait
    ASSERT_EQ(write(pty.master, "qr", 2), 2);
    int first = -1;
    for (int i = 0; i < 1000 && first < 0; ++i) {  // the pty hands the bytes on asynchronously
      first = keyboard.poll();
      usleep(1000);
    }
    EXPECT_EQ(first, 'q');  // without a newline: not line-buffered
    EXPECT_EQ(keyboard.poll(), 'r');
    termios now{};
    ASSERT_EQ(tcgetattr(pty.slave, &now), 0);
    EXPECT_EQ(now.c_lflag & static_cast<tcflag_t>(ICANON | ECHO), 0U);
  }
  termios after{};
  ASSERT_EQ(tcgetattr(pty.slave, &after), 0);
  EXPECT_NE(after.c_lflag & static_cast<tcflag_t>(ICANON), 0U);
}

TEST(RawKeyboard, WithoutATerminalNothingIsRead) {
  int pipe_ends[2];
  ASSERT_EQ(pipe(pipe_ends), 0);
  ASSERT_EQ(write(pipe_ends[1], "q", 1), 1);
  {
    const StdinFrom in(pipe_ends[0]);
    const RawKeyboard keyboard;
    EXPECT_EQ(keyboard.poll(), -1);
  }
  close(pipe_ends[0]);
  close(pipe_ends[1]);
}

}  // namespace
}  // namespace hapticctrl::program
