#pragma once
/// @file hello_limiter.hpp
/// Rate limit of handshake attempts (HELLO) per source address: a token bucket for each of the
/// most recent sources, so that a flood from one address neither costs the bridge a reply per
/// datagram nor starves another client's handshake; and a bucket for all sources together, so
/// that many addresses cannot add their budgets up (40 loopback addresses were answered 19 088
/// HELLOs of 20 000 before, 2026-12-02). A source seen for the first time, or again after it
/// was evicted, starts with kFirstHellos, never a full burst.
#include <array>
#include <cstdint>

#include "hapticctrl/base/time.hpp"

namespace hapticctrl::udp_bridge {

struct HelloLimits {
  double per_second = 20.0;  ///< sustained HELLOs per source (the client retries every 40 ms)
  double burst = 20.0;       ///< HELLOs a source may save up and send at once
  double total_per_second = 100.0;  ///< sustained HELLOs from all sources together
  double total_burst = 50.0;
};

class HelloLimiter {
 public:
  /// Sources tracked at once; the least recently seen one makes room for a new one.
  static constexpr std::size_t kSources = 16;
  /// HELLOs a new (or evicted and returning) source may send at once: a retry after a lost
  /// WELCOME, or a second client process on the same host.
  static constexpr double kFirstHellos = 2.0;

  explicit HelloLimiter(HelloLimits limits = {}) noexcept
      : limits_(limits), total_tokens_(limits.total_burst) {}

  /// Whether a HELLO from `ipv4` at `now` may be answered (spends a token if so).
  /// Real-time contract: noexcept, allocation-free, no syscall.
  bool admit(std::uint32_t ipv4, TimePoint now) noexcept;

 private:
  struct Source {
    std::uint32_t ipv4 = 0;
    bool used = false;
    double tokens = 0.0;
    TimePoint last;
  };
  Source& source_of(std::uint32_t ipv4, TimePoint now) noexcept;

  HelloLimits limits_;
  std::array<Source, kSources> sources_{};
  double total_tokens_;  ///< starts with the full total burst
  TimePoint total_last_;
};

}  // namespace hapticctrl::udp_bridge
