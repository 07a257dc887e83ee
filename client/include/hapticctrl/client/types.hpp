#pragma once
/// @file types.hpp
/// Value types of the hapticctrl client API. SI units; poses {x, y, z, qx, qy, qz, qw} with a
/// unit quaternion; twists and wrenches {linear xyz, angular xyz}.
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace hapticctrl::client {

using Pose7 = std::array<double, 7>;
using Vector6 = std::array<double, 6>;
using Joints6 = std::array<double, 6>;

/// What the client commands, so what the controller renders for the session (VirtuoseAPI's
/// COMMAND_TYPE subset). The joint-space two need a protocol 1.4 controller
/// (Connection::features() has HCP_FEATURE_JOINT_CONTROL; docs/control.md).
enum class CommandType : std::uint32_t {
  kNone = 0,
  kImpedance = 1,           ///< send_wrench: a wrench at the handle
  kVirtmech = 2,            ///< send_object_state: the handle coupled to an object
  kArticular = 3,           ///< send_joint_target: the joints held at set points
  kArticularImpedance = 4,  ///< send_joint_torque: a torque per joint
};

/// VirtuoseAPI indexing modes (values as on the wire).
enum class IndexingMode : std::uint32_t {
  kAll = 0,
  kTranslation = 1,
  kNone = 2,
  kAllInhibited = 3,
  kTranslationInhibited = 4,
  kRotationInhibited = 6,  ///< 5 is not one of VirtuoseAPI's
  kRotation = 7,
};

/// Controller state bits (as in the answer's state word).
namespace state_bits {
inline constexpr std::uint32_t kPowered = 1U << 0;
inline constexpr std::uint32_t kEmergencyStop = 1U << 1;
inline constexpr std::uint32_t kFailSafe = 1U << 2;
inline constexpr std::uint32_t kDegraded = 1U << 3;
inline constexpr std::uint32_t kCoupled = 1U << 4;
inline constexpr std::uint32_t kClientStale = 1U << 5;
inline constexpr std::uint32_t kStopping = 1U << 6;
/// 1.2: the coupling wrench was clipped to the force or torque limit this cycle.
inline constexpr std::uint32_t kSaturated = 1U << 7;
/// 1.2: bits 8 + 2j / 9 + 2j joint j (0-5) in its lower / upper wall; 20 / 21 the J2 + J3 sum.
inline constexpr unsigned kJointBoundsShift = 8;
/// The controller restarted after one that did not stop in order: it refuses this client's
/// power-on until an operator powers the arm on.
inline constexpr std::uint32_t kAwaitingOperator = 1U << 22;
}  // namespace state_bits

/// StateSnapshot::core_state values.
namespace core_states {
inline constexpr std::uint32_t kStarting = 0;
inline constexpr std::uint32_t kRunning = 1;
inline constexpr std::uint32_t kFailSafe = 2;  ///< from here on the controller is going away
inline constexpr std::uint32_t kStopping = 3;
inline constexpr std::uint32_t kStopped = 4;
}  // namespace core_states

/// StateSnapshot::stop_reason values a client acts on (the rest name a fault for the log).
namespace stop_reasons {
/// Never recorded by the controller: the bridge's verdict that the controller process is gone
/// (killed or crashed), not an orderly stop. A new controller may follow: connect again.
inline constexpr std::uint32_t kControllerLost = 8;
}  // namespace stop_reasons

/// One controller cycle as the client received it: taken atomically, timestamped.
struct StateSnapshot {
  bool valid = false;            ///< false until the first answer arrived
  std::uint64_t cycle = 0;       ///< controller cycle number
  std::int64_t received_ns = 0;  ///< this process's CLOCK_MONOTONIC at arrival
  std::uint32_t state_word = 0;  ///< state_bits
  std::uint32_t core_state = 0;  ///< 0 starting, 1 running, 2 fail-safe, 3 stopping, 4 stopped
  std::uint32_t stop_reason = 0;
  CommandType command_type = CommandType::kNone;
  Vector6 coupling_wrench{};  ///< wrench to apply to the virtual object
  Pose7 handle_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6 handle_twist{};
  Joints6 joint_position{};
  Joints6 joint_velocity{};

  [[nodiscard]] bool powered() const noexcept { return (state_word & state_bits::kPowered) != 0; }
  [[nodiscard]] bool emergency_stop() const noexcept {
    return (state_word & state_bits::kEmergencyStop) != 0;
  }
  [[nodiscard]] bool fail_safe() const noexcept {
    return (state_word & state_bits::kFailSafe) != 0;
  }
  /// The controller restarted after a fault and waits for an operator to power the arm on; a
  /// client's power-on is refused until then.
  [[nodiscard]] bool awaiting_operator() const noexcept {
    return (state_word & state_bits::kAwaitingOperator) != 0;
  }
  /// The controller rendered the coupling to the virtual object this cycle.
  [[nodiscard]] bool coupled() const noexcept { return (state_word & state_bits::kCoupled) != 0; }
  /// The controller process is gone (killed or crashed): not an orderly stop, and not a
  /// fail-safe it went through; the next controller of the instance serves a new session.
  [[nodiscard]] bool controller_lost() const noexcept {
    return stop_reason == stop_reasons::kControllerLost;
  }
  /// The controller is failing safe, stopping or gone: the session is over.
  [[nodiscard]] bool session_over() const noexcept {
    return fail_safe() || core_state >= core_states::kFailSafe;
  }
  /// The controller left in order (an operator's stop): the client ends too. A fail-safe or a
  /// lost controller process is not that: a new controller may follow, worth connecting to.
  [[nodiscard]] bool stopped_in_order() const noexcept {
    return !fail_safe() && !controller_lost() && core_state > core_states::kFailSafe;
  }
  /// Why the session ended, in words, from this last cycle.
  [[nodiscard]] const char* ending() const noexcept {
    if (fail_safe()) {
      return "controller failed safe";
    }
    if (controller_lost()) {
      return "controller lost (killed or crashed)";
    }
    return core_state > core_states::kFailSafe ? "controller stopped" : "session closed";
  }
};

/// Network statistics of the session, as seen by this client.
struct LinkStatistics {
  std::uint64_t answers_received = 0;
  std::uint64_t answers_lost = 0;    ///< gaps in the answer sequence
  std::uint64_t answers_late = 0;    ///< arrived after a newer one (dropped)
  std::uint64_t frames_invalid = 0;  ///< datagrams that failed decoding or did not belong
  std::uint64_t control_sent = 0;
  std::uint64_t control_received_by_controller = 0;  ///< from the answers (0 if unsupported)
  std::uint64_t rtt_samples = 0;
  double rtt_last_us = 0.0;  ///< client send -> controller cycle -> answer back
  double rtt_mean_us = 0.0;
  double rtt_max_us = 0.0;
  double interarrival_mean_us = 0.0;
  double interarrival_max_us = 0.0;
  double jitter_us = 0.0;  ///< RFC 3550 smoothed |inter-arrival - period|
  /// What the controller measured of this link and its coupling (protocol 1.1; 0 before).
  double link_delay_us = 0.0;   ///< one-way, client -> controller (smoothed)
  double link_jitter_us = 0.0;  ///< of that one-way delay
  double link_loss = 0.0;       ///< fraction of control frames lost on the way in
  double loop_delay_us = 0.0;   ///< the coupling loop the controller's gains are derived for
  double sample_age_us = 0.0;   ///< age of the object state the controller used last
  /// The coupling gains in force: k_lin [N/m], b_lin [N.s/m], k_ang [N.m/rad], b_ang
  /// [N.m.s/rad] (zero while not coupled).
  std::array<double, 4> coupling_gains{};
  /// Two-port passivity, this end of the channel (J since the session began): energy the
  /// object put in and got out, the controller's reported input, and the steps the library's
  /// passivity controller damped.
  double channel_energy_in = 0.0;
  double channel_energy_out = 0.0;
  double controller_energy_in = 0.0;
  std::uint64_t passivity_active_steps = 0;
  /// Contacts (protocol 1.3): the controller's contacts in force, the contact frames it refused
  /// this session, and the stiffest contact it accepts (N/m in the application's units; 0: the
  /// controller takes no contacts).
  std::uint32_t contacts_in_force = 0;
  std::uint32_t contacts_rejected = 0;
  double max_contact_stiffness = 0.0;
};

/// The most contacts an object may report at once (protocol 1.3).
inline constexpr std::size_t kMaxContacts = 8;

/// A contact the virtual object is in or near (protocol 1.3): a plane, the surface it touches,
/// through `point - distance * normal` and perpendicular to `normal`; client environment frame.
struct Contact {
  std::array<double, 3> point{};   ///< on the object, where it touches or is nearest [m]
  std::array<double, 3> normal{};  ///< unit: the direction in which the surface pushes the object
  double distance = 0.0;           ///< signed gap along normal [m]: < 0 penetrating
  double stiffness = 0.0;  ///< of the surface [N/m], at most the controller's limit (statistics)
  double damping = 0.0;    ///< [N.s/m]
  double friction_static = 0.0;   ///< Coulomb coefficient
  double friction_dynamic = 0.0;  ///< at most the static one
};

/// What set_contacts() did.
enum class ContactResult : std::uint8_t {
  kAccepted,     ///< sent with the next object states
  kTooMany,      ///< more than kMaxContacts (nothing changed)
  kInvalid,      ///< a value out of range: non-finite, a normal that is not a unit vector, ...
  kTooStiff,     ///< stiffer than the controller renders (LinkStatistics::max_contact_stiffness)
  kUnsupported,  ///< the controller speaks no protocol 1.3 (contacts are not sent)
};

/// Why a setup or blocking call failed.
enum class ErrorCode : std::uint8_t {
  kInvalidArgument,  ///< a value out of range (nothing was sent)
  kBusy,             ///< another client holds the controller
  kVersion,          ///< no common protocol version
  kNoController,     ///< the bridge answers, but no controller runs behind it
  kTimeout,          ///< no answer/acknowledgement within the timeout
  kRejected,         ///< the controller refused the value
  kClosed,           ///< the session is closed
  kTransport,        ///< socket or address error
};

/// The exception of every setup and blocking call; what() says what happened and what to do.
class ClientError : public std::runtime_error {
 public:
  ClientError(ErrorCode code, const std::string& message)
      : std::runtime_error(message), code_(code) {}
  [[nodiscard]] ErrorCode code() const noexcept { return code_; }

 private:
  ErrorCode code_;
};

}  // namespace hapticctrl::client
