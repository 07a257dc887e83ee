// Implements values.hpp: range rules for every number a peer can send.
#include "hapticctrl/protocol/values.hpp"

#include <cmath>

#include "hapticctrl/protocol/timing.hpp"

namespace hapticctrl::protocol {
namespace {

template <typename T, std::size_t N>
bool all_within(const T (&v)[N], double bound) noexcept {  // NOLINT(*-avoid-c-arrays)
  for (const T x : v) {
    if (!std::isfinite(x) || std::abs(static_cast<double>(x)) > bound) {
      return false;
    }
  }
  return true;
}

bool within(double x, double lo, double hi) noexcept {
  return std::isfinite(x) && x >= lo && x <= hi;
}

}  // namespace

template <typename T>
Problem check_pose(const T (&pose)[7]) noexcept {  // NOLINT(*-avoid-c-arrays)
  if (!all_within(pose, kMaxPosition)) {
    return "pose: every value must be finite and within 100 m";
  }
  double norm_sq = 0.0;
  for (int i = 3; i < 7; ++i) {
    norm_sq += static_cast<double>(pose[i]) * static_cast<double>(pose[i]);
  }
  if (std::abs(norm_sq - 1.0) > kMaxQuaternionError) {
    return "pose: the quaternion {qx, qy, qz, qw} must have unit norm";
  }
  return std::nullopt;
}
template Problem check_pose<float>(const float (&)[7]) noexcept;    // NOLINT(*-avoid-c-arrays)
template Problem check_pose<double>(const double (&)[7]) noexcept;  // NOLINT(*-avoid-c-arrays)

Problem check_twist(const float (&t)[6]) noexcept {  // NOLINT(*-avoid-c-arrays)
  for (int i = 0; i < 6; ++i) {
    const double bound = i < 3 ? kMaxLinearSpeed : kMaxAngularSpeed;
    if (!std::isfinite(t[i]) || std::abs(static_cast<double>(t[i])) > bound) {
      return "twist: finite, within 100 m/s and 1000 rad/s";
    }
  }
  return std::nullopt;
}

Problem check_control(const hcp_body& body) noexcept {
  if (body.type == HCP_CONTROL_OBJECT) {
    const hcp_control_object& o = body.hcp_body_u.object;
    if (auto p = check_pose(o.pose)) {
      return p;
    }
    return check_twist(o.twist);
  }
  if (body.type == HCP_CONTROL_OBJECT_TIMED) {
    const hcp_control_object_timed& o = body.hcp_body_u.timed;
    if (!all_within(o.position, kMaxPosition)) {
      return "pose: every value must be finite and within 100 m";
    }
    if (!unpack_rotation({o.rotation[0], o.rotation[1]})) {
      return "pose: the packed rotation is not a unit quaternion";
    }
    return check_twist(o.twist);
  }
  if (body.type == HCP_CONTROL_WRENCH) {
    if (!all_within(body.hcp_body_u.wrench.wrench, kMaxWrench)) {
      return "wrench: finite, within 1000 N and 1000 N.m";
    }
  }
  if (body.type == HCP_CONTROL_WRENCH_TIMED) {
    if (!all_within(body.hcp_body_u.wrench_timed.wrench, kMaxWrench)) {
      return "wrench: finite, within 1000 N and 1000 N.m";
    }
  }
  if (body.type == HCP_CONTROL_CONTACT) {
    return check_contact(body.hcp_body_u.contact);
  }
  if (body.type == HCP_CONTROL_JOINT_TARGET) {
    const hcp_control_joint_target& t = body.hcp_body_u.joint_target;
    if (!all_within(t.position, kMaxJointAngle) || !all_within(t.speed, kMaxJointSpeed)) {
      return "joint target: finite, within 10 rad and 100 rad/s";
    }
  }
  if (body.type == HCP_CONTROL_JOINT_TORQUE &&
      !all_within(body.hcp_body_u.joint_torque.torque, kMaxJointTorque)) {
    return "joint torque: finite, within 1000 N.m";
  }
  return std::nullopt;
}

ContactSlots contact_slots(std::uint32_t word) noexcept {
  return {word & 0xFU, (word >> 8U) & 0xFU};
}

std::uint32_t pack_contact_slots(std::uint32_t slot, std::uint32_t count) noexcept {
  return (slot & 0xFU) | ((count & 0xFU) << 8U);
}

Problem check_contact(const hcp_control_contact& frame) noexcept {
  const ContactSlots s = contact_slots(frame.slots);
  if ((frame.slots & ~0xF0FU) != 0 || s.count > HCP_MAX_CONTACTS ||
      (s.count > 0 && s.slot >= s.count)) {
    return "contact: slot 0-7 below a count of 0-8, other bits 0";
  }
  if (s.count == 0) {
    return std::nullopt;  // clears every slot: the contact is not looked at
  }
  const hcp_contact& c = frame.contact;
  if (!all_within(c.point, kMaxPosition) ||
      !within(static_cast<double>(c.distance), -kMaxContactDistance, kMaxContactDistance)) {
    return "contact: point within 100 m, distance within 1 m";
  }
  double norm_sq = 0.0;
  for (const float n : c.normal) {
    norm_sq += static_cast<double>(n) * static_cast<double>(n);
  }
  if (!(std::abs(norm_sq - 1.0) <= kMaxQuaternionError)) {
    return "contact: the normal must be a unit vector";
  }
  if (!within(static_cast<double>(c.stiffness), kMinContactStiffness, kMaxGain) ||
      !within(static_cast<double>(c.damping), 0.0, kMaxGain)) {
    return "contact: stiffness 1 to 1e6 N/m, damping 0 to 1e6 N.s/m";
  }
  const auto static_friction = static_cast<double>(c.friction[0]);
  if (!within(static_friction, 0.0, kMaxFriction) ||
      !within(static_cast<double>(c.friction[1]), 0.0, static_friction)) {
    return "contact: friction 0 to 10, the dynamic one at most the static one";
  }
  return std::nullopt;
}

Problem check_param(const hcp_param& param) noexcept {
  const auto& u = param.hcp_param_u;
  switch (param.id) {
    case HCP_P_TIME_STEP:
      return within(u.time_step, kMinTimeStep, kMaxTimeStep)
                 ? Problem{}
                 : Problem{"time step: between 1e-5 and 1 s"};
    case HCP_P_FORCE_FACTOR:
      return within(u.force_factor, kMinFactor, kMaxFactor)
                 ? Problem{}
                 : Problem{"force factor: between 0.001 and 1000"};
    case HCP_P_SPEED_FACTOR:
      return within(u.speed_factor, kMinFactor, kMaxFactor)
                 ? Problem{}
                 : Problem{"speed factor: between 0.001 and 1000"};
    case HCP_P_BASE_FRAME:
      return check_pose(u.base_frame);
    case HCP_P_OBSERVATION_FRAME:
      return check_pose(u.observation_frame);
    case HCP_P_BASE_FRAME_SP:
      return check_pose(u.base_frame_sp);
    case HCP_P_OBSERVATION_FRAME_SP:
      return check_pose(u.observation_frame_sp);
    case HCP_P_INDEXING_MODE:
      return u.indexing_mode <= kMaxIndexingMode && u.indexing_mode != kNotAnIndexingMode
                 ? Problem{}
                 : Problem{"indexing mode: 0 to 4, 6 or 7 (VirtuoseAPI's)"};
    case HCP_P_COMMAND_TYPE:
      return u.command_type <= kMaxCommandType
                 ? Problem{}
                 : Problem{
                       "command type: NONE (0), IMPEDANCE (1), VIRTMECH (2), ARTICULAR (3) "
                       "or ARTICULAR_IMPEDANCE (4)"};
    case HCP_P_OBJECT:
      return within(u.object.mass, 0.0, kMaxMass) && all_within(u.object.inertia, kMaxInertia) &&
                     u.object.inertia[0] >= 0.0 && u.object.inertia[1] >= 0.0 &&
                     u.object.inertia[2] >= 0.0
                 ? Problem{}
                 : Problem{"object: mass 0 to 1000 kg, inertia 0 to 1000 kg.m^2"};
    case HCP_P_GAINS:
      for (const double g : u.gains) {
        if (!within(g, 0.0, kMaxGain)) {
          return "gains: each 0 (derived) to 1e6";
        }
      }
      return std::nullopt;
    case HCP_P_FORCE_LIMITS:
      return within(u.force_limits[0], 0.0, kMaxForceLimit) &&
                     within(u.force_limits[1], 0.0, kMaxForceLimit)
                 ? Problem{}
                 : Problem{"force limits: 0 (the device's) to 1e4"};
    case HCP_P_WATCHDOG:
      return u.watchdog_ms >= kMinWatchdogMs && u.watchdog_ms <= kMaxWatchdogMs
                 ? Problem{}
                 : Problem{"watchdog: 10 to 60000 ms"};
    case HCP_P_POWER:
    case HCP_P_EMERGENCY_STOP:
    case HCP_P_EMERGENCY_RESET:
      return std::nullopt;
  }
  return "unknown parameter";
}

Problem check_hello(const hcp_hello& hello) noexcept {
  if (hello.watchdog_ms != 0 &&
      (hello.watchdog_ms < kMinWatchdogMs || hello.watchdog_ms > kMaxWatchdogMs)) {
    return "watchdog: 0 (default) or 10 to 60000 ms";
  }
  return std::nullopt;
}

Problem check_answer(const hcp_answer& a) noexcept {
  const bool finite =
      all_within(a.coupling_wrench, kMaxWrench) && all_within(a.handle_pose, kMaxPosition) &&
      all_within(a.handle_twist, kMaxAngularSpeed) && all_within(a.joint_position, kMaxPosition) &&
      all_within(a.joint_velocity, kMaxAngularSpeed);
  return finite ? Problem{} : Problem{"answer: non-finite or out-of-range state"};
}

Problem check_coupling_report(const hcp_coupling_report& c) noexcept {
  const bool ok = within(c.energy_in, 0.0, kMaxEnergy) && within(c.sample_age_s, -1.0, 1e3) &&
                  within(c.loop_delay_s, 0.0, 1e3) && within(c.link_delay_s, 0.0, 1e3) &&
                  within(c.link_jitter_s, 0.0, 1e3) && within(c.link_loss, 0.0, 1.0) &&
                  all_within(c.gains, kMaxGain) && c.gains[0] >= 0.0 && c.gains[1] >= 0.0 &&
                  c.gains[2] >= 0.0 && c.gains[3] >= 0.0;
  return ok ? Problem{} : Problem{"answer: coupling report non-finite or out of range"};
}

Problem check_local_coupling(const hcp_local_coupling& l) noexcept {
  const bool ok = all_within(l.contact_normal, 1.0 + kMaxQuaternionError) &&
                  within(l.normal_gains[0], 0.0, kMaxGain) &&
                  within(l.normal_gains[1], 0.0, kMaxGain) && within(l.limits[0], 0.0, kMaxGain) &&
                  within(l.limits[1], 0.0, kMaxGain) &&
                  within(l.max_contact_stiffness, 0.0, kMaxGain) && l.contacts <= HCP_MAX_CONTACTS;
  return ok ? Problem{} : Problem{"answer: local coupling non-finite or out of range"};
}

Problem check_body(const hcp_body& body) noexcept {
  switch (body.type) {
    case HCP_CONTROL_OBJECT:
    case HCP_CONTROL_OBJECT_TIMED:
    case HCP_CONTROL_WRENCH:
    case HCP_CONTROL_WRENCH_TIMED:
    case HCP_CONTROL_CONTACT:
    case HCP_CONTROL_JOINT_TARGET:
    case HCP_CONTROL_JOINT_TORQUE:
      return check_control(body);
    case HCP_PARAM:
      return check_param(body.hcp_body_u.param);
    case HCP_HELLO:
      return check_hello(body.hcp_body_u.hello);
    case HCP_ANSWER:
      return check_answer(body.hcp_body_u.answer);
    case HCP_ANSWER_TIMED:
      if (auto p = check_answer(body.hcp_body_u.answer_timed.answer)) {
        return p;
      }
      return check_coupling_report(body.hcp_body_u.answer_timed.coupling);
    case HCP_ANSWER_COUPLED:
      if (auto p = check_answer(body.hcp_body_u.answer_coupled.answer)) {
        return p;
      }
      if (auto p = check_coupling_report(body.hcp_body_u.answer_coupled.coupling)) {
        return p;
      }
      return check_local_coupling(body.hcp_body_u.answer_coupled.local);
    default:
      return std::nullopt;
  }
}

}  // namespace hapticctrl::protocol
