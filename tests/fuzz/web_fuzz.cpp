// libFuzzer target: what reaches the web bridge from outside. The first byte chooses: page
// messages (with remote commands on, then off), an event_t or a world_t from the LCM bus. A page
// request must come back accepted with a finite, bounded wrench or refused with a reason; an
// event the string check passes, and a world whose counts fit, must go into a frame that is
// valid JSON; nothing may throw.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <nlohmann/json.hpp>
#include <string_view>

#include "hapticctrl/web_bridge/page_request.hpp"
#include "hapticctrl/web_bridge/telemetry_view.hpp"

namespace {

namespace wb = hapticctrl::web_bridge;

void page_message(std::string_view text, bool allow_remote_commands) {
  const wb::PageRequest r = wb::parse_page_request(text, allow_remote_commands);
  if (r.kind == wb::PageRequestKind::kForce) {
    for (std::size_t i = 0; i < r.wrench.size(); ++i) {
      const double bound = i < 3 ? wb::kMaxPageForce : wb::kMaxPageTorque;
      if (!std::isfinite(r.wrench[i]) || std::fabs(r.wrench[i]) > bound) {
        std::abort();  // an unbounded force accepted
      }
    }
  }
  if (r.accepted() != r.reason.empty() || !nlohmann::json::accept(wb::reply_json(r))) {
    std::abort();
  }
  if (!allow_remote_commands && r.accepted() && r.name != "emergency_stop") {
    std::abort();  // only the emergency stop passes without remote commands
  }
}

void bus_event(const std::uint8_t* data, std::size_t size) {
  if (!wb::event_strings_sound(data, size)) {
    return;
  }
  hapticctrl_lcm::event_t e{};
  if (e.decode(data, 0, static_cast<int>(size)) < 0) {
    return;  // a wrong fingerprint: refused by LCM itself
  }
  wb::TelemetryView view;
  view.on_event(e, hapticctrl::TimePoint{});
  if (!nlohmann::json::accept(view.next_frame(hapticctrl::TimePoint{}))) {
    std::abort();
  }
}

void bus_world(const std::uint8_t* data, std::size_t size) {
  hapticctrl_lcm::world_t w{};
  if (w.decode(data, 0, static_cast<int>(size)) < 0 || !wb::world_counts_sound(w)) {
    return;  // counted as malformed by the bridge's LCM input
  }
  wb::TelemetryView view;
  view.on_world(w, hapticctrl::TimePoint{});
  if (!nlohmann::json::accept(view.next_frame(hapticctrl::TimePoint{}))) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) {
    return 0;
  }
  const std::string_view text(reinterpret_cast<const char*>(data) + 1, size - 1);
  switch (data[0] % 4) {
    case 0:
      page_message(text, true);
      break;
    case 1:
      page_message(text, false);
      break;
    case 2:
      bus_event(data + 1, size - 1);
      break;
    default:
      bus_world(data + 1, size - 1);
      break;
  }
  return 0;
}
