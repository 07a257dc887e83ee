// The full-screen panel driven through a pseudo-terminal, as an operator would: keys in, the
// controller's regions checked.
#include "hapticctrl/hmi/panel.hpp"

#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/wait.h>

#include "hapticctrl/hmi/operator.hpp"
#include "support/child_process.hpp"
#include "support/controller_stack.hpp"

namespace hapticctrl::hmi {
namespace {

using namespace std::chrono_literals;
using test::ControllerStack;

/// hapticctrl-hmi's panel on a pty; drains its screen output so that it never blocks.
class PanelOnPty {
 public:
  explicit PanelOnPty(const std::string& instance) {
    winsize size{};
    size.ws_row = 40;
    size.ws_col = 100;
    pid_ = forkpty(&fd_, nullptr, nullptr, &size);
    if (pid_ == 0) {
      setenv("TERM", "xterm", 1);
      execl(HAPTICCTRL_HMI_BINARY, "hapticctrl-hmi", "--instance", instance.c_str(), nullptr);
      _exit(127);
    }
  }
  PanelOnPty(const PanelOnPty&) = delete;
  PanelOnPty& operator=(const PanelOnPty&) = delete;
  ~PanelOnPty() {
    if (!reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    close(fd_);
  }
  void keys(const std::string& k) {
    ASSERT_EQ(write(fd_, k.data(), k.size()), static_cast<ssize_t>(k.size()));
    pump(150ms);
  }
  /// Reads the screen for `duration`.
  void pump(std::chrono::milliseconds duration) {
    const auto end = std::chrono::steady_clock::now() + duration;
    while (std::chrono::steady_clock::now() < end) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 10) > 0) {
        char buffer[4096];  // NOLINT(*-avoid-c-arrays)
        const ssize_t n = read(fd_, buffer, sizeof buffer);
        if (n <= 0) {
          return;
        }
        screen_.append(buffer, static_cast<std::size_t>(n));
      }
    }
  }
  int wait(std::chrono::milliseconds timeout) {
    for (auto end = std::chrono::steady_clock::now() + timeout;
         std::chrono::steady_clock::now() < end;) {
      pump(20ms);
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        reaped_ = true;
        return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
      }
    }
    return -1;
  }
  [[nodiscard]] const std::string& screen() const { return screen_; }

 private:
  int fd_ = -1;
  pid_t pid_ = -1;
  bool reaped_ = false;
  std::string screen_;
};

TEST(Panel, KeysPowerTheArmPushTheHandleAndStopTheController) {
  ControllerStack stack("panel");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator watch(stack.instance(), false);
  PanelOnPty panel(stack.instance());
  panel.pump(300ms);
  EXPECT_NE(panel.screen().find("power off"), std::string::npos);
  panel.keys("p");
  EXPECT_TRUE(ControllerStack::eventually([&] { return watch.status().powered(); }, 2s));
  panel.keys("1++");  // fx, two steps of 2 N
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return watch.status().position.operator_wrench[0] == 4.0; }, 2s))
      << "operator fx " << watch.status().position.operator_wrench[0];
  panel.keys("0");
  EXPECT_TRUE(ControllerStack::eventually(
      [&] { return watch.status().position.operator_wrench == shm::Vector6{}; }, 2s));
  panel.keys(" ");
  EXPECT_TRUE(ControllerStack::eventually([&] { return watch.status().emergency_stop(); }, 2s));
  panel.keys("r");
  EXPECT_TRUE(ControllerStack::eventually([&] { return !watch.status().emergency_stop(); }, 2s));
  panel.keys("Sn");
  EXPECT_TRUE(watch.controller_alive()) << "n cancels the stop";
  panel.keys("Sy");
  EXPECT_EQ(panel.wait(5s), 0) << "the panel leaves when the controller is gone";
  EXPECT_EQ(stack.core().wait(5s), 0);
  EXPECT_NE(panel.screen().find("POWER ON"), std::string::npos);
  EXPECT_NE(panel.screen().find("ended (stopping, stop requested)"), std::string::npos);
}

TEST(Panel, RefusesToRunWithoutATerminal) {
  ControllerStack stack("panelnotty");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), true);
  EXPECT_THROW((void)run_panel(op), HmiError);
}

}  // namespace
}  // namespace hapticctrl::hmi
