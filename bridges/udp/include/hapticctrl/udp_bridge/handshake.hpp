#pragma once
/// @file handshake.hpp
/// The gate of the bridge's one session: what a HELLO gets (a session, the WELCOME again, or a
/// REFUSE that says why), what a new session is granted (features, watchdog), and which frames
/// a session may send (the control frames of the features it negotiated, from its own address
/// with its own token).
///
/// Real-time contract: noexcept, no allocation, no syscall (the bridge's receive thread).
#include <cstdint>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/udp_socket.hpp"

namespace hapticctrl::udp_bridge {

/// The session as the gate (and the answer thread) sees it.
struct SessionView {
  std::uint64_t token = 0;  ///< 0: no session
  protocol::Endpoint peer{};
  std::uint32_t features = 0;
  std::uint32_t pad = 0;
};

/// What the bridge says to a HELLO.
struct HelloVerdict {
  enum class Kind : std::uint8_t {
    kOpen,          ///< a new session, then WELCOME
    kWelcomeAgain,  ///< the session's own client asks again (our WELCOME was lost)
    kRefuse,        ///< REFUSE with code, retry_ms and reason
  };
  Kind kind = Kind::kOpen;
  hcp_refuse_code code = HCP_REFUSE_BUSY;
  std::uint32_t retry_ms = 0;
  char reason[HCP_TEXT_BYTES] = {};  // NOLINT(*-avoid-c-arrays): the XDR field's shape
};

/// The gate's view of the bridge when a HELLO comes.
struct GateState {
  const SessionView& session;
  bool have_controller = false;
  Duration silent{};  ///< since the session's client was last heard
  std::uint32_t watchdog_ms = 0;
};

/// A valid HELLO from `from`: another major version is refused (saying both), a second client
/// while a session is active is told to retry when the session's watchdog would expire, and
/// without a controller nobody gets a session.
[[nodiscard]] HelloVerdict judge_hello(const hcp_frame& hello, const protocol::Endpoint& from,
                                       const GateState& state) noexcept;

/// The features a new session gets of those its HELLO asks for (local coupling builds on
/// timing: without it, neither).
[[nodiscard]] std::uint32_t granted_features(std::uint32_t asked) noexcept;

/// The watchdog a new session gets: the one asked for (0: `default_ms`), at most `max_ms`.
[[nodiscard]] std::uint32_t granted_watchdog_ms(std::uint32_t asked, std::uint32_t default_ms,
                                                std::uint32_t max_ms) noexcept;

/// Whether the session is `session` (its token, from its own address).
[[nodiscard]] bool from_session(const hcp_frame& in, const protocol::Endpoint& from,
                                const SessionView& session) noexcept;

/// Whether a session with `features` may send a control frame of `type`.
[[nodiscard]] bool negotiated(hcp_frame_type type, std::uint32_t features) noexcept;

}  // namespace hapticctrl::udp_bridge
