#pragma once
// Test support of hapticctrl-mujoco's world tests: an MJCF model written to a file for one test.
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace hapticctrl::mujoco::test {

/// A file with `text`, removed at the end of the test.
class TempModel {
 public:
  explicit TempModel(const std::string& text)
      : path_("/tmp/hapticctrl_world_test_" + std::to_string(getpid()) + ".xml") {
    std::ofstream(path_) << text;
  }
  ~TempModel() { std::remove(path_.c_str()); }
  TempModel(const TempModel&) = delete;
  TempModel& operator=(const TempModel&) = delete;
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace hapticctrl::mujoco::test
