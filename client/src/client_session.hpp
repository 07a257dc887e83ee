#pragma once
/// @file client_session.hpp
/// The client's side of the protocol as a state machine with no socket, no thread and no clock
/// of its own: decoded frames come in with the time they arrived, frames to send come out for
/// the caller to send. It owns the handshake, the answers (link monitor, two-port passivity,
/// the latest state), the acknowledgements of reliable frames, the keepalive and the silence
/// watchdog, and the statistics. Connection (connection.cpp) is the I/O shell around it: the
/// socket, the receive thread, the locks and the waiting.
///
/// Not thread-safe: the shell serialises every call. Nothing here blocks or sleeps.

#include <cstdint>
#include <optional>
#include <span>
#include <string>

#include "channel_passivity.hpp"
#include "contact_set.hpp"
#include "hapticctrl/client/connection.hpp"
#include "hapticctrl/protocol/codec.hpp"
#include "link_monitor.hpp"
#include "local_coupling.hpp"

namespace hapticctrl::client {

/// What a frame that arrived during the handshake did.
struct HandshakeStep {
  bool welcomed = false;            ///< the session is open
  std::optional<hcp_frame> reply;   ///< to send first (a refusal of the controller's version)
  std::optional<ClientError> fail;  ///< to throw after sending the reply: asking again won't help
};

/// What a frame that arrived in an open session was.
enum class Arrival : std::uint8_t {
  kIgnored,  ///< a duplicate or out-of-order answer, or a frame type a client does not expect
  kInvalid,  ///< not from this session (counted)
  kAnswer,   ///< a new state: latest() changed
  kAck,      ///< an acknowledgement: ack_of() may have it
  kClosed,   ///< the bridge ended the session (closed_reason() says why)
};

/// The controller's answer to a reliable frame.
struct AckOutcome {
  hcp_ack_status status = HCP_ACK_OK;
  std::string reason;
};

class ClientSession {
 public:
  /// `peer_text` names the controller in error messages ("host:port").
  ClientSession(ConnectOptions options, std::string peer_text);

  // --- handshake ---------------------------------------------------------------------------
  /// The HELLO to send at `now`, when one is due (at once, then every two retransmit periods,
  /// or once a refusal's retry time has passed).
  std::optional<hcp_frame> hello_due(TimePoint now);
  /// A frame from the controller's address before the session opened.
  HandshakeStep on_handshake_frame(const hcp_frame& frame, TimePoint now);
  /// The error when the connect timeout passes without a WELCOME (kTimeout, or the last
  /// refusal's code and reason).
  [[nodiscard]] ClientError handshake_timeout() const;

  // --- an open session ---------------------------------------------------------------------
  /// A frame from the controller's address (decoded).
  Arrival on_frame(const hcp_frame& frame, TimePoint now) noexcept;
  /// A datagram that did not decode, or came from another address.
  void on_invalid() noexcept { monitor_.on_invalid(); }
  /// Every frame the shell sent (the keepalive counts the quiet time from it).
  void on_sent(TimePoint now) noexcept { last_send_ = now; }
  /// The KEEPALIVE to send when the application has been quiet for a quarter of the watchdog.
  std::optional<hcp_frame> keepalive_due(TimePoint now) noexcept;
  /// Closes the session if the bridge sent nothing for the answer timeout; true if it did.
  bool close_if_silent(TimePoint now);
  /// Marks the session closed for `reason` (no effect if already closed).
  void close(std::string_view reason);
  [[nodiscard]] bool is_open() const noexcept { return open_; }
  [[nodiscard]] const std::string& closed_reason() const noexcept { return closed_reason_; }

  // --- control frames (unreliable) -----------------------------------------------------------
  /// The object-state frame for (pose, twist) sent at `now` (timed for a 1.1+ controller, with
  /// the echo of the newest answer and the energy the object put into the channel), or nothing
  /// when the session is closed or the rotation is not a unit quaternion.
  std::optional<hcp_frame> object_frame(const Pose7& pose, const Vector6& twist,
                                        TimePoint now) noexcept;
  std::optional<hcp_frame> wrench_frame(const Vector6& wrench, TimePoint now) noexcept;
  /// Protocol 1.4 (JOINT_CONTROL): ARTICULAR's joint set points, ARTICULAR_IMPEDANCE's torques;
  /// nothing when the session did not negotiate it, is closed, or a value is out of range.
  std::optional<hcp_frame> joint_target_frame(const Joints6& position, const Joints6& speed,
                                              TimePoint now) noexcept;
  std::optional<hcp_frame> joint_torque_frame(const Joints6& torque, TimePoint now) noexcept;
  /// The object's contacts from now on (protocol 1.3), checked as the controller checks them.
  ContactResult set_contacts(std::span<const Contact> contacts) noexcept;
  /// The next CONTROL_CONTACT to send at `now` after an object state, if one is due (a changed
  /// slot, a slot not sent for 5 ms, or the clearing of every slot); call until none is.
  std::optional<hcp_frame> contact_frame_due(TimePoint now) noexcept;
  /// One control frame left the socket (statistics).
  void on_control_sent() noexcept { ++control_sent_; }

  // --- reliable frames -----------------------------------------------------------------------
  /// The PARAM frame for `param` (sequence and token set). Throws ClientError(kInvalidArgument)
  /// naming `what` for a value the protocol refuses, kClosed when the session is closed.
  hcp_frame param_frame(const hcp_param& param, const std::string& what);
  /// The BYE frame. Throws kClosed when the session is closed.
  hcp_frame bye_frame(const std::string& what);
  /// The acknowledgement of reliable frame `sequence`, once it arrived (taken: asked once).
  std::optional<AckOutcome> take_ack(std::uint32_t sequence) noexcept;
  /// The controller acknowledged `param` (OK): what the client keeps of it takes effect (the
  /// watchdog the keepalive follows, the factors and object the channel's passivity uses).
  void on_param_applied(const hcp_param& param) noexcept;
  /// The error of a call `what` on a closed session, with the reason it closed.
  [[nodiscard]] ClientError closed_error(const std::string& what) const;

  // --- what the session knows ----------------------------------------------------------------
  [[nodiscard]] const StateSnapshot& latest() const noexcept { return latest_; }
  [[nodiscard]] LinkStatistics statistics() const noexcept;
  [[nodiscard]] std::uint32_t features() const noexcept { return features_; }
  [[nodiscard]] std::uint32_t watchdog_ms() const noexcept { return watchdog_ms_; }
  [[nodiscard]] Duration controller_period() const noexcept { return period_; }
  [[nodiscard]] std::uint32_t controller_version() const noexcept { return controller_version_; }
  [[nodiscard]] const std::string& peer_text() const noexcept { return peer_text_; }
  [[nodiscard]] const ConnectOptions& options() const noexcept { return options_; }

 private:
  [[nodiscard]] std::uint32_t version() const noexcept;
  void welcome(const hcp_frame& frame, TimePoint now) noexcept;
  [[nodiscard]] hcp_frame version_refusal(const hcp_frame& welcome, TimePoint now,
                                          std::string& reason) const;
  bool on_answer(const hcp_frame& frame, TimePoint now) noexcept;
  /// Protocol 1.3: the object's wrench (or an IMPEDANCE client's handle image) in latest_.
  void close_locally() noexcept;
  /// The object's penetration into the contacts set along the controller's contact normal (m).
  [[nodiscard]] double contact_penetration() const noexcept;
  [[nodiscard]] bool local() const noexcept {
    return (features_ & HCP_FEATURE_LOCAL_COUPLING) != 0;
  }
  hcp_frame timed_object_frame(const Pose7& pose, const Vector6& twist, TimePoint now) noexcept;
  [[nodiscard]] std::uint32_t answer_echo(TimePoint now) const noexcept;
  std::uint32_t next_control_sequence() noexcept { return ++control_sequence_; }
  std::optional<hcp_frame> checked_control(hcp_frame frame) const noexcept;

  ConnectOptions options_;
  std::string peer_text_;

  // Handshake.
  TimePoint next_hello_;
  std::uint32_t hello_sequence_ = 0;
  std::string last_refusal_;
  ErrorCode last_refusal_code_ = ErrorCode::kTimeout;

  // The session, once WELCOME opened it.
  bool open_ = false;
  std::string closed_reason_;
  std::uint64_t token_ = 0;
  std::uint32_t features_ = 0;
  std::uint32_t watchdog_ms_ = 0;
  std::uint32_t controller_version_ = 0;
  Duration period_{};
  TimePoint last_heard_;  ///< last valid frame from the bridge
  TimePoint last_send_;

  std::uint32_t control_sequence_ = 0;
  std::uint32_t reliable_sequence_ = 0;
  std::uint64_t control_sent_ = 0;
  std::optional<std::pair<std::uint32_t, AckOutcome>> ack_;  ///< the newest acknowledgement

  StateSnapshot latest_;
  LinkMonitor monitor_;
  ChannelPassivity passivity_;
  hcp_coupling_report report_{};  ///< the controller's, from the newest ANSWER_TIMED
  TimePoint last_object_send_ = kNotYet;
  std::uint64_t last_send_cycle_ = 0;  ///< the newest answer's cycle at the last object send
  double time_step_ = 0.0;             ///< the application's declared step (s)

  // Protocol 1.3: the object's side of the coupling, closed here (local_coupling.hpp).
  hcp_local_coupling local_{};  ///< from the newest ANSWER_COUPLED
  CouplingTerms terms_;
  Vector6 controller_wrench_{};              ///< the object's wrench as the newest answer gave it
  Pose7 channel_pose_{0, 0, 0, 0, 0, 0, 1};  ///< the handle as the newest answer gave it
  Vector6 channel_twist_{};
  Pose7 object_pose_{0, 0, 0, 0, 0, 0, 1};  ///< the object's newest state, as sent
  Vector6 object_twist_{};
  bool have_object_ = false;
  Vector6 held_wrench_{};  ///< IMPEDANCE: the wrench sent last
  TimePoint last_wrench_send_ = kNotYet;
  double speed_factor_ = 1.0;
  double force_factor_ = 1.0;
  ContactSet contacts_;  ///< protocol 1.3: the object's contacts, sent slot by slot
};

}  // namespace hapticctrl::client
