// Implements parameter_channel.hpp: the order of a session's PARAM frames and what each does.
#include "hapticctrl/udp_bridge/parameter_channel.hpp"

#include <algorithm>

#include "hapticctrl/protocol/values.hpp"

namespace hapticctrl::udp_bridge {

ParameterChannel::Step ParameterChannel::step_for(std::uint32_t sequence) const noexcept {
  if (!have_sequence_) {
    return Step::kApply;
  }
  if (sequence == last_.sequence) {
    return Step::kReplay;
  }
  return protocol::sequence_newer(sequence, last_.sequence) ? Step::kApply : Step::kStale;
}

void ParameterChannel::record(const ParamAck& ack) noexcept {
  if (ack.status == HCP_ACK_RETRY) {
    return;
  }
  last_ = ack;
  have_sequence_ = true;
}

const char* missing_feature(const hcp_param& param, std::uint32_t features) noexcept {
  const bool joint_mode = param.id == HCP_P_COMMAND_TYPE &&
                          (param.hcp_param_u.command_type == HCP_COMMAND_ARTICULAR ||
                           param.hcp_param_u.command_type == HCP_COMMAND_ARTICULAR_IMPEDANCE);
  if (joint_mode && (features & HCP_FEATURE_JOINT_CONTROL) == 0) {
    return "command type ARTICULAR and ARTICULAR_IMPEDANCE need protocol 1.4 (the session did "
           "not negotiate JOINT_CONTROL)";
  }
  return nullptr;
}

namespace {

void set_command_type(std::uint32_t type, shm::VprPayload& vpr) noexcept {
  if (vpr.command_type != type) {
    // The joint fields of the mode before are not a command of this one (vpr_flags).
    vpr.flags &= ~shm::vpr_flags::kJointCommand;
    vpr.joint_target = {};
    vpr.joint_speed = {};
    vpr.joint_torque = {};
  }
  vpr.command_type = type;
}

void set_object(const hcp_object& object, shm::VprPayload& vpr) noexcept {
  vpr.flags = object.attached != 0 ? (vpr.flags | shm::vpr_flags::kObjectAttached)
                                   : (vpr.flags & ~shm::vpr_flags::kObjectAttached);
  vpr.object_mass = object.mass;
  protocol::from_wire(object.inertia, vpr.object_inertia);
}

}  // namespace

ParamEffect apply_param(const hcp_param& param, std::uint32_t max_watchdog_ms, shm::VprPayload& vpr,
                        std::uint32_t& watchdog_ms) noexcept {
  const auto& u = param.hcp_param_u;
  switch (param.id) {
    case HCP_P_TIME_STEP:
      vpr.client_time_step = u.time_step;
      break;
    case HCP_P_FORCE_FACTOR:
      vpr.force_factor = u.force_factor;
      break;
    case HCP_P_SPEED_FACTOR:
      vpr.speed_factor = u.speed_factor;
      break;
    case HCP_P_BASE_FRAME:
      protocol::from_wire(u.base_frame, vpr.base_frame);
      break;
    case HCP_P_OBSERVATION_FRAME:
      protocol::from_wire(u.observation_frame, vpr.observation_frame);
      break;
    case HCP_P_BASE_FRAME_SP:
      protocol::from_wire(u.base_frame_sp, vpr.base_frame);
      break;
    case HCP_P_OBSERVATION_FRAME_SP:
      protocol::from_wire(u.observation_frame_sp, vpr.observation_frame);
      break;
    case HCP_P_INDEXING_MODE:
      vpr.indexing_mode = u.indexing_mode;
      break;
    case HCP_P_COMMAND_TYPE:
      set_command_type(u.command_type, vpr);
      break;
    case HCP_P_OBJECT:
      set_object(u.object, vpr);
      break;
    case HCP_P_GAINS:
      protocol::from_wire(u.gains, vpr.gain_override);
      break;
    case HCP_P_FORCE_LIMITS:
      protocol::from_wire(u.force_limits, vpr.force_limits);
      break;
    case HCP_P_WATCHDOG:
      watchdog_ms = std::min(u.watchdog_ms, max_watchdog_ms);
      vpr.watchdog_timeout_us = watchdog_ms * 1000U;
      break;
    case HCP_P_POWER:
      // A client's power-on is refused after a restart from a fault (J8): the core tells.
      return u.power_on != 0 ? ParamEffect{shm::CtrlCode::kPowerOn, shm::kPowerOnByClient}
                             : ParamEffect{shm::CtrlCode::kPowerOff, 0};
    case HCP_P_EMERGENCY_STOP:
      return {shm::CtrlCode::kEmergencyStop, 0};
    case HCP_P_EMERGENCY_RESET:
      return {shm::CtrlCode::kEmergencyReset, 0};
  }
  return {};
}

}  // namespace hapticctrl::udp_bridge
