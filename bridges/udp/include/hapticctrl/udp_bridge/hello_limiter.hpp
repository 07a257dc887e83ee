#pragma once
/// @file hello_limiter.hpp
/// Rate limit of handshake attempts (HELLO) per source address: a token bucket for each of the
/// most recent sources, so that a flood from one address neither costs the bridge a reply per
/// datagram nor starves another client's handshake.
#include <array>
#include <cstdint>

namespace hapticctrl::udp_bridge {

struct HelloLimits {
  double per_second = 20.0;  ///< sustained HELLOs per source (the client retries every 40 ms)
  double burst = 20.0;       ///< HELLOs a source may send at once
};

class HelloLimiter {
 public:
  /// Sources tracked at once; the least recently seen one makes room for a new one.
  static constexpr std::size_t kSources = 16;

  explicit HelloLimiter(HelloLimits limits = {}) noexcept : limits_(limits) {}

  /// Whether a HELLO from `ipv4` at `now_ns` may be answered (spends a token if so).
  /// Real-time contract: noexcept, allocation-free, no syscall.
  bool admit(std::uint32_t ipv4, std::int64_t now_ns) noexcept;

 private:
  struct Source {
    std::uint32_t ipv4 = 0;
    bool used = false;
    double tokens = 0.0;
    std::int64_t last_ns = 0;
  };
  Source& source_of(std::uint32_t ipv4, std::int64_t now_ns) noexcept;

  HelloLimits limits_;
  std::array<Source, kSources> sources_{};
};

}  // namespace hapticctrl::udp_bridge
