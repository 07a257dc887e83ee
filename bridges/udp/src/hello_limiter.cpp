// Implements hello_limiter.hpp: rate limit of handshake attempts (HELLO) per source address.
#include "hapticctrl/udp_bridge/hello_limiter.hpp"

#include <algorithm>

namespace hapticctrl::udp_bridge {

HelloLimiter::Source& HelloLimiter::source_of(std::uint32_t ipv4, std::int64_t now_ns) noexcept {
  Source* oldest = sources_.data();
  for (Source& s : sources_) {
    if (s.used && s.ipv4 == ipv4) {
      return s;
    }
    if (!s.used || (oldest->used && s.last_ns < oldest->last_ns)) {
      oldest = &s;
    }
  }
  *oldest = Source{ipv4, true, std::min(kFirstHellos, limits_.burst), now_ns};
  return *oldest;
}

namespace {

/// Refills a token bucket for the time since `last_ns` (none when time goes backwards).
void refill(double& tokens, std::int64_t& last_ns, std::int64_t now_ns, double rate,
            double burst) noexcept {
  const double elapsed = static_cast<double>(std::max<std::int64_t>(0, now_ns - last_ns)) * 1e-9;
  tokens = std::min(burst, tokens + elapsed * rate);
  last_ns = std::max(last_ns, now_ns);
}

}  // namespace

bool HelloLimiter::admit(std::uint32_t ipv4, std::int64_t now_ns) noexcept {
  refill(total_tokens_, total_last_ns_, now_ns, limits_.total_per_second, limits_.total_burst);
  Source& s = source_of(ipv4, now_ns);
  refill(s.tokens, s.last_ns, now_ns, limits_.per_second, limits_.burst);
  if (s.tokens < 1.0 || total_tokens_ < 1.0) {
    return false;
  }
  s.tokens -= 1.0;
  total_tokens_ -= 1.0;
  return true;
}

}  // namespace hapticctrl::udp_bridge
