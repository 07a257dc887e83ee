// The instance lock: the flock that marks the live core of an instance, and the "pid
// generation" record a core leaves in it for the next one (instance_lock.hpp).
#include "instance_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "hapticctrl/shm/error.hpp"

namespace hapticctrl::shm {
namespace {

constexpr mode_t kLockMode = 0600;

}  // namespace

LockRecord read_lock_record(int fd) {
  std::array<char, 64> text{};
  const ssize_t got = pread(fd, text.data(), text.size() - 1, 0);
  LockRecord record;
  if (got > 0) {
    // "PID GENERATION": both whole numbers, or the record is not one (a torn or foreign file).
    char* end = nullptr;
    errno = 0;
    const long pid = std::strtol(text.data(), &end, 10);
    const char* rest = end;
    const unsigned long long generation = std::strtoull(rest, &end, 10);
    if (errno == 0 && rest != text.data() && end != rest && *rest == ' ') {
      record.pid = pid;
      record.generation = generation;
    }
  }
  return record;
}

void write_lock_record(int fd, const LockRecord& record) {
  const std::string text =
      std::to_string(record.pid) + " " + std::to_string(record.generation) + "\n";
  if (ftruncate(fd, 0) != 0 || pwrite(fd, text.data(), text.size(), 0) < 0) {
    throw_system_error("write the instance lock", errno);
  }
}

int acquire_instance_lock(const InstancePaths& paths, const std::string& instance) {
  for (int attempt = 0; attempt < 5; ++attempt) {
    const int fd = open(paths.lock.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, kLockMode);
    if (fd < 0) {
      throw_system_error("open the instance lock " + paths.lock, errno);
    }
    if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int error = errno;
      const LockRecord holder = read_lock_record(fd);
      ::close(fd);
      if (error == EWOULDBLOCK) {
        throw ShmError(
            ShmErrc::kAlreadyRunning,
            "instance '" + instance + "' is already running" +
                (holder.pid > 0 ? " (core pid " + std::to_string(holder.pid) + ")" : "") +
                "; stop it first or choose another --instance");
      }
      throw_system_error("lock " + paths.lock, error);
    }
    struct stat held {};
    struct stat named {};
    if (fstat(fd, &held) == 0 && lstat(paths.lock.c_str(), &named) == 0 &&
        held.st_ino == named.st_ino) {
      return fd;
    }
    ::close(fd);
  }
  throw ShmError(ShmErrc::kSystem,
                 "could not take the lock of instance '" + instance + "' (it kept being replaced)");
}

}  // namespace hapticctrl::shm
