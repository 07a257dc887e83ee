// Implements private_directory.hpp: a directory only the controller's user can write, and files
// created in it exclusively, never through a link, mode 0600.
#include "hapticctrl/program/private_directory.hpp"

#include <dirent.h>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace hapticctrl::program {
namespace {

constexpr mode_t kFileMode = 0600;
constexpr std::size_t kMaxRead =
    std::size_t{64} * 1024;  ///< read_file() reads no more (notes, not data)
/// Names tried for one file of a series: its own, then .2 ... (a pid the directory saw before).
constexpr int kNameAttempts = 100;

[[noreturn]] void fail(const std::string& what, int error) {
  throw std::runtime_error(what + ": " + std::strerror(error));
}

void check_plain_name(const std::string& name) {
  if (name.empty() || name.find('/') != std::string::npos || name == "." || name == "..") {
    throw std::invalid_argument("'" + name + "' is not a plain file name");
  }
}

}  // namespace

PrivateDirectory::PrivateDirectory(std::string path) : path_(std::move(path)) {
  fd_ = open(path_.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (fd_ < 0) {
    const int error = errno;
    if (error == ELOOP || error == ENOTDIR) {
      throw std::runtime_error(path_ + " is not a directory (a symlink there could point " +
                               "anywhere): give a real directory");
    }
    fail("cannot open the directory " + path_, error);
  }
  struct stat st {};
  if (fstat(fd_, &st) != 0) {
    const int error = errno;
    close(fd_);
    fail("stat " + path_, error);
  }
  std::string problem;
  if (st.st_uid != geteuid() && st.st_uid != 0) {
    problem = "is owned by user " + std::to_string(st.st_uid) + ", not by this one (" +
              std::to_string(geteuid()) + ") or root";
  } else if ((st.st_mode & (S_IWGRP | S_IWOTH)) != 0) {
    problem = "may be written by its group or by others (mode " +
              std::to_string((st.st_mode >> 6) & 7) + std::to_string((st.st_mode >> 3) & 7) +
              std::to_string(st.st_mode & 7) + ")";
  }
  if (!problem.empty()) {
    close(fd_);
    fd_ = -1;
    throw std::runtime_error(path_ + " " + problem +
                             ": another user could plant a link there; give a directory only " +
                             "this user can write (the runtime directory, or a state directory)");
  }
}

PrivateDirectory::~PrivateDirectory() {
  if (fd_ >= 0) {
    close(fd_);
  }
}

PrivateDirectory::PrivateDirectory(PrivateDirectory&& other) noexcept
    : path_(std::move(other.path_)), fd_(std::exchange(other.fd_, -1)) {}

PrivateDirectory& PrivateDirectory::operator=(PrivateDirectory&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) {
      close(fd_);
    }
    path_ = std::move(other.path_);
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

bool PrivateDirectory::create_file(const std::string& name, std::string_view text) const {
  check_plain_name(name);
  const int fd =
      openat(fd_, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, kFileMode);
  if (fd < 0) {
    if (errno == EEXIST) {
      return false;
    }
    fail("cannot create " + path_ + "/" + name, errno);
  }
  // The umask may have taken bits away, never added any: 0600 exactly.
  int error = fchmod(fd, kFileMode) == 0 ? 0 : errno;
  for (std::size_t done = 0; error == 0 && done < text.size();) {
    const ssize_t n = write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno != EINTR) {
      error = errno;
    } else if (n > 0) {
      done += static_cast<std::size_t>(n);
    }
  }
  if (error == 0 && fsync(fd) != 0) {
    error = errno;
  }
  close(fd);
  if (error != 0) {
    fail("cannot write " + path_ + "/" + name, error);
  }
  return true;
}

std::vector<std::string> PrivateDirectory::files(std::string_view prefix,
                                                 std::string_view suffix) const {
  const int listing = openat(fd_, ".", O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  DIR* dir = listing >= 0 ? fdopendir(listing) : nullptr;
  if (dir == nullptr) {
    const int error = errno;
    if (listing >= 0) {
      close(listing);
    }
    fail("cannot list " + path_, error);
  }
  std::vector<std::tuple<std::int64_t, std::int64_t, std::string>> found;
  while (const dirent* entry = readdir(dir)) {
    const std::string_view name = entry->d_name;
    struct stat st {};
    if (name.size() < prefix.size() + suffix.size() || !name.starts_with(prefix) ||
        !name.ends_with(suffix) || fstatat(fd_, entry->d_name, &st, AT_SYMLINK_NOFOLLOW) != 0 ||
        !S_ISREG(st.st_mode)) {
      continue;
    }
    found.emplace_back(st.st_mtim.tv_sec, st.st_mtim.tv_nsec, std::string(name));
  }
  closedir(dir);
  std::sort(found.begin(), found.end());
  std::vector<std::string> names;
  names.reserve(found.size());
  for (auto& f : found) {
    names.push_back(std::move(std::get<2>(f)));
  }
  return names;
}

bool PrivateDirectory::contains(const std::string& name) const {
  check_plain_name(name);
  struct stat st {};
  if (fstatat(fd_, name.c_str(), &st, AT_SYMLINK_NOFOLLOW) == 0) {
    return true;
  }
  if (errno == ENOENT) {
    return false;
  }
  fail("stat " + path_ + "/" + name, errno);
}

std::string PrivateDirectory::read_file(const std::string& name) const {
  check_plain_name(name);
  const int fd = openat(fd_, name.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) {
    return "";
  }
  std::string text;
  struct stat st {};
  if (fstat(fd, &st) == 0 && S_ISREG(st.st_mode)) {
    std::array<char, 4096> chunk{};
    for (ssize_t n = 0; (n = read(fd, chunk.data(), chunk.size())) > 0 && text.size() < kMaxRead;) {
      text.append(chunk.data(), static_cast<std::size_t>(n));
    }
  }
  close(fd);
  return text;
}

std::string PrivateDirectory::add_to_series(const std::string& prefix, const std::string& stem,
                                            const std::string& suffix, std::string_view text,
                                            std::size_t keep) const {
  std::string written;
  for (int n = 1; n <= kNameAttempts && written.empty(); ++n) {
    std::string name = prefix;
    name += stem;
    if (n > 1) {
      name += "." + std::to_string(n);
    }
    name += suffix;
    if (create_file(name, text)) {
      written = name;
    }
  }
  if (written.empty()) {
    throw std::runtime_error("no free name in " + path_ + " for " + prefix + stem + suffix +
                             " after " + std::to_string(kNameAttempts) + " tries");
  }
  std::vector<std::string> kept = files(prefix, suffix);
  std::erase(kept, written);  // the new one stays whatever its time stamp
  const std::size_t others = keep > 0 ? keep - 1 : 0;
  for (std::size_t i = 0; i + others < kept.size(); ++i) {
    remove(kept[i]);
  }
  return path_ + "/" + written;
}

bool PrivateDirectory::remove(const std::string& name) const {
  check_plain_name(name);
  if (unlinkat(fd_, name.c_str(), 0) == 0) {
    return true;
  }
  if (errno == ENOENT) {
    return false;
  }
  fail("cannot remove " + path_ + "/" + name, errno);
}

}  // namespace hapticctrl::program
