// Implements rendezvous.hpp: where an instance is found: the runtime directory that holds each
// instance's socket (which hands out the segment) and the core's lock, and who may be trusted to
// own it.
#include "hapticctrl/shm/rendezvous.hpp"

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>

#include "hapticctrl/shm/error.hpp"

namespace hapticctrl::shm {
namespace {

constexpr std::size_t kMaxInstanceName = 32;
constexpr std::string_view kSystemDirectory = "/run/hapticctrl";
constexpr std::string_view kSocketSuffix = ".sock";
constexpr mode_t kDirectoryMode = 0750;

std::string environment(const char* name) {
  const char* value = std::getenv(name);  // NOLINT(concurrency-mt-unsafe): setup, before threads
  return value == nullptr ? std::string() : std::string(value);
}

/// This user's own directory: under $XDG_RUNTIME_DIR (private to the user, made by logind) or,
/// without one (containers, CI), /tmp/hapticctrl-<uid>, which another user could squat: the
/// owner check then refuses it with what to do.
std::string user_directory() {
  const std::string xdg = environment("XDG_RUNTIME_DIR");
  if (!xdg.empty()) {
    return xdg + "/hapticctrl";
  }
  return "/tmp/hapticctrl-" + std::to_string(geteuid());
}

bool exists(const std::string& path) {
  struct stat st {};
  return lstat(path.c_str(), &st) == 0;
}

std::string parent_of(const std::string& directory) {
  const auto slash = directory.find_last_of('/');
  if (slash == std::string::npos) {
    return ".";
  }
  return slash == 0 ? "/" : directory.substr(0, slash);
}

bool writable_by_others(const struct stat& st) {
  return (st.st_mode & (S_IWGRP | S_IWOTH)) != 0;
}

}  // namespace

void validate_instance_name(std::string_view instance) {
  const bool valid_chars = std::all_of(instance.begin(), instance.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '-';
  });
  if (instance.empty() || instance.size() > kMaxInstanceName || !valid_chars) {
    throw ShmError(ShmErrc::kBadInstanceName, "invalid instance name '" + std::string(instance) +
                                                  "': use 1 to 32 characters from [A-Za-z0-9_-]");
  }
}

InstancePaths InstancePaths::in(const std::string& directory, std::string_view instance) {
  validate_instance_name(instance);
  const std::string base = directory + "/" + std::string(instance);
  return InstancePaths{directory, base + std::string(kSocketSuffix), base + ".lock"};
}

std::string creator_runtime_directory() {
  if (std::string configured = environment("HAPTICCTRL_RUNTIME_DIR"); !configured.empty()) {
    return configured;
  }
  std::string system(kSystemDirectory);
  if (geteuid() == 0 || exists(system)) {
    return system;
  }
  return user_directory();
}

std::vector<std::string> attacher_runtime_directories() {
  if (std::string configured = environment("HAPTICCTRL_RUNTIME_DIR"); !configured.empty()) {
    return {configured};
  }
  return {std::string(kSystemDirectory), user_directory()};
}

uid_t trusted_directory_owner(const std::string& directory) {
  struct stat st {};
  if (lstat(directory.c_str(), &st) != 0) {
    if (errno == ENOENT) {
      throw ShmError(ShmErrc::kNoController, "the runtime directory " + directory +
                                                 " does not exist (no controller has run there)");
    }
    throw_system_error("stat " + directory, errno);
  }
  if (!S_ISDIR(st.st_mode)) {
    throw ShmError(ShmErrc::kInsecure, directory + " is not a directory (a symlink or file " +
                                           "there could point anywhere); remove it");
  }
  if (writable_by_others(st)) {
    throw ShmError(ShmErrc::kInsecure,
                   directory + " may be written by its group or by others (mode " +
                       std::to_string(st.st_mode & 07777) +
                       " decimal): anyone there could plant a controller; make it 0750");
  }
  if (st.st_uid == 0 || st.st_uid == geteuid()) {
    return st.st_uid;
  }
  // Owned by another user: trusted only if root handed it out (as systemd's RuntimeDirectory=
  // does under /run), i.e. only root can create or replace it.
  struct stat parent {};
  const std::string above = parent_of(directory);
  if (lstat(above.c_str(), &parent) == 0 && S_ISDIR(parent.st_mode) && parent.st_uid == 0 &&
      !writable_by_others(parent)) {
    return st.st_uid;
  }
  throw ShmError(ShmErrc::kInsecure,
                 directory + " belongs to uid " + std::to_string(st.st_uid) +
                     ", which is neither root nor this process's user, in " + above +
                     " where others may create directories: it could have been planted. "
                     "Remove it, or set HAPTICCTRL_RUNTIME_DIR to a directory root gave the "
                     "controller's user (see docs/security.md)");
}

void prepare_runtime_directory(const std::string& directory, gid_t group) {
  if (mkdir(directory.c_str(), kDirectoryMode) != 0 && errno != EEXIST) {
    throw_system_error("create the runtime directory " + directory, errno);
  }
  trusted_directory_owner(directory);
  struct stat st {};
  if (lstat(directory.c_str(), &st) == 0 && st.st_uid == geteuid()) {
    // Ours: group members may enter it (to connect), nobody else; whatever the umask was.
    if (chmod(directory.c_str(), kDirectoryMode) != 0) {
      throw_system_error("chmod " + directory, errno);
    }
    if (group != static_cast<gid_t>(-1) && st.st_gid != group &&
        chown(directory.c_str(), static_cast<uid_t>(-1), group) != 0) {
      throw_system_error("chown " + directory + " to group " + std::to_string(group), errno);
    }
  }
}

std::vector<std::string> listed_instances() {
  std::vector<std::string> names;
  for (const std::string& directory : attacher_runtime_directories()) {
    DIR* dir = opendir(directory.c_str());
    if (dir == nullptr) {
      continue;
    }
    while (const dirent* entry = readdir(dir)) {
      const std::string name = entry->d_name;
      if (name.size() > kSocketSuffix.size() && name.ends_with(kSocketSuffix)) {
        names.push_back(name.substr(0, name.size() - kSocketSuffix.size()));
      }
    }
    closedir(dir);
  }
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  return names;
}

}  // namespace hapticctrl::shm
