// Implements hello_limiter.hpp: rate limit of handshake attempts (HELLO) per source address.
#include "hapticctrl/udp_bridge/hello_limiter.hpp"

#include <algorithm>

namespace hapticctrl::udp_bridge {

HelloLimiter::Source& HelloLimiter::source_of(std::uint32_t ipv4, TimePoint now) noexcept {
  Source* oldest = sources_.data();
  for (Source& s : sources_) {
    if (s.used && s.ipv4 == ipv4) {
      return s;
    }
    if (!s.used || (oldest->used && s.last < oldest->last)) {
      oldest = &s;
    }
  }
  *oldest = Source{ipv4, true, std::min(kFirstHellos, limits_.burst), now};
  return *oldest;
}

namespace {

/// Refills a token bucket for the time since `last` (none when time goes backwards).
void refill(double& tokens, TimePoint& last, TimePoint now, double rate, double burst) noexcept {
  const double elapsed = to_seconds(std::max(Duration::zero(), now - last));
  tokens = std::min(burst, tokens + elapsed * rate);
  last = std::max(last, now);
}

}  // namespace

bool HelloLimiter::admit(std::uint32_t ipv4, TimePoint now) noexcept {
  refill(total_tokens_, total_last_, now, limits_.total_per_second, limits_.total_burst);
  Source& s = source_of(ipv4, now);
  refill(s.tokens, s.last, now, limits_.per_second, limits_.burst);
  if (s.tokens < 1.0 || total_tokens_ < 1.0) {
    return false;
  }
  s.tokens -= 1.0;
  total_tokens_ -= 1.0;
  return true;
}

}  // namespace hapticctrl::udp_bridge
