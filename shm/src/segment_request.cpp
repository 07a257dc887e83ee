// request_segment: the attacher's side of the handoff. It finds the core's socket, checks the
// core's credentials, asks for the segment and checks what it was handed (sealed, the expected
// size, the access asked for). The core's side is segment_handoff.cpp.
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <string>
#include <thread>
#include <utility>

#include "handoff_wire.hpp"
#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/segment_handoff.hpp"

namespace hapticctrl::shm {
namespace {

using namespace handoff;  // NOLINT(google-build-using-namespace): this file speaks it

/// False only when the socket is surely not there: a directory this process may not search
/// is reported by the connect that follows (permission denied), not as a missing controller.
bool socket_present(const std::string& path) {
  struct stat st {};
  return lstat(path.c_str(), &st) == 0 || errno != ENOENT;
}

UniqueFd connect_to_core(const InstancePaths& paths, std::string_view instance) {
  const sockaddr_un address = socket_address(paths.socket);
  UniqueFd socket_fd(socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!socket_fd.valid()) {
    throw_system_error("create a socket", errno);
  }
  set_timeouts(socket_fd.get(), kAttacherTimeout);
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): the sockets API
  if (connect(socket_fd.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    if (errno == ECONNREFUSED || errno == ENOENT) {
      throw ShmError(ShmErrc::kNoController,
                     "no controller is running for instance '" + std::string(instance) +
                         "': " + paths.socket +
                         " was left by a core that is gone; the next core start " + "replaces it");
    }
    throw_system_error("connect to the controller of instance '" + std::string(instance) + "' (" +
                           paths.socket + ")",
                       errno);
  }
  return socket_fd;
}

/// Receives the reply and its descriptors; every descriptor received is owned, whatever fails.
Reply receive_reply(int socket, std::array<UniqueFd, kHandedFds>& fds, std::size_t& count) {
  Reply reply{};
  iovec data{&reply, sizeof(reply)};
  alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(int) * kHandedFds)> control{};
  msghdr message{};
  message.msg_iov = &data;
  message.msg_iovlen = 1;
  message.msg_control = control.data();
  message.msg_controllen = control.size();
  const ssize_t got = recvmsg(socket, &message, MSG_CMSG_CLOEXEC | MSG_WAITALL);
  count = 0;
  for (cmsghdr* header = CMSG_FIRSTHDR(&message); header != nullptr;
       header = CMSG_NXTHDR(&message, header)) {
    if (header->cmsg_level == SOL_SOCKET && header->cmsg_type == SCM_RIGHTS) {
      const std::size_t n = (header->cmsg_len - CMSG_LEN(0)) / sizeof(int);
      for (std::size_t i = 0; i < n; ++i) {
        int fd = -1;
        std::memcpy(&fd, CMSG_DATA(header) + i * sizeof(int), sizeof(int));
        if (count < kHandedFds) {
          fds[count++] = UniqueFd(fd);
        } else {
          ::close(fd);
        }
      }
    }
  }
  if (got != static_cast<ssize_t>(sizeof(reply)) || reply.magic != kReplyMagic) {
    reply.magic = 0;
  }
  return reply;
}

void check_handed_segment(const HandedSegment& handed, bool writable, const std::string& from) {
  const int seals = fcntl(handed.segment.get(), F_GET_SEALS);
  if (seals < 0 || (static_cast<unsigned>(seals) & kSeals) != kSeals) {
    throw ShmError(ShmErrc::kInsecure, from + " handed out a segment that is not sealed against " +
                                           "resizing: refusing it (it could be truncated under " +
                                           "the mapping)");
  }
  struct stat st {};
  if (fstat(handed.segment.get(), &st) != 0 ||
      static_cast<std::size_t>(st.st_size) != kSegmentSize) {
    throw ShmError(ShmErrc::kLayoutMismatch,
                   from + " handed out a segment of " + std::to_string(st.st_size) +
                       " bytes where this program expects " + std::to_string(kSegmentSize) +
                       ": rebuild so that all hapticctrl programs come from one version");
  }
  const int access = fcntl(handed.segment.get(), F_GETFL) & O_ACCMODE;
  if ((writable ? O_RDWR : O_RDONLY) != access) {
    throw ShmError(ShmErrc::kInsecure, from + " handed out the segment with the wrong access");
  }
}

}  // namespace

HandedSegment request_segment(std::string_view instance, bool writable) {
  std::string looked_in;
  for (const std::string& directory : attacher_runtime_directories()) {
    const InstancePaths paths = InstancePaths::in(directory, instance);
    if (!socket_present(paths.socket)) {
      looked_in += (looked_in.empty() ? "" : " or ") + directory;
      continue;
    }
    const uid_t owner = trusted_directory_owner(directory);
    std::array<UniqueFd, kHandedFds> fds;
    std::size_t count = 0;
    ucred core{};
    Reply reply{};
    // A core whose every peer slot is held closes a new connection at once: asked again a
    // little later, it answers (J4). A core that stays silent for kAttacherTimeout does not.
    for (int attempt = 1;; ++attempt) {
      const auto asked = hapticctrl::MonotonicClock::now();
      const UniqueFd socket_fd = connect_to_core(paths, instance);
      core = peer_credentials(socket_fd.get());
      if (core.uid != owner && core.uid != 0) {
        throw ShmError(ShmErrc::kInsecure,
                       "the process serving " + paths.socket + " (pid " + std::to_string(core.pid) +
                           ") runs as uid " + std::to_string(core.uid) + ", not as the owner of " +
                           directory + " (uid " + std::to_string(owner) + "): refusing it");
      }
      const Request request{.writable = writable ? 1U : 0U};
      const bool sent = send(socket_fd.get(), &request, sizeof(request), MSG_NOSIGNAL) ==
                        static_cast<ssize_t>(sizeof(request));
      const int send_error = errno;
      // A core refuses an outsider right after accept, before reading: its refusal may be
      // waiting while our request found the connection closed.
      reply = receive_reply(socket_fd.get(), fds, count);
      const bool closed_at_once = hapticctrl::MonotonicClock::now() - asked < kBusyAnswer;
      if (reply.magic != kReplyMagic && closed_at_once && attempt < kBusyAttempts) {
        std::this_thread::sleep_for(kBusyPause);
        continue;
      }
      if (!sent && reply.magic != kReplyMagic) {
        throw_system_error("ask the controller of instance '" + std::string(instance) + "'",
                           send_error);
      }
      break;
    }
    const std::string from = "the core of instance '" + std::string(instance) + "'";
    if (reply.magic != kReplyMagic) {
      throw ShmError(ShmErrc::kSystem, from + " did not answer (" + paths.socket + ")");
    }
    if (reply.status == ReplyStatus::kRefused) {
      throw ShmError(ShmErrc::kPermissionDenied,
                     from +
                         " refused this process: permission denied (run as the controller's "
                         "user, root or a member of its group, see docs/security.md)");
    }
    if (reply.status != ReplyStatus::kServed || count != kHandedFds) {
      throw ShmError(ShmErrc::kSystem, from + " answered an unexpected reply");
    }
    HandedSegment handed{std::move(fds[0]), std::move(fds[1]), core.pid, core.uid};
    check_handed_segment(handed, writable, from);
    return handed;
  }
  throw ShmError(ShmErrc::kNoController, "no controller is running for instance '" +
                                             std::string(instance) + "' (no " +
                                             std::string(instance) + ".sock in " + looked_in +
                                             "); start hapticctrl-core first");
}

}  // namespace hapticctrl::shm
