#pragma once
/// @file values.hpp
/// Range rules for every number a peer can send. One set of rules, used by the client library
/// (to refuse a bad call with a clear exception before sending) and by the bridge (to drop or
/// refuse what arrives). Each check returns nothing when the values are acceptable, otherwise a
/// static text naming the field and its range.
///
/// Real-time contract: pure functions, no allocation; safe in a cycle.
#include <cstdint>
#include <optional>
#include <string_view>

#include "hapticctrl_protocol.h"

namespace hapticctrl::protocol {

using Problem = std::optional<std::string_view>;

inline constexpr double kMaxPosition = 100.0;        ///< m, any pose coordinate
inline constexpr double kMaxQuaternionError = 0.02;  ///< allowed | |q|^2 - 1 |
inline constexpr double kMaxLinearSpeed = 100.0;     ///< m/s per component
inline constexpr double kMaxAngularSpeed = 1000.0;   ///< rad/s per component
inline constexpr double kMaxWrench = 1000.0;         ///< N or N.m per component
inline constexpr double kMinTimeStep = 1e-5;         ///< s
inline constexpr double kMaxTimeStep = 1.0;          ///< s
inline constexpr double kMinFactor = 1e-3;
inline constexpr double kMaxFactor = 1e3;
/// VirtuoseAPI's seven indexing modes are 0-4, 6 and 7 (5 is not one of them).
inline constexpr unsigned kMaxIndexingMode = 7;
inline constexpr unsigned kNotAnIndexingMode = 5;
/// NONE, IMPEDANCE, VIRTMECH, and with protocol 1.4's JOINT_CONTROL ARTICULAR and
/// ARTICULAR_IMPEDANCE (the bridge refuses those two in a session without the feature).
inline constexpr unsigned kMaxCommandType = HCP_COMMAND_ARTICULAR_IMPEDANCE;
inline constexpr double kMaxMass = 1000.0;     ///< kg
inline constexpr double kMaxInertia = 1000.0;  ///< kg.m^2
inline constexpr double kMaxGain = 1e6;
inline constexpr double kMaxForceLimit = 1e4;
inline constexpr double kMaxEnergy = 1e12;           ///< J, a coupling channel's cumulative energy
inline constexpr double kMaxContactDistance = 1.0;   ///< m, |gap| of a contact
inline constexpr double kMaxJointAngle = 10.0;       ///< rad, a joint set point (any joint's range)
inline constexpr double kMaxJointSpeed = 100.0;      ///< rad/s, a joint speed
inline constexpr double kMaxJointTorque = 1000.0;    ///< N.m, a joint torque
inline constexpr double kMinContactStiffness = 1.0;  ///< N/m
inline constexpr double kMaxFriction = 10.0;         ///< Coulomb coefficient
inline constexpr unsigned kMinWatchdogMs = 10;
inline constexpr unsigned kMaxWatchdogMs = 60000;

/// A pose {x, y, z, qx, qy, qz, qw}: finite, within kMaxPosition, unit quaternion.
template <typename T>
[[nodiscard]] Problem check_pose(const T (&pose)[7]) noexcept;  // NOLINT(*-avoid-c-arrays)

/// A twist: finite, within kMaxLinearSpeed and kMaxAngularSpeed per component.
[[nodiscard]] Problem check_twist(const float (&twist)[6]) noexcept;  // NOLINT(*-avoid-c-arrays)
/// CONTROL_OBJECT, CONTROL_OBJECT_TIMED (position, packed rotation, twist), CONTROL_WRENCH(_TIMED),
/// CONTROL_CONTACT, CONTROL_JOINT_TARGET or CONTROL_JOINT_TORQUE.
[[nodiscard]] Problem check_control(const hcp_body& body) noexcept;

/// A CONTROL_CONTACT's slot word: this contact's slot and how many slots are in use.
struct ContactSlots {
  std::uint32_t slot = 0;
  std::uint32_t count = 0;
};
[[nodiscard]] ContactSlots contact_slots(std::uint32_t word) noexcept;
[[nodiscard]] std::uint32_t pack_contact_slots(std::uint32_t slot, std::uint32_t count) noexcept;
/// CONTROL_CONTACT: a slot below the count (or a count of 0, which clears every slot), a point
/// within kMaxPosition, a unit normal (+-2 %), a gap within kMaxContactDistance, stiffness
/// kMinContactStiffness..kMaxGain, damping 0..kMaxGain, friction 0..kMaxFriction with the
/// dynamic coefficient at most the static one. The controller's own stiffness limit is its check.
[[nodiscard]] Problem check_contact(const hcp_control_contact& frame) noexcept;
[[nodiscard]] Problem check_param(const hcp_param& param) noexcept;
[[nodiscard]] Problem check_hello(const hcp_hello& hello) noexcept;
[[nodiscard]] Problem check_answer(const hcp_answer& answer) noexcept;
[[nodiscard]] Problem check_coupling_report(const hcp_coupling_report& report) noexcept;
[[nodiscard]] Problem check_local_coupling(const hcp_local_coupling& local) noexcept;

/// Dispatches on the body's type: the rules above, or none for bodies without numbers.
[[nodiscard]] Problem check_body(const hcp_body& body) noexcept;

}  // namespace hapticctrl::protocol
