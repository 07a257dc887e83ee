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
  explicit PanelOnPty(const std::string& instance, const char* option = nullptr) {
    winsize size{};
    size.ws_row = 40;
    size.ws_col = 100;
    pid_ = forkpty(&fd_, nullptr, nullptr, &size);
    if (pid_ == 0) {
      setenv("TERM", "xterm", 1);
      execl(HAPTICCTRL_HMI_BINARY, "hapticctrl-hmi", "--instance", instance.c_str(), option,
            nullptr);
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
  /// Reads the screen until `text` shows after `from` (bounded by `timeout`).
  bool shows(const std::string& text, std::size_t from = 0,
             std::chrono::milliseconds timeout = 5s) {
    for (auto end = std::chrono::steady_clock::now() + timeout;
         std::chrono::steady_clock::now() < end;) {
      if (screen_.find(text, from) != std::string::npos) {
        return true;
      }
      pump(20ms);
    }
    return screen_.find(text, from) != std::string::npos;
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
  EXPECT_EQ(stack.core().wait(5s), 0);
  EXPECT_TRUE(panel.shows("controller stopped: stop requested at "))
      << "the panel says how the controller ended";
  panel.keys("q");
  EXPECT_EQ(panel.wait(5s), 0);
  EXPECT_NE(panel.screen().find("POWER ON"), std::string::npos);
  EXPECT_NE(panel.screen().find("ended (stopping, stop requested)"), std::string::npos);
}

/// A core that overruns 5 cycles in a row at cycle 100 (1 s at the 10 ms period).
std::vector<std::string> failing_core() {
  return {"--allow-fault-injection", "--inject-overrun", "100:5"};
}

TEST(Panel, AFailSafeIsToldWithItsReasonAndTimeAndROffersANewController) {
  // H5: the operator read "no controller is running ... start hapticctrl-core first".
  ControllerStack stack("panelfs", ControllerStack::kDefaultPeriodUs, {}, failing_core());
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  PanelOnPty panel(stack.instance(), "--offer-restart");
  EXPECT_TRUE(panel.shows("controller failed safe: 5 consecutive deadline misses at ", 0, 10s))
      << panel.screen();
  EXPECT_TRUE(panel.shows("R start a new controller"));
  EXPECT_TRUE(panel.shows(": fail-safe: 5 consecutive deadline misses")) << "among the last events";
  panel.keys("R");
  EXPECT_EQ(panel.wait(5s), 75) << "the script that started the core is asked for a new one";
}

TEST(Panel, ReattachesToTheNextControllerOfTheInstance) {
  ControllerStack stack("panelre", ControllerStack::kDefaultPeriodUs, {}, failing_core());
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  PanelOnPty panel(stack.instance());
  ASSERT_TRUE(panel.shows("controller failed safe: ", 0, 10s)) << panel.screen();
  EXPECT_TRUE(panel.shows("re-attaches to a controller started again"));
  const std::size_t ended_at = panel.screen().size();
  stack.start_core();
  EXPECT_TRUE(panel.shows("power off", ended_at)) << "the panel of the new controller";
  panel.keys("q");
  EXPECT_EQ(panel.wait(5s), 0);
}

TEST(Panel, RefusesToRunWithoutATerminal) {
  ControllerStack stack("panelnotty");
  ASSERT_TRUE(stack.ready()) << stack.diagnostics();
  Operator op(stack.instance(), true);
  EXPECT_THROW((void)run_panel(op, false), HmiError);
}

}  // namespace
}  // namespace hapticctrl::hmi
