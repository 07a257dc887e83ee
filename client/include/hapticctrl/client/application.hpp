#pragma once
/// @file application.hpp
/// What an application of the client library needs around a Connection (hapticctrl-demo and
/// hapticctrl-mujoco use them):
/// - a way into a controller that may be busy (another client's session, or one of its own that
///   crashed and holds the session until the bridge's watchdog frees it), not running yet, or
///   failing safe while the application sets it up: connect_retrying;
/// - a close that a controller going away cannot fail: close_quietly;
/// - how far from a surface to report a contact (protocol 1.3): contact_report_distance.
///
/// connect_retrying and close_quietly block (setup code); contact_report_distance is noexcept
/// and allocation-free (safe in a real-time loop).
#include <chrono>
#include <functional>
#include <optional>

#include "hapticctrl/client/connection.hpp"

namespace hapticctrl::client {

struct RetryPolicy {
  /// How long refusals are retried before the last one is thrown; 0: until may_continue()
  /// turns false.
  std::chrono::milliseconds patience{10000};
  /// A refused setup (kRejected) is retried too: the controller that accepted it before is
  /// failing safe again (a stall of the machine can fail it while the application sets it up).
  bool reconnecting = false;
  std::chrono::milliseconds interval{500};
};

/// Whether `policy` retries an error of `code` (busy, no controller, no answer, closed; rejected
/// when reconnecting).
[[nodiscard]] bool retried(ErrorCode code, const RetryPolicy& policy) noexcept;

/// Opens a session to `address` and runs `setup` on it (frames, factors, command type, power),
/// retrying what `policy` retries; `say` hears each new reason once. Returns the session, or
/// nothing once `may_continue()` turns false between attempts (checked every 50 ms); throws the
/// error when it is not retried or the patience has run out.
[[nodiscard]] std::optional<Connection> connect_retrying(
    const Address& address, const ConnectOptions& options,
    const std::function<void(Connection&)>& setup, const std::function<bool()>& may_continue,
    const RetryPolicy& policy, const std::function<void(const ClientError&)>& say);

/// Ends a session; a controller that is going away (a ClientError from close) ends it anyway.
void close_quietly(Connection& c) noexcept;

/// A contact is reported to the controller from this gap on (protocol 1.3): it renders a
/// surface only once the handle touches it, and must know of it before.
inline constexpr double kContactNear = 0.005;  // m
/// How fast a hand may bring the handle to a surface: the arm's speed brake.
inline constexpr double kReachSpeed = 1.0;  // m/s

/// How far from a surface a contact is reported: kContactNear plus what the handle can cover
/// at kReachSpeed over twice the link's round trip (or the coupling loop's delay, the larger).
[[nodiscard]] double contact_report_distance(const LinkStatistics& link) noexcept;

}  // namespace hapticctrl::client
