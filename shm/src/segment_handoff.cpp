// Implements the core's side of segment_handoff.hpp: the sealed segment and the server that hands
// it out to the processes allowed to map it (the attacher's side is segment_request.cpp).
#include "hapticctrl/shm/segment_handoff.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <sys/eventfd.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/un.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>
#include <utility>

#include "handoff_wire.hpp"
#include "hapticctrl/shm/error.hpp"
#include "hapticctrl/shm/layout.hpp"

namespace hapticctrl::shm {
namespace {

using namespace handoff;  // NOLINT(google-build-using-namespace): this file speaks it

int pidfd_of_self() {
  return static_cast<int>(syscall(SYS_pidfd_open, getpid(), 0));
}

/// Sends `reply` with `fds` attached (none when `count` is 0).
bool send_reply(int socket, const Reply& reply, const int* fds, std::size_t count) {
  iovec data{const_cast<Reply*>(&reply),
             sizeof(reply)};  // NOLINT(cppcoreguidelines-pro-type-const-cast)
  alignas(cmsghdr) std::array<char, CMSG_SPACE(sizeof(int) * kHandedFds)> control{};
  msghdr message{};
  message.msg_iov = &data;
  message.msg_iovlen = 1;
  if (count > 0) {
    message.msg_control = control.data();
    message.msg_controllen = CMSG_SPACE(sizeof(int) * count);
    cmsghdr* header = CMSG_FIRSTHDR(&message);
    header->cmsg_level = SOL_SOCKET;
    header->cmsg_type = SCM_RIGHTS;
    header->cmsg_len = CMSG_LEN(sizeof(int) * count);
    std::memcpy(CMSG_DATA(header), fds, sizeof(int) * count);
  }
  return sendmsg(socket, &message, MSG_NOSIGNAL) == static_cast<ssize_t>(sizeof(reply));
}

}  // namespace

int create_sealed_segment(const std::string& name, std::size_t size) {
  const int fd = memfd_create(name.c_str(), MFD_CLOEXEC | MFD_ALLOW_SEALING);
  if (fd < 0) {
    throw_system_error("create the segment", errno);
  }
  // Mode 0600: nobody opens it by name, it is handed over; a reader of another user cannot
  // reopen its read-only descriptor writable through /proc.
  if (fchmod(fd, 0600) != 0 || ftruncate(fd, static_cast<off_t>(size)) != 0 ||
      fcntl(fd, F_ADD_SEALS, kSeals) != 0) {
    const int error = errno;
    ::close(fd);
    throw_system_error("size and seal the segment", error);
  }
  return fd;
}

UniqueFd& UniqueFd::operator=(UniqueFd&& other) noexcept {
  if (this != &other) {
    reset();
    fd_ = other.release();
  }
  return *this;
}

int UniqueFd::release() noexcept {
  return std::exchange(fd_, -1);
}

void UniqueFd::reset() noexcept {
  if (fd_ >= 0) {
    ::close(fd_);
    fd_ = -1;
  }
}

struct SegmentServer::State {
  std::string socket_path;
  UniqueFd listener;
  UniqueFd wake;       ///< eventfd: written once to stop the thread
  UniqueFd writable;   ///< the memfd as the core holds it (read-write)
  UniqueFd read_only;  ///< the same file opened read-only, for readers
  UniqueFd core;       ///< a pidfd of this process
  gid_t group = 0;
  uid_t owner = 0;
  std::atomic<std::uint64_t> served{0};
  std::atomic<std::uint64_t> refused{0};
  std::atomic<bool> serving{false};  ///< the thread has started and runs our code
  pthread_t thread{};                ///< running once the constructor has returned

  /// The core's user, root, and members of its group (primary or supplementary).
  [[nodiscard]] bool allowed(int socket, const ucred& cred) const {
    if (cred.uid == 0 || cred.uid == owner || cred.gid == group) {
      return true;
    }
    std::array<gid_t, kMaxPeerGroups> groups{};
    socklen_t length = sizeof(groups);
    if (getsockopt(socket, SOL_SOCKET, SO_PEERGROUPS, groups.data(), &length) != 0) {
      return false;
    }
    const std::size_t count = length / sizeof(gid_t);
    for (std::size_t i = 0; i < count; ++i) {
      if (groups[i] == group) {
        return true;
      }
    }
    return false;
  }

  void serve(int socket) {
    set_timeouts(socket, kPeerTimeout);
    Request request{};
    const ssize_t got = recv(socket, &request, sizeof(request), MSG_WAITALL);
    Reply reply;
    if (got != static_cast<ssize_t>(sizeof(request)) || request.magic != kRequestMagic ||
        request.writable > 1) {
      reply.status = ReplyStatus::kBadRequest;
    } else if (!allowed(socket, peer_credentials(socket))) {
      reply.status = ReplyStatus::kRefused;
    }
    if (reply.status != ReplyStatus::kServed) {
      refused.fetch_add(1, std::memory_order_relaxed);
      send_reply(socket, reply, nullptr, 0);
      return;
    }
    const std::array<int, kHandedFds> fds{request.writable != 0 ? writable.get() : read_only.get(),
                                          core.get()};
    if (send_reply(socket, reply, fds.data(), fds.size())) {
      served.fetch_add(1, std::memory_order_relaxed);
    }
  }

  void run() {
    serving.store(true, std::memory_order_release);
    serving.notify_one();
    std::array<pollfd, 2> watched{pollfd{listener.get(), POLLIN, 0}, pollfd{wake.get(), POLLIN, 0}};
    for (;;) {
      if (poll(watched.data(), watched.size(), -1) < 0) {
        if (errno == EINTR) {
          continue;
        }
        return;
      }
      if (watched[1].revents != 0) {
        return;
      }
      const int socket = accept4(listener.get(), nullptr, nullptr, SOCK_CLOEXEC);
      if (socket >= 0) {
        serve(socket);
        ::close(socket);
      }
    }
  }

  static void* thread_main(void* self) {
    static_cast<State*>(self)->run();
    return nullptr;
  }
};

SegmentServer::SegmentServer(const InstancePaths& paths, int segment_fd, gid_t group)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.socket_path = paths.socket;
  s.owner = geteuid();
  s.group = group == static_cast<gid_t>(-1) ? getegid() : group;
  s.writable = UniqueFd(fcntl(segment_fd, F_DUPFD_CLOEXEC, 0));
  // A second open file description, read-only: a reader's mapping can then never be writable.
  s.read_only =
      UniqueFd(open(("/proc/self/fd/" + std::to_string(segment_fd)).c_str(), O_RDONLY | O_CLOEXEC));
  s.core = UniqueFd(pidfd_of_self());
  s.wake = UniqueFd(eventfd(0, EFD_CLOEXEC));
  if (!s.writable.valid() || !s.read_only.valid() || !s.core.valid() || !s.wake.valid()) {
    throw_system_error("prepare the segment's hand-off", errno);
  }

  const sockaddr_un address = socket_address(paths.socket);
  s.listener = UniqueFd(socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0));
  if (!s.listener.valid()) {
    throw_system_error("create the socket " + paths.socket, errno);
  }
  unlink(paths.socket.c_str());  // left by a core that died: we hold the instance lock
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): the sockets API
  if (bind(s.listener.get(), reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
    throw_system_error("bind " + paths.socket, errno);
  }
  if (chmod(paths.socket.c_str(), 0660) != 0 ||
      (group != static_cast<gid_t>(-1) &&
       chown(paths.socket.c_str(), static_cast<uid_t>(-1), group) != 0) ||
      listen(s.listener.get(), 16) != 0) {
    const int error = errno;
    unlink(paths.socket.c_str());
    throw_system_error("serve " + paths.socket, error);
  }

  pthread_attr_t attributes;
  pthread_attr_init(&attributes);
  pthread_attr_setstacksize(&attributes, kServerStack);
  sigset_t all;
  sigset_t previous;
  sigfillset(&all);
  pthread_sigmask(SIG_BLOCK, &all, &previous);  // the thread starts with every signal blocked
  const int rc = pthread_create(&s.thread, &attributes, &State::thread_main, &s);
  pthread_sigmask(SIG_SETMASK, &previous, nullptr);
  pthread_attr_destroy(&attributes);
  if (rc != 0) {
    unlink(paths.socket.c_str());
    throw_system_error("start the segment's server thread", rc);
  }
  // Returns once the thread runs our code: a process that forks right after (a test, a
  // supervisor) never copies a thread caught inside its own start-up, which can hold a lock of
  // the C library or a sanitizer's runtime that the child would then wait on forever (seen
  // under ASan, 2026-12-02: a child forked right after create() hung in 12 runs of 60).
  s.serving.wait(false, std::memory_order_acquire);
}

SegmentServer::~SegmentServer() {
  State& s = *state_;
  unlink(s.socket_path.c_str());  // first: no new attacher finds us
  const std::uint64_t one = 1;
  if (write(s.wake.get(), &one, sizeof(one)) == sizeof(one)) {
    pthread_join(s.thread, nullptr);
  } else {
    pthread_detach(s.thread);  // cannot happen with an eventfd; never block the stop sequence
  }
}

std::uint64_t SegmentServer::served() const noexcept {
  return state_->served.load(std::memory_order_relaxed);
}

std::uint64_t SegmentServer::refused() const noexcept {
  return state_->refused.load(std::memory_order_relaxed);
}

}  // namespace hapticctrl::shm
