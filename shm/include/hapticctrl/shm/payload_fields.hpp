#pragma once
/// @file payload_fields.hpp
/// Every region payload described once: for each field its name, unit and frame, visited in
/// declaration order by `for_each_field(payload, visitor)`.
///
/// The text forms (payload_text.hpp: CSV and JSON), and through them the LCM log's CSV files, the
/// web page's telemetry and `hapticctrl-hmi status`, are driven by these tables; the tests check
/// that each table names every byte of its struct and that the LCM and DDS mappings carry every
/// field or say why not. Adding a field to a payload: add it here too (the size test fails
/// otherwise), and map it in lcmtypes/ and bridges/dds/ or list it as not published there.
///
/// Real-time contract: not for the cycle (the consumers build strings); the visit itself does
/// nothing but call the visitor.

#include <array>
#include <concepts>
#include <span>
#include <string>
#include <type_traits>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::shm {

/// Names of the components of an array field (its CSV column suffixes).
using PartNames = std::span<const char* const>;
inline constexpr std::array<const char*, 7> kPoseParts{"x", "y", "z", "qx", "qy", "qz", "qw"};
inline constexpr std::array<const char*, 6> kSpatialParts{"x", "y", "z", "rx", "ry", "rz"};
inline constexpr std::array<const char*, 6> kJointParts{"1", "2", "3", "4", "5", "6"};
inline constexpr std::array<const char*, 3> kXyzParts{"x", "y", "z"};
inline constexpr std::array<const char*, 4> kQuaternionParts{"qx", "qy", "qz", "qw"};
inline constexpr std::array<const char*, 4> kGainParts{"k_lin", "b_lin", "k_ang", "b_ang"};
inline constexpr std::array<const char*, 2> kForceTorqueParts{"force", "torque"};
inline constexpr std::array<const char*, 2> kStiffnessDampingParts{"stiffness", "damping"};
inline constexpr std::array<const char*, 2> kStaticDynamicParts{"static", "dynamic"};
/// The wake-latency histogram's bins, from kLatencyBucketEdgesUs.
inline constexpr std::array<const char*, kLatencyBuckets> kLatencyBinParts{
    "0_2us",       "2_5us",        "5_10us",      "10_20us",    "20_50us",
    "50_100us",    "100_200us",    "200_500us",   "500_1000us", "1000_2000us",
    "2000_5000us", "5000_10000us", "10000us_plus"};
static_assert(kLatencyBucketEdgesUs.front() == 2 && kLatencyBucketEdgesUs.back() == 10000,
              "kLatencyBinParts names the bins of these edges");

/// A field as a reader sees it.
struct Field {
  const char* name;   ///< as in the struct
  const char* unit;   ///< SI unit ("" for a count, an index or a bit word); "ipv4": an address
  const char* frame;  ///< "base", "client", "joint" or "" (not spatial)
  PartNames parts;    ///< component names of an array field (empty: indexed from 0)
};

/// The payload types with a table (and the structs nested in them).
template <typename P>
concept Described = std::same_as<P, VprPayload> || std::same_as<P, VpPayload> ||
    std::same_as<P, ForcePayload> || std::same_as<P, PositionPayload> ||
    std::same_as<P, TelemetryPayload> || std::same_as<P, LinkStatsPayload> ||
    std::same_as<P, ContactSlot> || std::same_as<P, HandGrip> || std::same_as<P, LatencySummary>;

/// `P` or `const P`, for a visit that reads or one that writes.
template <typename Q, typename P>
concept Either = std::same_as<std::remove_const_t<Q>, P>;

template <Either<LatencySummary> Q, typename V>
constexpr void for_each_field(Q& s, V&& v) {
  v(Field{"min_ns", "ns", ""}, s.min_ns);
  v(Field{"avg_ns", "ns", ""}, s.avg_ns);
  v(Field{"max_ns", "ns", ""}, s.max_ns);
  v(Field{"p50_ns", "ns", ""}, s.p50_ns);
  v(Field{"p99_ns", "ns", ""}, s.p99_ns);
  v(Field{"p999_ns", "ns", ""}, s.p999_ns);
  v(Field{"samples", "", ""}, s.samples);
  v(Field{"overflows", "", ""}, s.overflows);
}

template <Either<ContactSlot> Q, typename V>
constexpr void for_each_field(Q& c, V&& v) {
  v(Field{"point", "m", "client", kXyzParts}, c.point);
  v(Field{"normal", "", "client", kXyzParts}, c.normal);
  v(Field{"distance", "m", "client"}, c.distance);
  v(Field{"stiffness", "N/m", ""}, c.stiffness);
  v(Field{"damping", "N.s/m", ""}, c.damping);
  v(Field{"friction", "", "", kStaticDynamicParts}, c.friction);
  v(Field{"object_pose", "m, quaternion", "client", kPoseParts}, c.object_pose);
  v(Field{"received_time_ns", "ns", ""}, c.received_time_ns);
  v(Field{"sample_time_ns", "ns", ""}, c.sample_time_ns);
}

template <Either<HandGrip> Q, typename V>
constexpr void for_each_field(Q& h, V&& v) {
  v(Field{"anchor", "m", "base", kXyzParts}, h.anchor);
  v(Field{"anchor_velocity", "m/s", "base", kXyzParts}, h.anchor_velocity);
  v(Field{"stiffness", "N/m", ""}, h.stiffness);
  v(Field{"damping", "N.s/m", ""}, h.damping);
  v(Field{"anchor_rotation", "quaternion", "base", kQuaternionParts}, h.anchor_rotation);
  v(Field{"angular_stiffness", "N.m/rad", ""}, h.angular_stiffness);
  v(Field{"angular_damping", "N.m.s/rad", ""}, h.angular_damping);
}

template <Either<VprPayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"session_id", "", ""}, p.session_id);
  v(Field{"client_sequence", "", ""}, p.client_sequence);
  v(Field{"client_time_ns", "ns", ""}, p.client_time_ns);
  v(Field{"received_time_ns", "ns", ""}, p.received_time_ns);
  v(Field{"sample_time_ns", "ns", ""}, p.sample_time_ns);
  v(Field{"echo_cycle", "", ""}, p.echo_cycle);
  v(Field{"link_delay_ns", "ns", ""}, p.link_delay_ns);
  v(Field{"link_jitter_ns", "ns", ""}, p.link_jitter_ns);
  v(Field{"link_loss_ppm", "ppm", ""}, p.link_loss_ppm);
  v(Field{"client_energy_in", "J", ""}, p.client_energy_in);
  v(Field{"command_type", "", ""}, p.command_type);
  v(Field{"indexing_mode", "", ""}, p.indexing_mode);
  v(Field{"watchdog_timeout_us", "us", ""}, p.watchdog_timeout_us);
  v(Field{"flags", "", ""}, p.flags);
  v(Field{"object_pose", "m, quaternion", "client", kPoseParts}, p.object_pose);
  v(Field{"object_twist", "m/s, rad/s", "client", kSpatialParts}, p.object_twist);
  v(Field{"impedance_wrench", "N, N.m", "client", kSpatialParts}, p.impedance_wrench);
  v(Field{"object_mass", "kg", ""}, p.object_mass);
  v(Field{"object_inertia", "kg.m2", "client", kXyzParts}, p.object_inertia);
  v(Field{"client_time_step", "s", ""}, p.client_time_step);
  v(Field{"force_factor", "", ""}, p.force_factor);
  v(Field{"speed_factor", "", ""}, p.speed_factor);
  v(Field{"base_frame", "m, quaternion", "client", kPoseParts}, p.base_frame);
  v(Field{"observation_frame", "m, quaternion", "client", kPoseParts}, p.observation_frame);
  v(Field{"gain_override", "N/m, N.s/m, N.m/rad, N.m.s/rad", "", kGainParts}, p.gain_override);
  v(Field{"force_limits", "N, N.m", "", kForceTorqueParts}, p.force_limits);
  v(Field{"joint_target", "rad", "joint", kJointParts}, p.joint_target);
  v(Field{"joint_speed", "rad/s", "joint", kJointParts}, p.joint_speed);
  v(Field{"joint_torque", "N.m", "joint", kJointParts}, p.joint_torque);
  v(Field{"contact_count", "", ""}, p.contact_count);
  v(Field{"contact_frames", "", ""}, p.contact_frames);
  v(Field{"contacts", "", "client"}, p.contacts);
}

template <Either<VpPayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"cycle", "", ""}, p.cycle);
  v(Field{"echo_client_sequence", "", ""}, p.echo_client_sequence);
  v(Field{"echo_client_time_ns", "ns", ""}, p.echo_client_time_ns);
  v(Field{"state_word", "", ""}, p.state_word);
  v(Field{"core_state", "", ""}, p.core_state);
  v(Field{"stop_reason", "", ""}, p.stop_reason);
  v(Field{"command_type", "", ""}, p.command_type);
  v(Field{"object_wrench", "N, N.m", "client", kSpatialParts}, p.object_wrench);
  v(Field{"client_handle_pose", "m, quaternion", "client", kPoseParts}, p.client_handle_pose);
  v(Field{"client_handle_twist", "m/s, rad/s", "client", kSpatialParts}, p.client_handle_twist);
  v(Field{"joint_position", "rad", "joint", kJointParts}, p.joint_position);
  v(Field{"joint_velocity", "rad/s", "joint", kJointParts}, p.joint_velocity);
  v(Field{"sample_age_ns", "ns", ""}, p.sample_age_ns);
  v(Field{"loop_delay_ns", "ns", ""}, p.loop_delay_ns);
  v(Field{"gains", "N/m, N.s/m, N.m/rad, N.m.s/rad", "", kGainParts}, p.gains);
  v(Field{"channel_energy_in", "J", ""}, p.channel_energy_in);
  v(Field{"channel_energy_out", "J", ""}, p.channel_energy_out);
  v(Field{"contact_normal", "", "client", kXyzParts}, p.contact_normal);
  v(Field{"normal_gains", "N/m, N.s/m", "", kStiffnessDampingParts}, p.normal_gains);
  v(Field{"limits", "N, N.m", "", kForceTorqueParts}, p.limits);
  v(Field{"max_contact_stiffness", "N/m", ""}, p.max_contact_stiffness);
  v(Field{"contacts", "", ""}, p.contacts);
  v(Field{"contacts_rejected", "", ""}, p.contacts_rejected);
  v(Field{"surface_point", "m", "client", kXyzParts}, p.surface_point);
  v(Field{"surface_normal", "", "client", kXyzParts}, p.surface_normal);
  v(Field{"surface_depth", "m", ""}, p.surface_depth);
  v(Field{"surface_force", "N", ""}, p.surface_force);
  v(Field{"surface_hidden", "m", ""}, p.surface_hidden);
  v(Field{"surface_withheld", "J", ""}, p.surface_withheld);
  v(Field{"contact_age_ns", "ns", ""}, p.contact_age_ns);
}

template <Either<ForcePayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"wrench", "N, N.m", "base", kSpatialParts}, p.wrench);
  v(Field{"hand", "", "base"}, p.hand);
}

template <Either<PositionPayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"cycle", "", ""}, p.cycle);
  v(Field{"state_word", "", ""}, p.state_word);
  v(Field{"core_state", "", ""}, p.core_state);
  v(Field{"joint_position", "rad", "joint", kJointParts}, p.joint_position);
  v(Field{"joint_velocity", "rad/s", "joint", kJointParts}, p.joint_velocity);
  v(Field{"joint_torque", "N.m", "joint", kJointParts}, p.joint_torque);
  v(Field{"handle_pose", "m, quaternion", "base", kPoseParts}, p.handle_pose);
  v(Field{"handle_twist", "m/s, rad/s", "base", kSpatialParts}, p.handle_twist);
  v(Field{"operator_wrench", "N, N.m", "base", kSpatialParts}, p.operator_wrench);
  v(Field{"rendered_wrench", "N, N.m", "base", kSpatialParts}, p.rendered_wrench);
}

template <Either<TelemetryPayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"cycle", "", ""}, p.cycle);
  v(Field{"period_ns", "ns", ""}, p.period_ns);
  v(Field{"rt_mode", "", ""}, p.rt_mode);
  v(Field{"core_state", "", ""}, p.core_state);
  v(Field{"stop_reason", "", ""}, p.stop_reason);
  v(Field{"consecutive_misses", "", ""}, p.consecutive_misses);
  v(Field{"misses_total", "", ""}, p.misses_total);
  v(Field{"degraded_cycles", "", ""}, p.degraded_cycles);
  v(Field{"skipped_slots", "", ""}, p.skipped_slots);
  v(Field{"late_servo_discarded", "", ""}, p.late_servo_discarded);
  v(Field{"window_miss_ppm", "ppm", ""}, p.window_miss_ppm);
  v(Field{"leaky_bucket_score", "", ""}, p.leaky_bucket_score);
  v(Field{"wake_latency", "ns", ""}, p.wake_latency);
  v(Field{"servo_start_delay", "ns", ""}, p.servo_start_delay);
  v(Field{"servo_execution", "ns", ""}, p.servo_execution);
  v(Field{"measured_period", "ns", ""}, p.measured_period);
  v(Field{"vpr_torn", "", ""}, p.vpr_torn);
  v(Field{"vpr_stale", "", ""}, p.vpr_stale);
  v(Field{"vpr_rejected", "", ""}, p.vpr_rejected);
  v(Field{"force_rejected", "", ""}, p.force_rejected);
  v(Field{"ctrl_accepted", "", ""}, p.ctrl_accepted);
  v(Field{"ctrl_rejected", "", ""}, p.ctrl_rejected);
  v(Field{"would_fail_safe", "", ""}, p.would_fail_safe);
  v(Field{"first_would_fail_safe_cycle", "", ""}, p.first_would_fail_safe_cycle);
  v(Field{"wake_histogram", "", "", kLatencyBinParts}, p.wake_histogram);
}

template <Either<LinkStatsPayload> Q, typename V>
constexpr void for_each_field(Q& p, V&& v) {
  v(Field{"session_id", "", ""}, p.session_id);
  v(Field{"peer_ipv4", "ipv4", ""}, p.peer_ipv4);
  v(Field{"peer_port", "", ""}, p.peer_port);
  v(Field{"watchdog_ms", "ms", ""}, p.watchdog_ms);
  v(Field{"features", "", ""}, p.features);
  v(Field{"frames_in", "", ""}, p.frames_in);
  v(Field{"frames_out", "", ""}, p.frames_out);
  v(Field{"control_accepted", "", ""}, p.control_accepted);
  v(Field{"params_applied", "", ""}, p.params_applied);
  v(Field{"param_duplicates", "", ""}, p.param_duplicates);
  v(Field{"params_rejected", "", ""}, p.params_rejected);
  v(Field{"sessions_opened", "", ""}, p.sessions_opened);
  v(Field{"sessions_closed", "", ""}, p.sessions_closed);
  v(Field{"watchdog_expiries", "", ""}, p.watchdog_expiries);
  v(Field{"refused_busy", "", ""}, p.refused_busy);
  v(Field{"refused_version", "", ""}, p.refused_version);
  v(Field{"send_failures", "", ""}, p.send_failures);
  v(Field{"dropped", "", "", kLinkDropNames}, p.dropped);
  v(Field{"link_delay_ns", "ns", ""}, p.link_delay_ns);
  v(Field{"link_jitter_ns", "ns", ""}, p.link_jitter_ns);
  v(Field{"link_loss_ppm", "ppm", ""}, p.link_loss_ppm);
}

/// Whether a field's value is a struct with a table of its own.
template <typename T>
inline constexpr bool kNested = Described<std::remove_const_t<T>>;

/// Every arithmetic value of a payload, nested structs and arrays unrolled: `leaf(column, field,
/// value)` with the column name "<field>_<part>" ("handle_pose_qx", "wake_latency_p99_ns",
/// "contacts_3_point_x") and a reference to the value (const when `p` is). Not for the cycle.
template <typename Q, typename L>
requires Described<std::remove_const_t<Q>>
void for_each_leaf(Q& p, L&& leaf, const std::string& prefix = "");

namespace detail {
inline std::string joined(const std::string& prefix, const char* name) {
  return prefix.empty() ? std::string(name) : prefix + "_" + name;
}
template <typename T, typename L>
void leaf_of(const std::string& column, const Field& f, T& value, L& leaf) {
  if constexpr (kNested<T>) {
    for_each_leaf(value, leaf, column);
  } else if constexpr (std::is_arithmetic_v<std::remove_const_t<T>>) {
    leaf(column, f, value);
  } else {  // std::array of values or of structs
    for (std::size_t i = 0; i < value.size(); ++i) {
      std::string part = column + "_";
      part += i < f.parts.size() ? std::string(f.parts[i]) : std::to_string(i);
      leaf_of(part, f, value[i], leaf);
    }
  }
}
}  // namespace detail

template <typename Q, typename L>
requires Described<std::remove_const_t<Q>>
void for_each_leaf(Q& p, L&& leaf, const std::string& prefix) {
  for_each_field(p, [&](const Field& f, auto& value) {
    detail::leaf_of(detail::joined(prefix, f.name), f, value, leaf);
  });
}

}  // namespace hapticctrl::shm
