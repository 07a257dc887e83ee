#pragma once
/// @file page_request.hpp
/// What a page may ask, validated: JSON text from a WebSocket becomes an HMI command or an
/// operator wrench for LCM (hmi_command_t, hmi_force_t), or a refusal with its reason. The LCM
/// bridge validates again before anything reaches the core; this layer refuses early so that the
/// page is told why, and so that nothing malformed reaches the bus.
///
/// Page messages:
///   {"type":"command","command":"power_on|power_off|emergency_stop|emergency_reset"}
///   {"type":"force","wrench":[fx,fy,fz,tx,ty,tz]}   (N, N.m, base frame)
///
/// Real-time contract: soft-RT (a web server thread); allocates (JSON parsing), never throws.
#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace hapticctrl::web_bridge {

/// The largest page message accepted; the real ones are under 200 bytes.
inline constexpr std::size_t kMaxPageMessageBytes = 1024;

/// Operator wrench bounds per axis: the LCM bridge's and the core's (shm::ForceLimits).
inline constexpr double kMaxPageForce = 100.0;  ///< N
inline constexpr double kMaxPageTorque = 10.0;  ///< N.m

enum class PageRequestKind : std::uint8_t {
  kCommand,     ///< `command` holds the hmi_command_t code
  kForce,       ///< `wrench` holds the operator wrench
  kMalformed,   ///< not JSON, not an object, unknown type, a missing or mistyped field
  kOutOfRange,  ///< a wrench value non-finite or beyond the bounds
  kRefused,     ///< a command or force while remote commands are disabled
};

struct PageRequest {
  PageRequestKind kind = PageRequestKind::kMalformed;
  std::int32_t command = 0;  ///< hmi_command_t::POWER_ON ...
  std::string name;          ///< the command's name as the page sent it ("force" for forces)
  std::array<double, 6> wrench{};
  std::string reason;  ///< why it was not accepted (empty when accepted)

  [[nodiscard]] bool accepted() const noexcept {
    return kind == PageRequestKind::kCommand || kind == PageRequestKind::kForce;
  }
};

/// Parses and validates one page message. Only the emergency stop passes when
/// `allow_remote_commands` is false.
[[nodiscard]] PageRequest parse_page_request(std::string_view text, bool allow_remote_commands);

/// The page's answer to a request: {"type":"reply","request":name,"ok":bool,"reason":...}.
[[nodiscard]] std::string reply_json(const std::string& request, bool ok,
                                     const std::string& reason);
/// The answer to a parsed request: ok when accepted, else its reason.
[[nodiscard]] std::string reply_json(const PageRequest& request);

}  // namespace hapticctrl::web_bridge
