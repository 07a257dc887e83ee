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
  *oldest = Source{ipv4, true, limits_.burst, now_ns};
  return *oldest;
}

bool HelloLimiter::admit(std::uint32_t ipv4, std::int64_t now_ns) noexcept {
  Source& s = source_of(ipv4, now_ns);
  const double elapsed = static_cast<double>(std::max<std::int64_t>(0, now_ns - s.last_ns)) * 1e-9;
  s.tokens = std::min(limits_.burst, s.tokens + elapsed * limits_.per_second);
  s.last_ns = now_ns;
  if (s.tokens < 1.0) {
    return false;
  }
  s.tokens -= 1.0;
  return true;
}

}  // namespace hapticctrl::udp_bridge
