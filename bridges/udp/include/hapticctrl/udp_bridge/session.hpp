#pragma once
/// @file session.hpp
/// The UDP bridge's protocol state machine: one client session at a time, driven by datagrams
/// and the clock, with no socket of its own (the caller sends the reply it produces). The
/// receive side (on_datagram, check_watchdog) runs on one thread; the answer side (answer) on
/// another, reading the session through an in-process seqlock. Its parts, each tested alone:
/// the handshake gate (handshake.hpp), the parameter channel (parameter_channel.hpp) and the
/// control intake with the link estimator (control_ingest.hpp); the session holds the state they
/// share (the session, its VPr, the counters) and encodes the replies.
///
/// Real-time contract: every member after construction is noexcept and allocation-free; the
/// only syscall is getrandom() when a session opens.
#include <array>
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "hapticctrl/protocol/udp_socket.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"
#include "hapticctrl/udp_bridge/client_allow_list.hpp"
#include "hapticctrl/udp_bridge/control_ingest.hpp"
#include "hapticctrl/udp_bridge/handshake.hpp"
#include "hapticctrl/udp_bridge/hello_limiter.hpp"
#include "hapticctrl/udp_bridge/link_timing.hpp"
#include "hapticctrl/udp_bridge/parameter_channel.hpp"

namespace hapticctrl::udp_bridge {

/// Where accepted client data goes: the controller's VPr region and a ctrl slot.
struct ControllerPorts {
  shm::SeqlockCell<shm::VprPayload>* vpr = nullptr;
  shm::CtrlWriter* ctrl = nullptr;
  Duration period{};  ///< the core's cycle (WELCOME.period_ns)
  /// The core's heartbeat cycle (the segment header's): WELCOME.cycle. Null: 0 is sent.
  const std::atomic<std::uint64_t>* heartbeat_cycle = nullptr;
};

/// Counters shared by both threads (relaxed atomics), copied into the link_stats region.
struct LinkCounters {
  std::atomic<std::uint64_t> frames_in{0};
  std::atomic<std::uint64_t> frames_out{0};
  std::atomic<std::uint64_t> answers_sent{0};  ///< of frames_out (the bridge's --json only)
  std::atomic<std::uint64_t> control_accepted{0};
  std::atomic<std::uint64_t> params_applied{0};
  std::atomic<std::uint64_t> param_duplicates{0};
  std::atomic<std::uint64_t> params_rejected{0};
  std::atomic<std::uint64_t> sessions_opened{0};
  std::atomic<std::uint64_t> sessions_closed{0};
  std::atomic<std::uint64_t> watchdog_expiries{0};
  std::atomic<std::uint64_t> refused_busy{0};
  std::atomic<std::uint64_t> refused_version{0};
  std::atomic<std::uint64_t> send_failures{0};
  std::array<std::atomic<std::uint64_t>, shm::kLinkDropCount> dropped{};

  void drop(shm::LinkDrop why) noexcept {
    dropped[static_cast<std::size_t>(why)].fetch_add(1, std::memory_order_relaxed);
  }
  [[nodiscard]] std::uint64_t dropped_for(shm::LinkDrop why) const noexcept {
    return dropped[static_cast<std::size_t>(why)].load(std::memory_order_relaxed);
  }
};

/// The session watchdog unless the client asks for another: a session outlives a link blackout
/// this long (the core fades the force out within 50 ms of the last fresh sample whatever the
/// watchdog, and ramps it back when samples flow again). It was 100 ms until 2026-12-02: a
/// blackout longer than that decoupled the client for good (H1 asks for 2 s to be survived).
inline constexpr std::uint32_t kDefaultWatchdogMs = 3000;
/// The longest watchdog a client may ask for unless the bridge is told otherwise.
inline constexpr std::uint32_t kMaxWatchdogMs = 10000;

/// Bridge-wide settings.
struct SessionSettings {
  std::uint32_t default_watchdog_ms = kDefaultWatchdogMs;
  /// The longest watchdog a client may ask for (HELLO or a WATCHDOG parameter); until its
  /// first control frame a session is held no longer than the default (one HELLO held the
  /// session for 60 s before, 2026-12-02).
  std::uint32_t max_watchdog_ms = kMaxWatchdogMs;
  ClientAllowList allowed_clients;  ///< empty: every source address
  HelloLimits hello_limits;
};

/// The drop reason a codec status stands for.
[[nodiscard]] shm::LinkDrop drop_reason_of(protocol::DecodeStatus status) noexcept;

class Session {
 public:
  /// `random_token` returns a fresh unpredictable 64-bit value (getrandom in production).
  Session(SessionSettings settings, std::function<std::uint64_t()> random_token);

  /// Connects the session to a running controller (or, with nullptr ports, to none: HELLO is
  /// then refused with NO_CONTROLLER). Closing an active session publishes "no session" first.
  void set_controller(const ControllerPorts* ports, TimePoint now) noexcept;

  /// Handles one datagram from `from`. Writes at most one reply frame into `reply` and returns
  /// its length (0: nothing to send); the reply always goes back to `from`.
  std::size_t on_datagram(std::span<const std::uint8_t> bytes, const protocol::Endpoint& from,
                          TimePoint now, std::span<std::uint8_t> reply) noexcept;

  /// Counts a datagram that did not fit the receive buffer.
  void on_oversized() noexcept;

  /// Closes the session if the client has been silent longer than its watchdog.
  /// Returns true if it did.
  bool check_watchdog(TimePoint now) noexcept;

  /// Closes the session (bridge shutdown or controller gone); the core then ramps out. When
  /// there was one, writes a REFUSE telling its client why into `notice` (returns its length)
  /// and its address into `to`.
  std::size_t close(TimePoint now, std::string_view why, std::span<std::uint8_t> notice,
                    protocol::Endpoint& to) noexcept;

  /// Answer side: encodes the answer frame for one VP sample into `out`; returns its length
  /// and the destination, or 0 when there is no session.
  std::size_t answer(const shm::VpPayload& vp, TimePoint now, std::span<std::uint8_t> out,
                     protocol::Endpoint& to) noexcept;

  [[nodiscard]] LinkCounters& counters() noexcept { return counters_; }
  [[nodiscard]] const LinkCounters& counters() const noexcept { return counters_; }
  /// Copies the counters and session into a link_stats payload.
  void fill_stats(shm::LinkStatsPayload& out) const noexcept;

 private:
  std::size_t on_hello(const hcp_frame& in, const protocol::Endpoint& from, TimePoint now,
                       std::span<std::uint8_t> reply) noexcept;
  std::size_t on_param(const hcp_frame& in, bool values_ok, TimePoint now,
                       std::span<std::uint8_t> reply) noexcept;
  /// A valid PARAM of the session with a new sequence: its ACK (applied, rejected or RETRY).
  ParamAck take_param(const hcp_param& param, std::uint32_t sequence, TimePoint now) noexcept;
  std::size_t on_bye(const hcp_frame& in, TimePoint now, std::span<std::uint8_t> reply) noexcept;
  void on_control(const hcp_frame& in, TimePoint now) noexcept;
  std::size_t refuse(hcp_refuse_code code, std::uint32_t peer_version, std::uint32_t retry_ms,
                     std::string_view reason, TimePoint now, std::span<std::uint8_t> reply,
                     std::uint64_t token = 0) noexcept;
  std::size_t ack(const ParamAck& a, TimePoint now, std::span<std::uint8_t> reply) noexcept;
  std::size_t welcome(TimePoint now, std::span<std::uint8_t> reply) noexcept;
  void open(const hcp_frame& hello, const protocol::Endpoint& from, TimePoint now) noexcept;
  void end_session(TimePoint now) noexcept;
  void publish_vpr(TimePoint now) noexcept;
  void publish_view() noexcept;

  SessionSettings settings_;
  std::function<std::uint64_t()> random_token_;
  ControllerPorts ports_{};
  bool have_controller_ = false;

  // Receive-thread state.
  SessionView session_{};
  std::uint64_t session_number_ = 0;
  std::uint32_t watchdog_ms_ = 0;
  TimePoint last_heard_;
  bool engaged_ = false;  ///< a control or parameter frame since the HELLO
  std::uint32_t reply_sequence_ = 0;
  std::uint32_t control_received_ = 0;
  shm::VprPayload vpr_{};
  AnswerLog answer_log_;  ///< written by the answer thread, read by the intake
  ControlIngest ingest_{answer_log_};
  ParameterChannel params_;
  HelloLimiter hello_limiter_;

  // Shared with the answer thread.
  shm::SeqlockCell<SessionView> view_;
  shm::SeqlockCell<LinkFigures> link_view_;  ///< written by the receive thread
  std::atomic<std::uint32_t> control_received_shared_{0};
  std::uint32_t answer_sequence_ = 0;  ///< answer thread only
  LinkFigures link_answered_;          ///< answer thread only: the figures of the last answer
  LinkCounters counters_;
};

}  // namespace hapticctrl::udp_bridge
