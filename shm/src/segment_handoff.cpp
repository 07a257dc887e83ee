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

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <string>
#include <utility>

#include "handoff_wire.hpp"
#include "hapticctrl/base/time.hpp"
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
  std::atomic<std::uint64_t> busy{0};  ///< connections closed because every slot was held
  std::atomic<bool> serving{false};    ///< the thread has started and runs our code
  pthread_t thread{};                  ///< running once the constructor has returned

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

  /// A connected peer whose request has not fully arrived (credentials already checked).
  struct Peer {
    int fd = -1;
    hapticctrl::MonotonicClock::time_point deadline;
    std::size_t got = 0;
    Request request{};
  };
  /// Peers served at once. Served one at a time, with a backlog of 16, 16 silent connections
  /// held 200 ms each made `hapticctrl-hmi status` fail 2 times of 3 (J4 review of f3c5aec).
  static constexpr std::size_t kMaxPeers = 256;
  std::array<Peer, kMaxPeers> peers{};
  std::array<pollfd, kMaxPeers + 2> watched{};
  std::array<std::size_t, kMaxPeers + 2> watched_peer{};  ///< watched index -> peers index

  void refuse(int socket, ReplyStatus status) {
    refused.fetch_add(1, std::memory_order_relaxed);
    Reply reply;
    reply.status = status;
    send_reply(socket, reply, nullptr, 0);  // non-blocking: best effort
    ::close(socket);
  }

  /// Right after accept, before reading anything: a peer outside the core's user and group
  /// gets its refusal at once and is never read from.
  void admit(int socket) {
    if (!allowed(socket, peer_credentials(socket))) {
      refuse(socket, ReplyStatus::kRefused);
      return;
    }
    for (Peer& peer : peers) {
      if (peer.fd < 0) {
        peer = Peer{socket, hapticctrl::MonotonicClock::now() + kPeerDeadline, 0, {}};
        return;
      }
    }
    ::close(socket);  // all slots held: the attacher tries again within its budget
    busy.fetch_add(1, std::memory_order_relaxed);
  }

  void finish(Peer& peer) {
    ::close(peer.fd);
    peer.fd = -1;
  }

  void read_request(Peer& peer) {
    auto* bytes = reinterpret_cast<unsigned char*>(&peer.request);  // NOLINT(*-reinterpret-cast)
    const ssize_t n = recv(peer.fd, bytes + peer.got, sizeof(Request) - peer.got, MSG_DONTWAIT);
    if (n < 0 && (errno == EAGAIN || errno == EINTR)) {
      return;
    }
    if (n <= 0) {
      refused.fetch_add(1, std::memory_order_relaxed);  // closed or failed before a request
      finish(peer);
      return;
    }
    peer.got += static_cast<std::size_t>(n);
    if (peer.got < sizeof(Request)) {
      return;
    }
    if (peer.request.magic != kRequestMagic || peer.request.writable > 1) {
      refuse(peer.fd, ReplyStatus::kBadRequest);
      peer.fd = -1;
      return;
    }
    const std::array<int, kHandedFds> fds{
        peer.request.writable != 0 ? writable.get() : read_only.get(), core.get()};
    if (send_reply(peer.fd, Reply{}, fds.data(), fds.size())) {
      served.fetch_add(1, std::memory_order_relaxed);
    }
    finish(peer);
  }

  /// Poll timeout (ms) until the nearest peer's deadline; -1 when no peer waits.
  int next_timeout() const {
    const auto now = hapticctrl::MonotonicClock::now();
    auto nearest = hapticctrl::MonotonicClock::time_point::max();
    for (const Peer& peer : peers) {
      if (peer.fd >= 0) {
        nearest = std::min(nearest, peer.deadline);
      }
    }
    if (nearest == hapticctrl::MonotonicClock::time_point::max()) {
      return -1;
    }
    const auto left = std::chrono::ceil<std::chrono::milliseconds>(nearest - now).count();
    return static_cast<int>(std::max<std::int64_t>(0, left));
  }

  void drop_late_peers() {
    const auto now = hapticctrl::MonotonicClock::now();
    for (Peer& peer : peers) {
      if (peer.fd >= 0 && now >= peer.deadline) {
        refused.fetch_add(1, std::memory_order_relaxed);  // silent too long
        finish(peer);
      }
    }
  }

  void run() {
    serving.store(true, std::memory_order_release);
    serving.notify_one();
    for (;;) {
      std::size_t count = 0;
      watched[count++] = pollfd{listener.get(), POLLIN, 0};
      watched[count++] = pollfd{wake.get(), POLLIN, 0};
      for (std::size_t i = 0; i < peers.size(); ++i) {
        if (peers[i].fd >= 0) {
          watched_peer[count] = i;
          watched[count++] = pollfd{peers[i].fd, POLLIN, 0};
        }
      }
      if (poll(watched.data(), count, next_timeout()) < 0 && errno != EINTR) {
        break;
      }
      if (watched[1].revents != 0) {
        break;
      }
      for (std::size_t w = 2; w < count; ++w) {
        if (watched[w].revents != 0) {
          read_request(peers[watched_peer[w]]);
        }
      }
      if (watched[0].revents != 0) {
        for (int socket = 0; (socket = accept4(listener.get(), nullptr, nullptr,
                                               SOCK_CLOEXEC | SOCK_NONBLOCK)) >= 0;) {
          admit(socket);
        }
      }
      drop_late_peers();
    }
    for (Peer& peer : peers) {
      if (peer.fd >= 0) {
        finish(peer);
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
      fcntl(s.listener.get(), F_SETFL, O_NONBLOCK) != 0 ||
      listen(s.listener.get(), kBacklog) != 0) {
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
