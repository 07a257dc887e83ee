#pragma once
/// Starts a real binary with its stdout/stderr captured to files; kills and reaps it on
/// destruction, so a failing test leaves no process behind.

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "support/child_process.hpp"

namespace hapticctrl::test {

class SpawnedProcess {
 public:
  SpawnedProcess(const std::string& binary, const std::vector<std::string>& args) {
    static int counter = 0;
    const std::string base =
        "/tmp/hapticctrl-test-" + std::to_string(getpid()) + "-" + std::to_string(++counter);
    out_path_ = base + ".out";
    err_path_ = base + ".err";
    pid_ = fork();
    if (pid_ == 0) {
      const int out = open(out_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      const int err = open(err_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
      dup2(out, STDOUT_FILENO);
      dup2(err, STDERR_FILENO);
      std::vector<char*> argv;
      argv.push_back(const_cast<char*>(binary.c_str()));
      for (const auto& a : args) {
        argv.push_back(const_cast<char*>(a.c_str()));
      }
      argv.push_back(nullptr);
      execv(binary.c_str(), argv.data());
      _exit(127);
    }
  }
  SpawnedProcess(const SpawnedProcess&) = delete;
  SpawnedProcess& operator=(const SpawnedProcess&) = delete;
  ~SpawnedProcess() {
    if (pid_ > 0 && !reaped_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
    unlink(out_path_.c_str());
    unlink(err_path_.c_str());
  }

  [[nodiscard]] pid_t pid() const { return pid_; }
  /// Signals the process unless it has been reaped (its pid may belong to another by then).
  void signal(int sig) const {
    if (!reaped_) {
      kill(pid_, sig);
    }
  }

  /// Exit status, 128+signal if killed, -1 on timeout. Once reaped, the same status again.
  int wait(std::chrono::milliseconds timeout = std::chrono::seconds(30)) {
    if (!reaped_) {
      status_ = wait_for_exit(pid_, timeout, reaped_);
    }
    return status_;
  }

  [[nodiscard]] std::string out() const { return slurp(out_path_); }
  [[nodiscard]] std::string err() const { return slurp(err_path_); }

 private:
  static std::string slurp(const std::string& path) {
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
  }

  pid_t pid_ = -1;
  bool reaped_ = false;
  int status_ = -1;
  std::string out_path_;
  std::string err_path_;
};

}  // namespace hapticctrl::test
