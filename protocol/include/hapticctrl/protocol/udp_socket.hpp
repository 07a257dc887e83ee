#pragma once
/// @file udp_socket.hpp
/// The datagram transport seam shared by the UDP bridge and the client library, and its UDP/IPv4
/// implementation.
///
/// Setup (construction, bind, address parsing) throws std::system_error/std::invalid_argument
/// with a clear message. Per-datagram calls never throw and never allocate: one syscall each.
#include <netinet/in.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>

namespace hapticctrl::protocol {

/// An IPv4 address and port.
struct Endpoint {
  sockaddr_in address{};

  /// Parses a dotted IPv4 address or a host name (resolved once, IPv4 only) and a port.
  /// Throws std::invalid_argument naming the input when it cannot be resolved.
  static Endpoint resolve(std::string_view host, std::uint16_t port);
  /// "a.b.c.d:port"
  [[nodiscard]] std::string to_string() const;
  [[nodiscard]] std::uint16_t port() const noexcept;
  [[nodiscard]] bool is_loopback() const noexcept;
  friend bool operator==(const Endpoint& a, const Endpoint& b) noexcept;
};

/// Result of one receive.
struct Received {
  enum class Status : std::uint8_t { kDatagram, kTimeout, kOversized, kError };
  Status status = Status::kTimeout;
  std::size_t size = 0;  ///< bytes in the buffer (kDatagram)
};

/// One datagram in, one datagram out.
class DatagramTransport {
 public:
  virtual ~DatagramTransport() = default;
  /// Sends one datagram. Real-time contract: one syscall, no allocation; false on failure.
  virtual bool send_to(std::span<const std::uint8_t> bytes, const Endpoint& to) noexcept = 0;
  /// Waits up to `timeout` (0: poll) for one datagram. Datagrams larger than `buffer` are
  /// consumed and reported kOversized. Real-time contract: blocking wait, no allocation.
  virtual Received receive(std::span<std::uint8_t> buffer, Endpoint& from,
                           std::chrono::nanoseconds timeout) noexcept = 0;
};

/// A bound UDP/IPv4 socket. Move-only.
class UdpSocket final : public DatagramTransport {
 public:
  /// Binds `local` (port 0: any free port). Throws std::system_error with the address.
  explicit UdpSocket(const Endpoint& local);
  UdpSocket(UdpSocket&& other) noexcept;
  UdpSocket& operator=(UdpSocket&& other) noexcept;
  UdpSocket(const UdpSocket&) = delete;
  UdpSocket& operator=(const UdpSocket&) = delete;
  ~UdpSocket() override;

  bool send_to(std::span<const std::uint8_t> bytes, const Endpoint& to) noexcept override;
  Received receive(std::span<std::uint8_t> buffer, Endpoint& from,
                   std::chrono::nanoseconds timeout) noexcept override;

  /// The bound address (with the port the kernel chose for port 0).
  [[nodiscard]] Endpoint local_endpoint() const;

 private:
  int fd_ = -1;
};

}  // namespace hapticctrl::protocol
