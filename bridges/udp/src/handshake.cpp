// Implements handshake.hpp: the gate of the bridge's one session.
#include "hapticctrl/udp_bridge/handshake.hpp"

#include <algorithm>
#include <cstdio>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {
namespace {

HelloVerdict refusal(hcp_refuse_code code, std::uint32_t retry_ms, const char* reason) noexcept {
  HelloVerdict v;
  v.kind = HelloVerdict::Kind::kRefuse;
  v.code = code;
  v.retry_ms = retry_ms;
  protocol::set_text(v.reason, reason);
  return v;
}

}  // namespace

HelloVerdict judge_hello(const hcp_frame& hello, const protocol::Endpoint& from,
                         const GateState& state) noexcept {
  const std::uint32_t theirs = hello.header.protocol;
  const std::uint32_t oldest = hello.body.hcp_body_u.hello.min_version;
  const std::uint32_t our_major = protocol::version_major(protocol::kVersion);
  if (protocol::version_major(oldest) > our_major || protocol::version_major(theirs) < our_major) {
    HelloVerdict v = refusal(HCP_REFUSE_VERSION, 0, "");
    std::snprintf(v.reason, sizeof v.reason,
                  "protocol version mismatch: client %u.%u (oldest %u.%u), controller %u.%u",
                  protocol::version_major(theirs), protocol::version_minor(theirs),
                  protocol::version_major(oldest), protocol::version_minor(oldest), our_major,
                  protocol::version_minor(protocol::kVersion));
    return v;
  }
  if (state.session.token != 0) {
    if (from == state.session.peer) {
      return HelloVerdict{HelloVerdict::Kind::kWelcomeAgain};
    }
    const auto silent_ms = std::chrono::duration_cast<std::chrono::milliseconds>(state.silent);
    const auto retry = static_cast<std::uint32_t>(std::max<std::int64_t>(
        1, static_cast<std::int64_t>(state.watchdog_ms) - silent_ms.count()));
    return refusal(HCP_REFUSE_BUSY, retry,
                   "busy: another client session is active on this controller");
  }
  if (!state.have_controller) {
    return refusal(HCP_REFUSE_NO_CONTROLLER, 0,
                   "no controller: hapticctrl-core is not running for this bridge's instance");
  }
  return HelloVerdict{HelloVerdict::Kind::kOpen};
}

std::uint32_t granted_features(std::uint32_t asked) noexcept {
  std::uint32_t features = asked & protocol::kAllFeatures;
  if ((features & HCP_FEATURE_TIMING) == 0) {
    features &= ~static_cast<std::uint32_t>(HCP_FEATURE_LOCAL_COUPLING);  // builds on it
  }
  return features;
}

std::uint32_t granted_watchdog_ms(std::uint32_t asked, std::uint32_t default_ms,
                                  std::uint32_t max_ms) noexcept {
  return std::min(asked != 0 ? asked : default_ms, max_ms);
}

bool from_session(const hcp_frame& in, const protocol::Endpoint& from,
                  const SessionView& session) noexcept {
  return session.token != 0 && in.header.token == session.token && from == session.peer;
}

bool negotiated(hcp_frame_type type, std::uint32_t features) noexcept {
  switch (type) {
    case HCP_CONTROL_OBJECT_TIMED:
      return (features & HCP_FEATURE_TIMING) != 0;
    case HCP_CONTROL_WRENCH_TIMED:
    case HCP_CONTROL_CONTACT:
      return (features & HCP_FEATURE_LOCAL_COUPLING) != 0;
    case HCP_CONTROL_JOINT_TARGET:
    case HCP_CONTROL_JOINT_TORQUE:
      return (features & HCP_FEATURE_JOINT_CONTROL) != 0;
    default:
      return true;
  }
}

}  // namespace hapticctrl::udp_bridge
