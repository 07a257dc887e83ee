#pragma once
// What the core and an attacher say on the handoff socket (segment_handoff.cpp serves,
// segment_request.cpp asks): the request and reply records, the descriptors handed, the seals
// and timeouts, and the socket helpers both sides use. Internal to shm/; setup code only.
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <sys/un.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>

#include "hapticctrl/shm/error.hpp"
#include "hapticctrl/shm/layout.hpp"

namespace hapticctrl::shm::handoff {

inline constexpr std::uint32_t kRequestMagic = 0x48435251;  // "HCRQ"
inline constexpr std::uint32_t kReplyMagic = 0x48435250;    // "HCRP"
inline constexpr std::size_t kHandedFds = 2;                // the segment, the core's pidfd
inline constexpr std::size_t kServerStack = std::size_t{64} * 1024;
inline constexpr std::size_t kMaxPeerGroups = 256;
/// A peer that has not sent its request within this is dropped (it holds one of the server's
/// slots meanwhile, never the server).
inline constexpr std::chrono::milliseconds kPeerDeadline{200};
/// Connections the kernel queues before the server accepts them (it accepts all it can at once).
inline constexpr int kBacklog = 256;
inline constexpr timeval kAttacherTimeout{2, 0};  // a core that does not answer is reported
/// A core that closed a connection within kBusyAnswer had every peer slot held: the attacher asks
/// again after kBusyPause, kBusyAttempts times in all (about 0.5 s).
inline constexpr std::chrono::milliseconds kBusyAnswer{50};
inline constexpr std::chrono::milliseconds kBusyPause{50};
inline constexpr int kBusyAttempts = 10;
inline constexpr unsigned kSeals = F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL;

enum class ReplyStatus : std::uint32_t { kServed = 0, kRefused = 1, kBadRequest = 2 };

struct Request {
  std::uint32_t magic = kRequestMagic;
  std::uint32_t abi_version = kAbiVersion;
  std::uint32_t writable = 0;
};

struct Reply {
  std::uint32_t magic = kReplyMagic;
  ReplyStatus status = ReplyStatus::kServed;
};

inline sockaddr_un socket_address(const std::string& path) {
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  if (path.size() >= sizeof(address.sun_path)) {
    throw ShmError(ShmErrc::kSystem, "socket path " + path + " is longer than the " +
                                         std::to_string(sizeof(address.sun_path) - 1) +
                                         " characters a Unix socket allows: choose a shorter "
                                         "HAPTICCTRL_RUNTIME_DIR");
  }
  std::memcpy(address.sun_path, path.c_str(), path.size() + 1);
  return address;
}

inline ucred peer_credentials(int socket) {
  ucred cred{};
  socklen_t length = sizeof(cred);
  if (getsockopt(socket, SOL_SOCKET, SO_PEERCRED, &cred, &length) != 0) {
    cred.pid = 0;
    cred.uid = static_cast<uid_t>(-1);
    cred.gid = static_cast<gid_t>(-1);
  }
  return cred;
}

inline void set_timeouts(int socket, const timeval& timeout) {
  setsockopt(socket, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  setsockopt(socket, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout));
}

}  // namespace hapticctrl::shm::handoff
