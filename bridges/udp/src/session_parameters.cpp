// The UDP bridge's parameter frames (Session::on_param, apply, ack): each PARAM applied once
// (into VPr or a ctrl command) and acknowledged, a retransmission acknowledged again.
#include <algorithm>

#include "hapticctrl/protocol/values.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace hapticctrl::udp_bridge {

using shm::LinkDrop;

namespace {

/// The joint-space command types need protocol 1.4's JOINT_CONTROL.
bool needs_joint_control(const hcp_param& p) noexcept {
  return p.id == HCP_P_COMMAND_TYPE &&
         (p.hcp_param_u.command_type == HCP_COMMAND_ARTICULAR ||
          p.hcp_param_u.command_type == HCP_COMMAND_ARTICULAR_IMPEDANCE);
}

}  // namespace

std::size_t Session::on_param(const hcp_frame& in, bool values_ok, TimeNs now,
                              std::span<std::uint8_t> reply) noexcept {
  const std::uint32_t seq = in.header.sequence;
  last_heard_ = now;
  engaged_ = true;
  if (have_param_seq_ && seq == last_ack_.sequence) {  // our ACK was lost: say it again
    counters_.param_duplicates.fetch_add(1, std::memory_order_relaxed);
    return ack(last_ack_, now, reply);
  }
  if (have_param_seq_ && !protocol::sequence_newer(seq, last_ack_.sequence)) {
    counters_.drop(LinkDrop::kSequence);
    return 0;
  }
  LastAck result{seq, HCP_ACK_OK};
  if (!values_ok) {
    counters_.drop(LinkDrop::kRange);
    counters_.params_rejected.fetch_add(1, std::memory_order_relaxed);
    result.status = HCP_ACK_REJECTED;
    const auto problem = protocol::check_param(in.body.hcp_body_u.param);
    protocol::set_text(result.reason, problem.value_or("value out of range"));
  } else if (needs_joint_control(in.body.hcp_body_u.param) &&
             (session_.features & HCP_FEATURE_JOINT_CONTROL) == 0) {
    counters_.params_rejected.fetch_add(1, std::memory_order_relaxed);
    result.status = HCP_ACK_REJECTED;
    protocol::set_text(result.reason,
                       "command type ARTICULAR and ARTICULAR_IMPEDANCE need protocol 1.4 (the "
                       "session did not negotiate JOINT_CONTROL)");
  } else {
    result.status = apply(in.body.hcp_body_u.param, now);
    if (result.status == HCP_ACK_RETRY) {
      return ack(result, now, reply);  // not applied, not recorded: the retransmission applies
    }
    counters_.params_applied.fetch_add(1, std::memory_order_relaxed);
  }
  last_ack_ = result;
  have_param_seq_ = true;
  return ack(last_ack_, now, reply);
}

hcp_ack_status Session::apply(const hcp_param& param, TimeNs now) noexcept {
  const auto& u = param.hcp_param_u;
  shm::CtrlCode ctrl = shm::CtrlCode::kNone;
  std::uint32_t arg = 0;
  switch (param.id) {
    case HCP_P_TIME_STEP:
      vpr_.client_time_step = u.time_step;
      break;
    case HCP_P_FORCE_FACTOR:
      vpr_.force_factor = u.force_factor;
      break;
    case HCP_P_SPEED_FACTOR:
      vpr_.speed_factor = u.speed_factor;
      break;
    case HCP_P_BASE_FRAME:
      protocol::from_wire(u.base_frame, vpr_.base_frame);
      break;
    case HCP_P_OBSERVATION_FRAME:
      protocol::from_wire(u.observation_frame, vpr_.observation_frame);
      break;
    case HCP_P_BASE_FRAME_SP:
      protocol::from_wire(u.base_frame_sp, vpr_.base_frame);
      break;
    case HCP_P_OBSERVATION_FRAME_SP:
      protocol::from_wire(u.observation_frame_sp, vpr_.observation_frame);
      break;
    case HCP_P_INDEXING_MODE:
      vpr_.indexing_mode = u.indexing_mode;
      break;
    case HCP_P_COMMAND_TYPE:
      if (vpr_.command_type != u.command_type) {
        // The joint fields of the mode before are not a command of this one (vpr_flags).
        vpr_.flags &= ~shm::vpr_flags::kJointCommand;
        vpr_.joint_target = {};
        vpr_.joint_speed = {};
        vpr_.joint_torque = {};
      }
      vpr_.command_type = u.command_type;
      break;
    case HCP_P_OBJECT:
      vpr_.flags = u.object.attached != 0 ? (vpr_.flags | shm::vpr_flags::kObjectAttached)
                                          : (vpr_.flags & ~shm::vpr_flags::kObjectAttached);
      vpr_.object_mass = u.object.mass;
      protocol::from_wire(u.object.inertia, vpr_.object_inertia);
      break;
    case HCP_P_GAINS:
      protocol::from_wire(u.gains, vpr_.gain_override);
      break;
    case HCP_P_FORCE_LIMITS:
      protocol::from_wire(u.force_limits, vpr_.force_limits);
      break;
    case HCP_P_WATCHDOG:
      watchdog_ms_ = std::min(u.watchdog_ms, settings_.max_watchdog_ms);
      vpr_.watchdog_timeout_us = watchdog_ms_ * 1000U;
      break;
    case HCP_P_POWER:
      ctrl = u.power_on != 0 ? shm::CtrlCode::kPowerOn : shm::CtrlCode::kPowerOff;
      arg = u.power_on != 0 ? shm::kPowerOnByClient : 0;  // refused after a restart (J8)
      break;
    case HCP_P_EMERGENCY_STOP:
      ctrl = shm::CtrlCode::kEmergencyStop;
      break;
    case HCP_P_EMERGENCY_RESET:
      ctrl = shm::CtrlCode::kEmergencyReset;
      break;
  }
  if (ctrl != shm::CtrlCode::kNone) {
    if (ports_.ctrl == nullptr ||
        ports_.ctrl->send(ctrl, arg, now) != shm::CtrlSendStatus::kQueued) {
      return HCP_ACK_RETRY;
    }
    return HCP_ACK_OK;
  }
  publish_vpr(now);
  return HCP_ACK_OK;
}

std::size_t Session::ack(const LastAck& result, TimeNs now,
                         std::span<std::uint8_t> reply) noexcept {
  hcp_frame out = protocol::make_frame(HCP_ACK, session_.token, ++reply_sequence_, now);
  hcp_ack& a = out.body.hcp_body_u.ack;
  a.acked_sequence = result.sequence;
  a.status = result.status;
  std::copy(std::begin(result.reason), std::end(result.reason), std::begin(a.reason));
  return protocol::encode(out, reply);
}

}  // namespace hapticctrl::udp_bridge
