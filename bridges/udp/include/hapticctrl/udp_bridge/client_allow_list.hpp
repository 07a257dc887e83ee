#pragma once
/// @file client_allow_list.hpp
/// Which client addresses the UDP bridge serves (--allow-client): IPv4 networks, each an
/// address with an optional prefix length. An empty list allows every address (the bridge
/// binds loopback unless told otherwise).
#include <cstdint>
#include <string>
#include <vector>

namespace hapticctrl::udp_bridge {

/// One IPv4 network, host byte order.
struct Ipv4Network {
  std::uint32_t address = 0;
  std::uint32_t mask = 0xFFFFFFFFU;

  /// Parses "a.b.c.d" or "a.b.c.d/prefix" (0..32). Throws std::invalid_argument naming it.
  static Ipv4Network parse(const std::string& text);
  [[nodiscard]] bool contains(std::uint32_t ipv4) const noexcept {
    return (ipv4 & mask) == (address & mask);
  }
};

class ClientAllowList {
 public:
  ClientAllowList() = default;
  explicit ClientAllowList(std::vector<Ipv4Network> networks) : networks_(std::move(networks)) {}

  /// Whether datagrams from `ipv4` (host byte order) are served. Real-time contract: noexcept,
  /// allocation-free (a scan of the configured networks).
  [[nodiscard]] bool allows(std::uint32_t ipv4) const noexcept {
    if (networks_.empty()) {
      return true;
    }
    for (const Ipv4Network& n : networks_) {
      if (n.contains(ipv4)) {
        return true;
      }
    }
    return false;
  }
  [[nodiscard]] bool empty() const noexcept { return networks_.empty(); }

 private:
  std::vector<Ipv4Network> networks_;
};

}  // namespace hapticctrl::udp_bridge
