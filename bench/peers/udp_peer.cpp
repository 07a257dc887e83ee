// Plain UDP on loopback: the writer sends each message as one datagram to the reader's socket;
// the reader drains what arrived and keeps the newest (a socket queues, it has no latest value).
#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <string>

#include "peers/peer_transport.hpp"

namespace hapticctrl::bench {
namespace {

sockaddr_in loopback(std::uint16_t port) {
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_port = htons(port);
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  return a;
}

[[noreturn]] void fail(const char* what) {
  throw std::runtime_error(std::string("udp: ") + what + ": " + std::strerror(errno));
}

class UdpWriter final : public PeerWriter {
 public:
  explicit UdpWriter(std::uint16_t port)
      : to_(loopback(port)), fd_(socket(AF_INET, SOCK_DGRAM, 0)) {
    if (fd_ < 0) {
      fail("socket");
    }
  }
  UdpWriter(const UdpWriter&) = delete;
  UdpWriter& operator=(const UdpWriter&) = delete;
  ~UdpWriter() override { close(fd_); }
  bool publish(const Message& message) override {
    // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): the sockets API
    return sendto(fd_, &message, sizeof message, 0, reinterpret_cast<const sockaddr*>(&to_),
                  sizeof to_) == static_cast<ssize_t>(sizeof message);
  }

 private:
  sockaddr_in to_;
  int fd_;
};

class UdpReader final : public PeerReader {
 public:
  explicit UdpReader(int fd) : fd_(fd) {}
  bool wait(std::chrono::milliseconds timeout) override {
    pollfd p{fd_, POLLIN, 0};
    return poll(&p, 1, static_cast<int>(timeout.count())) > 0;
  }
  bool read(Message& out) override {
    bool got = false;
    while (recv(fd_, &out, sizeof out, MSG_DONTWAIT) == static_cast<ssize_t>(sizeof out)) {
      got = true;  // keep draining: the newest is the one that counts
    }
    return got;
  }

 private:
  int fd_;
};

class UdpTransport final : public PeerTransport {
 public:
  UdpTransport() = default;
  UdpTransport(const UdpTransport&) = delete;
  UdpTransport& operator=(const UdpTransport&) = delete;
  ~UdpTransport() override { teardown(); }

  [[nodiscard]] std::string name() const override { return "udp"; }
  [[nodiscard]] std::vector<ReadMode> modes() const override { return {ReadMode::kWake}; }
  void setup(ReadMode /*mode*/) override {
    fd_ = socket(AF_INET, SOCK_DGRAM, 0);
    if (fd_ < 0) {
      fail("socket");
    }
    sockaddr_in any = loopback(0);
    socklen_t length = sizeof any;
    // NOLINTBEGIN(cppcoreguidelines-pro-type-reinterpret-cast): the sockets API
    if (bind(fd_, reinterpret_cast<const sockaddr*>(&any), sizeof any) != 0 ||
        getsockname(fd_, reinterpret_cast<sockaddr*>(&any), &length) != 0) {
      fail("bind");
    }
    // NOLINTEND(cppcoreguidelines-pro-type-reinterpret-cast)
    port_ = ntohs(any.sin_port);
  }
  std::unique_ptr<PeerWriter> make_writer(ReadMode /*mode*/) override {
    return std::make_unique<UdpWriter>(port_);
  }
  std::unique_ptr<PeerReader> make_reader(ReadMode /*mode*/) override {
    return std::make_unique<UdpReader>(fd_);
  }
  void teardown() override {
    if (fd_ >= 0) {
      close(fd_);
      fd_ = -1;
    }
  }

 private:
  int fd_ = -1;
  std::uint16_t port_ = 0;
};

}  // namespace

std::unique_ptr<PeerTransport> make_udp_transport() {
  return std::make_unique<UdpTransport>();
}

}  // namespace hapticctrl::bench
