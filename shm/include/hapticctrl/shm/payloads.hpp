#pragma once
/// @file payloads.hpp
/// THE contract between hapticctrl processes: the payload of every shared-memory region.
///
/// Rules: fixed-size fields only, explicit padding, no pointers, SI units, poses as
/// {x, y, z, qx, qy, qz, qw} in metres and a unit quaternion, twists and wrenches as
/// {linear xyz, angular xyz}. Any change to a struct here bumps kAbiVersion (layout.hpp), and the
/// static_asserts at the bottom pin the sizes so an accidental change fails to compile.
/// Everything read from shared memory is untrusted input for the reader: validate before use.

#include <array>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::shm {

using Pose7 = std::array<double, 7>;    ///< x, y, z [m], qx, qy, qz, qw
using Vector6 = std::array<double, 6>;  ///< linear xyz, angular xyz
using Joints6 = std::array<double, 6>;  ///< one value per joint, base to wrist

/// Command type of the client session (VirtuoseAPI's COMMAND_TYPE subset; protocol 1.4 adds the
/// joint-space two, J6).
enum class CommandType : std::uint32_t {
  kNone = 0,
  kImpedance = 1,
  kVirtmech = 2,
  kArticular = 3,           ///< the joints held at set points (joint_target, joint_speed)
  kArticularImpedance = 4,  ///< a torque per joint (joint_torque)
};

/// Lifecycle of the core process, in VP and the segment header.
enum class CoreState : std::uint32_t {
  kStarting = 0,
  kRunning = 1,
  kFailSafe = 2,  ///< fail-safe sequence under way (VP says why)
  kStopping = 3,  ///< orderly stop under way (same sequence, not a fault)
  kStopped = 4,
};

/// Numbered, latched reasons for leaving the cycle. 0 means none.
enum class StopReason : std::uint32_t {
  kNone = 0,
  kConsecutiveMisses = 1,  ///< exactly 5 consecutive deadline misses
  kStopRequested = 2,      ///< ctrl stop command (orderly, exit 0)
  kSignal = 3,             ///< SIGINT/SIGTERM (orderly, exit 0)
  kChronicMisses = 4,      ///< windowed miss rate / leaky bucket over threshold (if enabled)
  kArmFault = 5,           ///< arm I/O reported a fault or non-finite measures
  kDurationElapsed = 6,    ///< --duration reached (orderly, exit 0)
  kVelocityLimit = 7,      ///< handle or joint speed above the safety threshold
  kCoreLost = 8,  ///< never written by the core: a bridge's verdict that the core process is gone
};

/// Bits of the state word carried in VP (and over the protocol).
namespace state_bits {
inline constexpr std::uint32_t kPowered = 1U << 0;        ///< motor supply on, commands enabled
inline constexpr std::uint32_t kEmergencyStop = 1U << 1;  ///< e-stop latched until reset
inline constexpr std::uint32_t kFailSafe = 1U << 2;       ///< fail-safe sequence started
inline constexpr std::uint32_t kDegraded = 1U << 3;       ///< this cycle ran the degraded SERVO
inline constexpr std::uint32_t kCoupled = 1U << 4;        ///< coupling active this cycle
inline constexpr std::uint32_t kClientStale = 1U << 5;    ///< VPr stale: extrapolating/fading
inline constexpr std::uint32_t kStopping = 1U << 6;       ///< orderly stop under way
/// The coupling wrench was clipped to the force or torque limit this cycle.
inline constexpr std::uint32_t kSaturated = 1U << 7;
/// Bits 8 + 2j / 9 + 2j: joint j (0-5) in its lower / upper wall; bits 20 / 21: the J2 + J3 sum in
/// its lower / upper wall (the arm model's coupled limit). `joint_bound(j, upper)` names them.
inline constexpr std::uint32_t kJointBoundsShift = 8;
inline constexpr std::uint32_t kJointBoundsMask = 0x3FFFU << kJointBoundsShift;
/// The core before this one did not stop in order (killed, crashed or failed safe): a client's
/// power-on is refused until an operator powers the arm on (J8; IEC 60204-1 7.5: no restart of
/// its own after a fault).
inline constexpr std::uint32_t kAwaitingOperator = 1U << 22;
/// The bound bit of joint `j` (0-5; 6 for the J2 + J3 sum), lower or upper.
[[nodiscard]] HAPTICCTRL_RT constexpr std::uint32_t joint_bound(unsigned j, bool upper) noexcept {
  return 1U << (kJointBoundsShift + 2U * j + (upper ? 1U : 0U));
}
}  // namespace state_bits

/// Bits of VprPayload::flags.
namespace vpr_flags {
inline constexpr std::uint32_t kObjectAttached = 1U << 0;  ///< VIRTMECH couples only when set
/// The session negotiated protocol 1.3's local coupling: the client closes its object's side of
/// the coupling, reports its IMPEDANCE energy and may send contacts.
inline constexpr std::uint32_t kLocalCoupling = 1U << 1;
/// Protocol 1.4: the joint command of the command type in force (a CONTROL_JOINT_TARGET in
/// ARTICULAR, a CONTROL_JOINT_TORQUE in ARTICULAR_IMPEDANCE) has come since it was set: until
/// then the joint fields are not the client's and the core renders nothing from them.
inline constexpr std::uint32_t kJointCommand = 1U << 2;
}  // namespace vpr_flags

/// Contact slots a client may use (protocol 1.3, HCP_MAX_CONTACTS).
inline constexpr std::size_t kMaxContacts = 8;

/// One contact of the client's object (protocol 1.3 CONTROL_CONTACT) as the bridge took it: a
/// plane through point - distance * normal, perpendicular to normal, that the object touches or
/// is near. Client environment frame. stiffness 0: the slot is empty.
struct ContactSlot {
  std::array<double, 3> point{};     ///< on the object [m]
  std::array<double, 3> normal{};    ///< unit: the direction in which the surface pushes the object
  double distance = 0.0;             ///< signed gap along normal [m]: < 0 penetrating
  double stiffness = 0.0;            ///< [N/m]; 0: empty slot
  double damping = 0.0;              ///< [N.s/m]
  std::array<double, 2> friction{};  ///< static, dynamic Coulomb coefficients
  /// The object's pose when the contact came (the newest object state of the session).
  Pose7 object_pose{0, 0, 0, 0, 0, 0, 1};
  std::int64_t received_time_ns = 0;  ///< bridge receive time, CLOCK_MONOTONIC
  /// When the client computed it, on this host's clock (as VprPayload::sample_time_ns); 0: unknown.
  std::int64_t sample_time_ns = 0;
};

/// VPr: client -> core. Written by the UDP bridge from validated control frames.
struct VprPayload {
  std::uint64_t session_id = 0;  ///< 0: no client session
  /// Sequence number of the client frame the object state (or IMPEDANCE wrench) came from: a new
  /// value is a new sample (a contact frame leaves it as it is).
  std::uint64_t client_sequence = 0;
  std::int64_t client_time_ns = 0;    ///< the client's sender timestamp (its own clock)
  std::int64_t received_time_ns = 0;  ///< bridge receive time, CLOCK_MONOTONIC
  /// When the client computed this state, on this host's CLOCK_MONOTONIC: received_time_ns less
  /// the link's one-way delay as the bridge measured it for this frame (protocol 1.1 timing);
  /// 0 when unknown (a 1.0 client): the core then dates the sample at its arrival.
  std::int64_t sample_time_ns = 0;
  /// The core cycle whose ANSWER the client had received when it computed this state (0:
  /// unknown). The core's cycle minus this is the coupling loop's delay in cycles.
  std::uint64_t echo_cycle = 0;
  std::int64_t link_delay_ns = 0;   ///< smoothed one-way delay of the client link (bridge's view)
  std::int64_t link_jitter_ns = 0;  ///< smoothed |change| of the one-way delay between frames
  std::uint32_t link_loss_ppm = 0;  ///< control frames lost on the way in (smoothed)
  std::uint32_t reserved = 0;
  /// Energy the client's object has put into the coupling channel since the session began (J;
  /// protocol 1.1; negative: the client does not report it, no two-port passivity).
  double client_energy_in = -1.0;
  std::uint32_t command_type = 0;  ///< CommandType
  std::uint32_t indexing_mode = 0;
  std::uint32_t watchdog_timeout_us = 0;
  std::uint32_t flags = 0;  ///< vpr_flags
  Pose7 object_pose{};
  Vector6 object_twist{};
  Vector6 impedance_wrench{};              ///< IMPEDANCE: wrench to render at the handle [N, N·m]
  double object_mass = 0.0;                ///< kg
  std::array<double, 3> object_inertia{};  ///< principal inertia, kg·m²
  double client_time_step = 0.0;           ///< s
  double force_factor = 1.0;
  double speed_factor = 1.0;
  Pose7 base_frame{0, 0, 0, 0, 0, 0, 1};
  Pose7 observation_frame{0, 0, 0, 0, 0, 0, 1};
  std::array<double, 4> gain_override{};  ///< k_lin, b_lin, k_ang, b_ang; 0 = derived
  std::array<double, 2> force_limits{};   ///< max force [N], max torque [N·m]; 0 = model's
  Joints6 joint_target{};                 ///< ARTICULAR: where each joint is to be [rad]
  Joints6 joint_speed{};   ///< ARTICULAR: how fast each joint is to move there [rad/s]
  Joints6 joint_torque{};  ///< ARTICULAR_IMPEDANCE: a torque per joint [N·m]
  /// Contacts of the object (protocol 1.3): slots below contact_count are in use.
  std::uint32_t contact_count = 0;
  std::uint32_t contact_frames = 0;  ///< CONTROL_CONTACT frames taken this session (wraps)
  std::array<ContactSlot, kMaxContacts> contacts{};
};

/// VP: core -> client (read by the UDP bridge once per cycle).
struct VpPayload {
  std::uint64_t cycle = 0;
  std::uint64_t echo_client_sequence = 0;  ///< last VPr client_sequence the core used
  std::int64_t echo_client_time_ns = 0;
  std::uint32_t state_word = 0;    ///< state_bits
  std::uint32_t core_state = 0;    ///< CoreState
  std::uint32_t stop_reason = 0;   ///< StopReason, once fail-safe or stop has begun
  std::uint32_t command_type = 0;  ///< CommandType in force
  /// The wrench the client applies to its object, in the client's frame [N, N·m] (force factor
  /// applied; not the wrench rendered on the handle: PositionPayload::rendered_wrench).
  Vector6 object_wrench{};
  /// The handle as the client sees it: in the client's frame, speed factor applied (not the
  /// handle in the base frame: PositionPayload::handle_pose).
  Pose7 client_handle_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6 client_handle_twist{};
  Joints6 joint_position{};
  Joints6 joint_velocity{};
  /// The coupling as the core ran it this cycle (telemetry and the client's statistics).
  std::int64_t sample_age_ns = 0;  ///< age of the client sample used (network + bridge + wait)
  std::int64_t loop_delay_ns = 0;  ///< coupling loop delay the gains were derived for
  std::array<double, 4> gains{};   ///< k_lin N/m, b_lin N.s/m, k_ang N.m/rad, b_ang N.m.s/rad
  /// Two-port passivity, the core's end of the channel (J since the session began): energy the
  /// core put in (sent to the client, which bounds its output by it) and took out.
  double channel_energy_in = 0.0;
  double channel_energy_out = 0.0;
  /// Protocol 1.3, the coupling as the client closes its object's side (ANSWER_COUPLED): the
  /// coupling is stiffer along contact_normal (client frame; 0 0 0: none) by normal_gains
  /// (stiffness N/m, damping N.s/m, base frame units as `gains`) while it pushes the object into
  /// a contact; the force and torque limits in force.
  std::array<double, 3> contact_normal{};
  std::array<double, 2> normal_gains{};
  std::array<double, 2> limits{};
  double max_contact_stiffness = 0.0;   ///< N/m, the stiffest contact the core accepts
  std::uint32_t contacts = 0;           ///< contact slots in force (fresh)
  std::uint32_t contacts_rejected = 0;  ///< contacts refused this session (stiffer than the limit)
  /// J2: the reported surface the core renders on the handle (client frame; normal 0 0 0: none):
  /// a point on the plane as rendered and its normal, how deep the handle's point is in it as
  /// rendered, the force it renders along the normal, how much of the reported depth a model
  /// update hid (passive updates), the age of the newest contact in force (-1: none) and the
  /// energy the hidden depth withheld from the hand this session.
  std::array<double, 3> surface_point{};
  std::array<double, 3> surface_normal{};
  double surface_depth = 0.0;     ///< m
  double surface_force = 0.0;     ///< N
  double surface_hidden = 0.0;    ///< m
  double surface_withheld = 0.0;  ///< J
  std::int64_t contact_age_ns = -1;
};

/// A spring-damper hand gripping the simulated handle: it pulls the handle point towards
/// `anchor` (which moves at `anchor_velocity`) with `stiffness` and resists the handle's speed
/// relative to the anchor with `damping`; its wrist turns the handle towards `anchor_rotation`
/// with `angular_stiffness` and resists its rotation with `angular_damping`. All four 0: no hand.
/// The operator model of the coupling benchmark and tests (a person's grip is 100-1000 N/m,
/// 2-20 N.s/m; ../shared/HAPTICS_REFERENCE.md).
struct HandGrip {
  std::array<double, 3> anchor{};                     ///< base frame [m]
  std::array<double, 3> anchor_velocity{};            ///< base frame [m/s]
  double stiffness = 0.0;                             ///< N/m
  double damping = 0.0;                               ///< N.s/m
  std::array<double, 4> anchor_rotation{0, 0, 0, 1};  ///< base frame, quaternion x y z w
  double angular_stiffness = 0.0;                     ///< N.m/rad
  double angular_damping = 0.0;                       ///< N.m.s/rad
};

/// force: the operator on the simulated handle (written by the HMI side): a wrench, plus an
/// optional spring-damper hand the simulator evaluates at every integration sub-step.
struct ForcePayload {
  Vector6 wrench{};  ///< base frame, at the handle point [N, N·m]
  HandGrip hand{};
};

/// position: arm state for the HMI and monitors.
struct PositionPayload {
  std::uint64_t cycle = 0;
  std::uint32_t state_word = 0;
  std::uint32_t core_state = 0;
  Joints6 joint_position{};
  Joints6 joint_velocity{};
  Joints6 joint_torque{};  ///< commanded motor torques after saturation [N·m]
  Pose7 handle_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6 handle_twist{};
  Vector6 operator_wrench{};  ///< operator's wrench on the handle, base frame
  Vector6 rendered_wrench{};  ///< the wrench the controller renders on the handle, base frame
};

/// Real-time mode the core obtained at start (telemetry).
enum class RtMode : std::uint32_t {
  kNone = 0,          ///< SCHED_OTHER, no memory lock
  kFifo = 1,          ///< SCHED_FIFO but memory not locked
  kFifoLocked = 2,    ///< SCHED_FIFO and mlockall
  kFifoLockedRt = 3,  ///< SCHED_FIFO, mlockall, PREEMPT_RT kernel
};

/// Summary statistics of a latency series, nanoseconds.
struct LatencySummary {
  std::int64_t min_ns = 0;
  std::int64_t avg_ns = 0;
  std::int64_t max_ns = 0;
  std::int64_t p50_ns = 0;
  std::int64_t p99_ns = 0;
  std::int64_t p999_ns = 0;
  std::uint64_t samples = 0;
  std::uint64_t overflows = 0;  ///< samples beyond the histogram's last bin
};

/// Upper bin edges [µs] of the coarse wake-latency histogram in telemetry; the last bin counts
/// everything from the last edge on (the core's 1 µs histogram overflows there too).
inline constexpr std::array<std::int64_t, 12> kLatencyBucketEdgesUs{
    2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000};
inline constexpr std::size_t kLatencyBuckets = kLatencyBucketEdgesUs.size() + 1;

/// telemetry: cycle health, published by the core at a few tens of Hz.
struct TelemetryPayload {
  std::uint64_t cycle = 0;
  std::int64_t period_ns = 0;
  std::uint32_t rt_mode = 0;  ///< RtMode
  std::uint32_t core_state = 0;
  std::uint32_t stop_reason = 0;
  std::uint32_t consecutive_misses = 0;
  std::uint64_t misses_total = 0;
  std::uint64_t degraded_cycles = 0;
  std::uint64_t skipped_slots = 0;         ///< periods skipped after late wake-ups
  std::uint64_t late_servo_discarded = 0;  ///< late main SERVO outputs refused (stale cycle)
  std::uint32_t window_miss_ppm = 0;       ///< misses per million cycles over the recent window
  std::uint32_t leaky_bucket_score = 0;
  LatencySummary wake_latency{};       ///< CLOCK: actual - scheduled wake-up
  LatencySummary servo_start_delay{};  ///< SERVO start - CLOCK release
  LatencySummary servo_execution{};    ///< SERVO start to finish
  LatencySummary measured_period{};    ///< between consecutive CLOCK wake-ups
  std::uint64_t vpr_torn = 0;          ///< VPr reads that gave up
  std::uint64_t vpr_stale = 0;         ///< cycles run on extrapolated/faded client data
  std::uint64_t vpr_rejected = 0;      ///< VPr samples refused (non-finite, out of range)
  std::uint64_t force_rejected = 0;    ///< force samples rejected (non-finite, out of range)
  std::uint64_t ctrl_accepted = 0;
  std::uint64_t ctrl_rejected = 0;
  /// Benchmark mode (--benchmark-mode): how often, and first at which cycle, a miss rule would
  /// have failed the core safe; always 0 otherwise.
  std::uint64_t would_fail_safe = 0;
  std::uint64_t first_would_fail_safe_cycle = 0;
  /// CLOCK wake latency since start, in the kLatencyBucketEdgesUs bins (offline histograms).
  std::array<std::uint64_t, kLatencyBuckets> wake_histogram{};
};

/// Why the UDP bridge dropped an incoming datagram (index into LinkStatsPayload::dropped).
enum class LinkDrop : std::uint32_t {
  kSize = 0,     ///< truncated, oversized, or not a multiple of 4 bytes
  kMagic,        ///< not a hapticctrl frame
  kVersion,      ///< another major protocol version
  kCrc,          ///< CRC-32 mismatch
  kMalformed,    ///< XDR decoding failed or unknown frame type
  kToken,        ///< no session, wrong session token, or another source address
  kSequence,     ///< replayed or reordered (not newer than the last accepted)
  kRange,        ///< non-finite or out-of-range value
  kUnexpected,   ///< a frame type the bridge never accepts (WELCOME, ANSWER, ...)
  kNotAllowed,   ///< the source address is not on the allow-list (--allow-client)
  kRateLimited,  ///< a HELLO beyond its source's handshake rate (--hello-rate)
  kCount,
};
inline constexpr std::size_t kLinkDropCount = static_cast<std::size_t>(LinkDrop::kCount);
/// Stable short names of LinkDrop values, for telemetry and logs.
inline constexpr std::array<const char*, kLinkDropCount> kLinkDropNames{
    "size",     "magic", "version",    "crc",         "malformed",   "token",
    "sequence", "range", "unexpected", "not_allowed", "rate_limited"};

/// link_stats: the UDP bridge's session and frame counters (written by hapticctrl-udp).
struct LinkStatsPayload {
  std::uint64_t session_id = 0;  ///< current session token's public id (0: no session)
  std::uint32_t peer_ipv4 = 0;   ///< client address (host byte order), 0 without a session
  std::uint32_t peer_port = 0;
  std::uint32_t watchdog_ms = 0;
  std::uint32_t features = 0;    ///< protocol features in use
  std::uint64_t frames_in = 0;   ///< datagrams received
  std::uint64_t frames_out = 0;  ///< datagrams sent
  std::uint64_t control_accepted = 0;
  std::uint64_t params_applied = 0;  ///< PARAM frames applied (duplicates re-acknowledged only)
  std::uint64_t param_duplicates = 0;
  std::uint64_t params_rejected = 0;
  std::uint64_t sessions_opened = 0;
  std::uint64_t sessions_closed = 0;    ///< by BYE
  std::uint64_t watchdog_expiries = 0;  ///< sessions closed because the client fell silent
  std::uint64_t refused_busy = 0;
  std::uint64_t refused_version = 0;
  std::uint64_t send_failures = 0;
  std::array<std::uint64_t, kLinkDropCount> dropped{};
  /// The client link as the bridge measures it (protocol 1.1 timing; 0 for a 1.0 client): the
  /// same figures the bridge puts in VPr for the core and on each answer for the client.
  std::int64_t link_delay_ns = 0;   ///< smoothed one-way delay
  std::int64_t link_jitter_ns = 0;  ///< smoothed |change| of the one-way delay between frames
  std::uint32_t link_loss_ppm = 0;  ///< control frames lost on the way in (smoothed)
  std::uint32_t reserved = 0;
};

// Layout pins: a change here is an ABI change (bump kAbiVersion in layout.hpp).
static_assert(sizeof(ContactSlot) == 160);
static_assert(sizeof(VprPayload) == 1896);
static_assert(sizeof(VpPayload) == 512);
static_assert(sizeof(ForcePayload) == 160);
static_assert(sizeof(PositionPayload) == 360);
static_assert(sizeof(LatencySummary) == 64);
static_assert(sizeof(TelemetryPayload) == 496);
static_assert(sizeof(LinkStatsPayload) == 232);

}  // namespace hapticctrl::shm
