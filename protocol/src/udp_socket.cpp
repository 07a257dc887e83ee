// Implements udp_socket.hpp: the datagram transport seam shared by the UDP bridge and the client
// library, and its UDP/IPv4 implementation.
#include "hapticctrl/protocol/udp_socket.hpp"

#include <arpa/inet.h>
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <stdexcept>
#include <system_error>
#include <utility>

namespace hapticctrl::protocol {
namespace {

const sockaddr* as_sockaddr(const sockaddr_in& a) noexcept {
  return reinterpret_cast<const sockaddr*>(&a);  // the sockets API's own convention
}

}  // namespace

Endpoint Endpoint::resolve(std::string_view host, std::uint16_t port) {
  Endpoint e;
  e.address.sin_family = AF_INET;
  e.address.sin_port = htons(port);
  const std::string name(host);
  if (::inet_pton(AF_INET, name.c_str(), &e.address.sin_addr) == 1) {
    return e;
  }
  addrinfo hints{};
  hints.ai_family = AF_INET;
  hints.ai_socktype = SOCK_DGRAM;
  addrinfo* found = nullptr;
  const int rc = ::getaddrinfo(name.c_str(), nullptr, &hints, &found);
  if (rc != 0 || found == nullptr) {
    throw std::invalid_argument("cannot resolve host '" + name +
                                "' to an IPv4 address: " + ::gai_strerror(rc));
  }
  e.address.sin_addr = reinterpret_cast<const sockaddr_in*>(found->ai_addr)->sin_addr;
  ::freeaddrinfo(found);
  return e;
}

std::string Endpoint::to_string() const {
  char text[INET_ADDRSTRLEN] = {};
  ::inet_ntop(AF_INET, &address.sin_addr, text, sizeof text);
  return std::string(text) + ":" + std::to_string(port());
}

std::uint16_t Endpoint::port() const noexcept {
  return ntohs(address.sin_port);
}

bool Endpoint::is_loopback() const noexcept {
  return (ntohl(address.sin_addr.s_addr) >> 24U) == 127U;
}

bool operator==(const Endpoint& a, const Endpoint& b) noexcept {
  return a.address.sin_addr.s_addr == b.address.sin_addr.s_addr &&
         a.address.sin_port == b.address.sin_port;
}

UdpSocket::UdpSocket(const Endpoint& local) {
  fd_ = ::socket(AF_INET, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  if (fd_ < 0) {
    throw std::system_error(errno, std::generic_category(), "cannot create a UDP socket");
  }
  if (::bind(fd_, as_sockaddr(local.address), sizeof local.address) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    throw std::system_error(err, std::generic_category(), "cannot bind UDP " + local.to_string());
  }
}

UdpSocket::UdpSocket(UdpSocket&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}

UdpSocket& UdpSocket::operator=(UdpSocket&& other) noexcept {
  if (this != &other) {
    if (fd_ >= 0) {
      ::close(fd_);
    }
    fd_ = std::exchange(other.fd_, -1);
  }
  return *this;
}

UdpSocket::~UdpSocket() {
  if (fd_ >= 0) {
    ::close(fd_);
  }
}

bool UdpSocket::send_to(std::span<const std::uint8_t> bytes, const Endpoint& to) noexcept {
  const ssize_t n = ::sendto(fd_, bytes.data(), bytes.size(), MSG_DONTWAIT, as_sockaddr(to.address),
                             sizeof to.address);
  return n == static_cast<ssize_t>(bytes.size());
}

Received UdpSocket::receive(std::span<std::uint8_t> buffer, Endpoint& from,
                            std::chrono::nanoseconds timeout) noexcept {
  pollfd p{fd_, POLLIN, 0};
  const timespec ts{static_cast<time_t>(timeout.count() / 1'000'000'000),
                    static_cast<long>(timeout.count() % 1'000'000'000)};
  const int ready = ::ppoll(&p, 1, &ts, nullptr);
  if (ready == 0 || (ready < 0 && errno == EINTR)) {
    return {Received::Status::kTimeout, 0};
  }
  if (ready < 0) {
    return {Received::Status::kError, 0};
  }
  socklen_t length = sizeof from.address;
  // MSG_TRUNC: the return value is the datagram's real size, so oversize is detectable.
  const ssize_t n = ::recvfrom(fd_, buffer.data(), buffer.size(), MSG_TRUNC | MSG_DONTWAIT,
                               reinterpret_cast<sockaddr*>(&from.address), &length);
  if (n < 0) {
    return {errno == EAGAIN ? Received::Status::kTimeout : Received::Status::kError, 0};
  }
  if (static_cast<std::size_t>(n) > buffer.size()) {
    return {Received::Status::kOversized, buffer.size()};
  }
  return {Received::Status::kDatagram, static_cast<std::size_t>(n)};
}

Endpoint UdpSocket::local_endpoint() const {
  Endpoint e;
  socklen_t length = sizeof e.address;
  if (::getsockname(fd_, reinterpret_cast<sockaddr*>(&e.address), &length) != 0) {
    throw std::system_error(errno, std::generic_category(), "getsockname");
  }
  return e;
}

}  // namespace hapticctrl::protocol
