#pragma once
/// Test helpers: unique instance names and forked children with bounded waits.

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <string>
#include <thread>

namespace hapticctrl::test {

/// An instance name no other concurrently running test uses.
inline std::string unique_instance(const std::string& tag) {
  static int counter = 0;
  return "t" + std::to_string(getpid()) + "-" + std::to_string(++counter) + "-" + tag;
}

/// Polls `pid` for up to `timeout`: its exit status, 128+signal if killed, -1 on timeout.
/// Sets `reaped` once the process has been collected.
inline int wait_for_exit(pid_t pid, std::chrono::milliseconds timeout, bool& reaped) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  while (std::chrono::steady_clock::now() < deadline) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid) {
      reaped = true;
      if (WIFEXITED(status)) {
        return WEXITSTATUS(status);
      }
      return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return -1;
}

/// A forked child running `body`; its return value is the exit status. The destructor kills
/// and reaps it, so a failing test never leaves a process behind.
class Child {
 public:
  explicit Child(const std::function<int()>& body) {
    pid_ = fork();
    if (pid_ == 0) {
      int status = 1;
      try {
        status = body();
      } catch (...) {
        status = 99;
      }
      _exit(status);
    }
  }
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;
  ~Child() {
    if (pid_ > 0 && !reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }

  [[nodiscard]] pid_t pid() const { return pid_; }

  /// Waits up to `timeout` for the child to exit; returns its exit status, 128+signal if it was
  /// killed, or -1 on timeout.
  int wait(std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
    return wait_for_exit(pid_, timeout, reaped_);
  }

  void kill_now(int sig = SIGKILL) { kill(pid_, sig); }

 private:
  pid_t pid_ = -1;
  bool reaped_ = false;
};

/// A pipe used to hand a byte from a child to the parent (e.g. "I am ready").
class ReadyPipe {
 public:
  ReadyPipe() {
    if (pipe(fds_) != 0) {
      std::abort();
    }
  }
  ReadyPipe(const ReadyPipe&) = delete;
  ReadyPipe& operator=(const ReadyPipe&) = delete;
  ~ReadyPipe() {
    ::close(fds_[0]);
    ::close(fds_[1]);
  }
  void signal(char c = 'r') { (void)!::write(fds_[1], &c, 1); }
  /// Waits for one byte, at most `timeout`. Returns the byte or 0 on timeout.
  char wait(std::chrono::milliseconds timeout = std::chrono::seconds(10)) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      fd_set set;
      FD_ZERO(&set);
      FD_SET(fds_[0], &set);
      timeval tv{0, 10000};
      if (select(fds_[0] + 1, &set, nullptr, nullptr, &tv) > 0) {
        char c = 0;
        if (::read(fds_[0], &c, 1) == 1) {
          return c;
        }
      }
    }
    return 0;
  }

 private:
  int fds_[2]{-1, -1};
};

}  // namespace hapticctrl::test
