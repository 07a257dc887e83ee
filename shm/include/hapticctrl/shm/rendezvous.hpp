#pragma once
/// @file rendezvous.hpp
/// Where an instance is found: the runtime directory that holds each instance's socket (which
/// hands out the segment) and the core's lock, and who may be trusted to own it.
///
/// Setup code only: every function here may allocate, make syscalls and throw ShmError.

#include <sys/types.h>

#include <string>
#include <string_view>
#include <vector>

namespace hapticctrl::shm {

/// The files of one instance in a runtime directory.
struct InstancePaths {
  std::string directory;
  std::string socket;  ///< `<directory>/<instance>.sock`: hands the segment to attachers
  std::string lock;    ///< `<directory>/<instance>.lock`: the live core's exclusive flock

  /// Throws ShmError(kBadInstanceName) unless `instance` is 1-32 of [A-Za-z0-9_-].
  static InstancePaths in(const std::string& directory, std::string_view instance);
};

/// Throws ShmError(kBadInstanceName) unless `instance` is 1-32 of [A-Za-z0-9_-].
void validate_instance_name(std::string_view instance);

/// The directory a core creates its instance in: `$HAPTICCTRL_RUNTIME_DIR` when set; else
/// `/run/hapticctrl` for root, or when it exists (a deployment's, e.g. systemd's
/// RuntimeDirectory); else `$XDG_RUNTIME_DIR/hapticctrl`; else `/tmp/hapticctrl-<uid>`.
[[nodiscard]] std::string creator_runtime_directory();

/// The directories an attacher looks in, in order: `$HAPTICCTRL_RUNTIME_DIR` alone when set;
/// else `/run/hapticctrl`, then this user's own directory (as above).
[[nodiscard]] std::vector<std::string> attacher_runtime_directories();

/// Checks that `directory` may be trusted to hold a controller's socket and returns its owner:
/// a real directory (not a symlink) that neither group nor others may write, owned by root, by
/// this process's user, or handed out by root (its parent is root's and only root may write
/// it, as /run). Anything else could have been planted by another user: ShmError(kInsecure).
/// ShmError(kNoController) when it does not exist.
uid_t trusted_directory_owner(const std::string& directory);

/// The creator's side: creates `directory` (mode 0750, group `group` unless -1) if missing,
/// then checks it as trusted_directory_owner() does. Throws ShmError.
void prepare_runtime_directory(const std::string& directory, gid_t group);

/// Names of the instances whose socket is in the attacher's directories (running, or left by a
/// core that died), sorted, without duplicates.
[[nodiscard]] std::vector<std::string> listed_instances();

}  // namespace hapticctrl::shm
