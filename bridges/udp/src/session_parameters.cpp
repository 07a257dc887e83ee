// The UDP bridge's parameter frames (Session::on_param, take_param, ack): the parameter channel
// orders them, apply_param says what each does; the session sends its ctrl command, publishes
// VPr and acknowledges.
#include <algorithm>

#include "hapticctrl/protocol/values.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace hapticctrl::udp_bridge {

using shm::LinkDrop;

std::size_t Session::on_param(const hcp_frame& in, bool values_ok, TimePoint now,
                              std::span<std::uint8_t> reply) noexcept {
  const std::uint32_t seq = in.header.sequence;
  last_heard_ = now;
  engaged_ = true;
  switch (params_.step_for(seq)) {
    case ParameterChannel::Step::kReplay:  // our ACK was lost: say it again
      counters_.param_duplicates.fetch_add(1, std::memory_order_relaxed);
      return ack(params_.last(), now, reply);
    case ParameterChannel::Step::kStale:
      counters_.drop(LinkDrop::kSequence);
      return 0;
    case ParameterChannel::Step::kApply:
      break;
  }
  ParamAck result{seq, HCP_ACK_REJECTED};
  if (!values_ok) {
    counters_.drop(LinkDrop::kRange);
    counters_.params_rejected.fetch_add(1, std::memory_order_relaxed);
    const auto problem = protocol::check_param(in.body.hcp_body_u.param);
    protocol::set_text(result.reason, problem.value_or("value out of range"));
  } else if (const char* missing = missing_feature(in.body.hcp_body_u.param, session_.features)) {
    counters_.params_rejected.fetch_add(1, std::memory_order_relaxed);
    protocol::set_text(result.reason, missing);
  } else {
    result = take_param(in.body.hcp_body_u.param, seq, now);
  }
  params_.record(result);  // not a RETRY: the retransmission applies
  return ack(result, now, reply);
}

ParamAck Session::take_param(const hcp_param& param, std::uint32_t sequence,
                             TimePoint now) noexcept {
  const ParamEffect effect = apply_param(param, settings_.max_watchdog_ms, vpr_, watchdog_ms_);
  if (effect.ctrl == shm::CtrlCode::kNone) {
    publish_vpr(now);
  } else if (ports_.ctrl == nullptr ||
             ports_.ctrl->send(effect.ctrl, effect.ctrl_arg, to_ns(now)) !=
                 shm::CtrlSendStatus::kQueued) {
    return {sequence, HCP_ACK_RETRY};
  }
  counters_.params_applied.fetch_add(1, std::memory_order_relaxed);
  return {sequence, HCP_ACK_OK};
}

std::size_t Session::ack(const ParamAck& result, TimePoint now,
                         std::span<std::uint8_t> reply) noexcept {
  hcp_frame out = protocol::make_frame(HCP_ACK, session_.token, ++reply_sequence_, to_ns(now));
  hcp_ack& a = out.body.hcp_body_u.ack;
  a.acked_sequence = result.sequence;
  a.status = result.status;
  std::copy(std::begin(result.reason), std::end(result.reason), std::begin(a.reason));
  return protocol::encode(out, reply);
}

}  // namespace hapticctrl::udp_bridge
