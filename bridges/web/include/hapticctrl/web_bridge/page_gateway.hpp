#pragma once
/// @file page_gateway.hpp
/// From a page's text message to the LCM HMI channels: validates it (page_request.hpp), limits
/// each page's force messages to kMinForceIntervalNs apart, publishes what passes and counts
/// every outcome. The LCM bridge validates and rate-limits again before the core sees anything.
///
/// Real-time contract: soft-RT (the web server's connection threads); allocates, never throws
/// out of handle().
#include <atomic>
#include <cstdint>
#include <string>
#include <string_view>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/web_bridge/page_request.hpp"
#include "hapticctrl_lcm/hmi_command_t.hpp"
#include "hapticctrl_lcm/hmi_force_t.hpp"

namespace hapticctrl::web_bridge {

/// A page sends its sliders' wrench at 20 Hz while they are off zero; the LCM bridge lets the
/// force decay after 200 ms of silence. Faster than 100 Hz is a broken or hostile page.
inline constexpr Duration kMinForceInterval = std::chrono::milliseconds(10);

/// Where accepted requests go (LCM in the web bridge, a recorder in tests).
class HmiPublisher {
 public:
  virtual ~HmiPublisher() = default;
  /// Returns false when the message could not be sent.
  virtual bool publish(const hapticctrl_lcm::hmi_command_t& m) = 0;
  virtual bool publish(const hapticctrl_lcm::hmi_force_t& m) = 0;
};

/// One page's connection state.
struct PageSession {
  std::string peer;  ///< "address:port", for the message's origin field and the log
  TimePoint last_force;
  bool sent_force = false;
};

struct GatewayCounters {
  std::atomic<std::uint64_t> commands_forwarded{0};
  std::atomic<std::uint64_t> forces_forwarded{0};
  std::atomic<std::uint64_t> refused{0};       ///< remote commands disabled
  std::atomic<std::uint64_t> malformed{0};     ///< not a valid page message
  std::atomic<std::uint64_t> out_of_range{0};  ///< wrench non-finite or beyond bounds
  std::atomic<std::uint64_t> rate_limited{0};  ///< forces closer than kMinForceIntervalNs
  std::atomic<std::uint64_t> publish_failed{0};
};

class PageGateway {
 public:
  PageGateway(HmiPublisher& publisher, bool allow_remote_commands) noexcept
      : publisher_(publisher), allow_remote_commands_(allow_remote_commands) {}

  /// Handles one text message of `page` at `now`; returns the reply for the page
  /// (empty for forwarded forces, which the page sends 20 times a second).
  [[nodiscard]] std::string handle(PageSession& page, std::string_view text, TimePoint now);
  [[nodiscard]] bool allow_remote_commands() const noexcept { return allow_remote_commands_; }
  [[nodiscard]] const GatewayCounters& counters() const noexcept { return counters_; }

 private:
  std::string forward(PageSession& page, const PageRequest& request, TimePoint now);

  HmiPublisher& publisher_;
  bool allow_remote_commands_;
  GatewayCounters counters_;
};

}  // namespace hapticctrl::web_bridge
