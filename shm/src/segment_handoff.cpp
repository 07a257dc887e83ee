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

#include "hapticctrl/shm/error.hpp"
#include "hapticctrl/shm/layout.hpp"

namespace hapticctrl::shm {
namespace {

constexpr std::uint32_t kRequestMagic = 0x48435251;  // "HCRQ"
constexpr std::uint32_t kReplyMagic = 0x48435250;    // "HCRP"
constexpr std::size_t kHandedFds = 2;                // the segment, the core's pidfd
constexpr std::size_t kServerStack = std::size_t{64} * 1024;
constexpr std::size_t kMaxPeerGroups = 256;
constexpr timeval kPeerTimeout{0, 200'000};  // a silent peer cannot hold the server up
constexpr timeval kAttacherTimeout{2, 0};    // a core that does not answer is reported
constexpr unsigned kSeals = F_SEAL_SHRINK | F_SEAL_GROW | F_SEAL_SEAL;

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

sockaddr_un socket_address(const std::string& path) {
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

int pidfd_of_self() {
  return static_cast<int>(syscall(SYS_pidfd_open, getpid(), 0));
}

ucred peer_credentials(int socket) {
  ucred cred{};
  socklen_t length = sizeof(cred);
  if (getsockopt(socket, SOL_SOCKET, SO_PEERCRED, &cred, &length) != 0) {
    cred.pid = 0;
    cred.uid = static_cast<uid_t>(-1);
    cred.gid = static_cast<gid_t>(-1);
  }
  return cred;
}

void set_timeouts(int socket, const timeval& timeout) {
  setsockopt(socket, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  setsockopt(socket, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout));
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

namespace {

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
    const UniqueFd socket_fd = connect_to_core(paths, instance);
    const ucred core = peer_credentials(socket_fd.get());
    if (core.uid != owner && core.uid != 0) {
      throw ShmError(ShmErrc::kInsecure,
                     "the process serving " + paths.socket + " (pid " + std::to_string(core.pid) +
                         ") runs as uid " + std::to_string(core.uid) + ", not as the owner of " +
                         directory + " (uid " + std::to_string(owner) + "): refusing it");
    }
    const Request request{.writable = writable ? 1U : 0U};
    if (send(socket_fd.get(), &request, sizeof(request), MSG_NOSIGNAL) !=
        static_cast<ssize_t>(sizeof(request))) {
      throw_system_error("ask the controller of instance '" + std::string(instance) + "'", errno);
    }
    std::array<UniqueFd, kHandedFds> fds;
    std::size_t count = 0;
    const Reply reply = receive_reply(socket_fd.get(), fds, count);
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
