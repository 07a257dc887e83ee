#pragma once
// Helpers of the segment tests (tests/shm/segment*_test.cpp, instance_lock_test.cpp): where an
// instance's names are, the expected errors, a forged header, a runtime directory of the test's
// own, playing another user, and a silent peer of the hand-off socket.
#include <grp.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/shm/segment_handoff.hpp"

namespace hapticctrl::test {

using shm::HandedSegment;
using shm::InstancePaths;
using shm::kPageSize;
using shm::SegmentHeader;
using shm::ShmErrc;
using shm::ShmError;

inline InstancePaths paths_of(const std::string& instance) {
  return InstancePaths::in(shm::creator_runtime_directory(), instance);
}

/// A connection to the instance's socket with nothing sent: what a silent or stuck peer holds.
/// -1 if it could not connect.
inline int connect_silently(const std::string& instance) {
  const std::string path = paths_of(instance).socket;
  const int fd = socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): the sockets API
  if (fd < 0 || connect(fd, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    if (fd >= 0) {
      close(fd);
    }
    return -1;
  }
  return fd;
}

/// `count` silent peers of the instance's hand-off socket (connect_silently), closed when this
/// goes (or by close_all()), so that a failed assertion leaves no descriptor open.
class SilentPeers {
 public:
  SilentPeers(const std::string& instance, int count) {
    for (int i = 0; i < count; ++i) {
      fds_.push_back(connect_silently(instance));
    }
  }
  ~SilentPeers() { close_all(); }
  SilentPeers(const SilentPeers&) = delete;
  SilentPeers& operator=(const SilentPeers&) = delete;

  /// How many of them connected (all of them, when the server took every connection).
  [[nodiscard]] std::size_t connected() const {
    return static_cast<std::size_t>(
        std::count_if(fds_.begin(), fds_.end(), [](int fd) { return fd >= 0; }));
  }
  [[nodiscard]] std::size_t size() const { return fds_.size(); }
  [[nodiscard]] int operator[](std::size_t i) const { return fds_[i]; }
  void close_all() {
    for (int& fd : fds_) {
      if (fd >= 0) {
        close(fd);
        fd = -1;
      }
    }
  }

 private:
  std::vector<int> fds_;
};

inline bool exists(const std::string& path) {
  struct stat st {};
  return stat(path.c_str(), &st) == 0;
}

/// Expects `fn` to throw ShmError with `code` and a message containing `text`.
template <typename Fn>
void expect_shm_error(Fn&& fn, ShmErrc code, const std::string& text) {
  try {
    fn();
    FAIL() << "expected ShmError containing '" << text << "'";
  } catch (const ShmError& e) {
    EXPECT_EQ(e.code(), code) << e.what();
    EXPECT_THAT(e.what(), testing::HasSubstr(text)) << e.what();
  }
}

/// Maps the raw header of an instance read-write, as a process of the group that asked for a
/// writable segment could, to forge bad segments.
class RawHeader {
 public:
  explicit RawHeader(const std::string& instance)
      : handed_(shm::request_segment(instance, true)),
        address_(mmap(nullptr, kPageSize, PROT_READ | PROT_WRITE, MAP_SHARED, handed_.segment.get(),
                      0)) {}
  RawHeader(const RawHeader&) = delete;
  RawHeader& operator=(const RawHeader&) = delete;
  ~RawHeader() { munmap(address_, kPageSize); }
  SegmentHeader* operator->() { return static_cast<SegmentHeader*>(address_); }

 private:
  HandedSegment handed_;
  void* address_ = nullptr;
};

/// Sets HAPTICCTRL_RUNTIME_DIR for the scope of a test (the processes it forks inherit it).
class RuntimeDirectory {
 public:
  explicit RuntimeDirectory(std::string path) : path_(std::move(path)) {
    setenv("HAPTICCTRL_RUNTIME_DIR", path_.c_str(), 1);
  }
  RuntimeDirectory(const RuntimeDirectory&) = delete;
  RuntimeDirectory& operator=(const RuntimeDirectory&) = delete;
  ~RuntimeDirectory() {
    unsetenv("HAPTICCTRL_RUNTIME_DIR");
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

/// In a forked child: becomes nobody/nogroup with no supplementary group (root only).
inline bool become_nobody() {
  return setgroups(0, nullptr) == 0 && setgid(65534) == 0 && setuid(65534) == 0;
}

}  // namespace hapticctrl::test
