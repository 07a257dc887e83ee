// Implements page_gateway.hpp: from a page's text message to the LCM HMI channels: validates it
// (page_request.hpp), limits each page's force messages to kMinForceIntervalNs apart, publishes
// what passes and counts every outcome.
#include "hapticctrl/web_bridge/page_gateway.hpp"

#include <algorithm>

namespace hapticctrl::web_bridge {
namespace {

void count(std::atomic<std::uint64_t>& counter) noexcept {
  counter.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

std::string PageGateway::handle(PageSession& page, std::string_view text, TimePoint now) {
  PageRequest request = parse_page_request(text, allow_remote_commands_);
  switch (request.kind) {
    case PageRequestKind::kCommand:
    case PageRequestKind::kForce:
      return forward(page, request, now);
    case PageRequestKind::kRefused:
      count(counters_.refused);
      break;
    case PageRequestKind::kOutOfRange:
      count(counters_.out_of_range);
      break;
    case PageRequestKind::kMalformed:
      count(counters_.malformed);
      break;
  }
  return reply_json(request);
}

std::string PageGateway::forward(PageSession& page, const PageRequest& request, TimePoint now) {
  const bool force = request.kind == PageRequestKind::kForce;
  if (force && page.sent_force && now - page.last_force < kMinForceInterval) {
    count(counters_.rate_limited);
    return {};  // the next one, a few ms later, carries the same intent
  }
  const std::string origin = "web " + page.peer;
  bool sent = false;
  if (force) {
    hapticctrl_lcm::hmi_force_t m{};
    m.utime = to_ns(now) / 1000;
    std::copy(request.wrench.begin(), request.wrench.end(), m.wrench);
    m.origin = origin;
    sent = publisher_.publish(m);
    page.last_force = now;
    page.sent_force = true;
  } else {
    hapticctrl_lcm::hmi_command_t m{};
    m.utime = to_ns(now) / 1000;
    m.command = request.command;
    m.origin = origin;
    sent = publisher_.publish(m);
  }
  if (!sent) {
    count(counters_.publish_failed);
    return reply_json(request.name, false, "the LCM bus refused the message");
  }
  count(force ? counters_.forces_forwarded : counters_.commands_forwarded);
  // Forces stream at 20 Hz: only commands get an acknowledgement.
  return force ? std::string() : reply_json(request);
}

}  // namespace hapticctrl::web_bridge
