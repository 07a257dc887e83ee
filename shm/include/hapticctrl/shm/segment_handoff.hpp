#pragma once
/// @file segment_handoff.hpp
/// How a segment travels from the core to the processes that map it: the core's segment is a
/// sealed memfd (it cannot be shrunk or grown, so nobody can make a mapping fault with SIGBUS)
/// that has no name anyone could open, squat or plant. The core serves it on a Unix-domain
/// socket in its runtime directory (rendezvous.hpp); each side checks the other's credentials
/// (SO_PEERCRED): the core serves only its own user, root and members of its group; the
/// attacher accepts only a core that runs as the directory's owner or as root.
///
/// Setup code only: nothing here is for the cycle. Segment uses it; tests use request_segment()
/// to play a process of the group that scribbles or truncates.

#include <sys/types.h>

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "hapticctrl/shm/rendezvous.hpp"

namespace hapticctrl::shm {

/// An owned file descriptor, closed on destruction.
class UniqueFd {
 public:
  UniqueFd() = default;
  explicit UniqueFd(int fd) noexcept : fd_(fd) {}
  UniqueFd(UniqueFd&& other) noexcept : fd_(other.release()) {}
  UniqueFd& operator=(UniqueFd&& other) noexcept;
  UniqueFd(const UniqueFd&) = delete;
  UniqueFd& operator=(const UniqueFd&) = delete;
  ~UniqueFd() { reset(); }

  [[nodiscard]] int get() const noexcept { return fd_; }
  [[nodiscard]] bool valid() const noexcept { return fd_ >= 0; }
  int release() noexcept;
  void reset() noexcept;

 private:
  int fd_ = -1;
};

/// Creates a segment of `size` bytes as a memfd named `name` (for /proc only), sealed against
/// shrinking, growing and further seals: what request_segment() checks. Throws ShmError.
[[nodiscard]] int create_sealed_segment(const std::string& name, std::size_t size);

/// What the core hands an attacher.
struct HandedSegment {
  UniqueFd segment;  ///< the sealed memfd: read-write if asked for, read-only otherwise
  UniqueFd core;     ///< a pidfd of the core: readable once the core has exited
  pid_t core_pid = 0;
  uid_t core_uid = 0;
};

/// Serves one instance's segment: listens on `paths.socket` and answers requests on a thread of
/// its own (signals blocked, 64 KiB stack, never the cycle's CPU time: it sleeps in poll until
/// someone connects). Up to 256 peers at once, none able to hold up another: a peer's
/// credentials are checked right after accept, before anything is read (outsiders get their
/// refusal at once); an allowed peer has 200 ms to send its request, read without blocking.
class SegmentServer {
 public:
  /// Binds `paths.socket` (mode 0660, group `group` unless -1; a stale socket is replaced: the
  /// caller holds the instance lock) and starts serving `segment_fd`. Throws ShmError.
  SegmentServer(const InstancePaths& paths, int segment_fd, gid_t group);
  SegmentServer(const SegmentServer&) = delete;
  SegmentServer& operator=(const SegmentServer&) = delete;
  /// Stops serving and removes the socket.
  ~SegmentServer();

  /// Requests answered with the segment, and refused (a peer that is not the core's user, root
  /// or in its group; a malformed request; silent for 200 ms). Any thread.
  [[nodiscard]] std::uint64_t served() const noexcept;
  [[nodiscard]] std::uint64_t refused() const noexcept;

  struct State;

 private:
  std::unique_ptr<State> state_;
};

/// Asks the core that serves `instance` for its segment, in the attacher's runtime directories
/// (rendezvous.hpp), checking the directory, the core's credentials, the seals and the size.
/// Throws ShmError: kNoController (no socket, or left by a core that is gone), kPermissionDenied,
/// kInsecure (an untrusted directory or core, an unsealed segment), kLayoutMismatch.
[[nodiscard]] HandedSegment request_segment(std::string_view instance, bool writable);

}  // namespace hapticctrl::shm
