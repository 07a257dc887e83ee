// The UDP bridge's answer side (Session::answer, fill_stats): the answer frame for each VP
// sample, read from the answer thread through the session view's seqlock, and the link
// statistics.
#include <algorithm>

#include "hapticctrl/protocol/values.hpp"
#include "hapticctrl/udp_bridge/session.hpp"

namespace hapticctrl::udp_bridge {
namespace {

/// The coupling as the core ran it (VP) and the link as this bridge measures it.
void fill_report(const shm::VpPayload& vp, const LinkFigures& link,
                 hcp_coupling_report& c) noexcept {
  c.energy_in = vp.channel_energy_in;
  c.sample_age_s = static_cast<double>(vp.sample_age_ns) * 1e-9;
  c.loop_delay_s = static_cast<double>(vp.loop_delay_ns) * 1e-9;
  c.link_delay_s = to_seconds(link.delay);
  c.link_jitter_s = to_seconds(link.jitter);
  c.link_loss = static_cast<double>(link.loss_ppm) * 1e-6;
  protocol::to_wire(vp.gains, c.gains);
}

}  // namespace

std::size_t Session::answer(const shm::VpPayload& vp, TimePoint now, std::span<std::uint8_t> out,
                            protocol::Endpoint& to) noexcept {
  SessionView view;
  if (!view_.read(view).ok() || view.token == 0) {
    return 0;
  }
  to = view.peer;
  answer_log_.record(vp.cycle, now);
  const bool timed = (view.features & HCP_FEATURE_TIMING) != 0;
  const bool coupled = timed && (view.features & HCP_FEATURE_LOCAL_COUPLING) != 0;
  const hcp_frame_type type = coupled ? HCP_ANSWER_COUPLED : timed ? HCP_ANSWER_TIMED : HCP_ANSWER;
  hcp_frame f = protocol::make_frame(type, view.token, ++answer_sequence_, to_ns(now));
  auto& u = f.body.hcp_body_u;
  hcp_answer& a = coupled ? u.answer_coupled.answer : (timed ? u.answer_timed.answer : u.answer);
  if (timed) {
    // Unchanged when the receive thread is mid-write (the read then leaves it as it was).
    (void)link_view_.read(link_answered_);
    fill_report(vp, link_answered_, coupled ? u.answer_coupled.coupling : u.answer_timed.coupling);
  }
  if (coupled) {
    hcp_local_coupling& l = u.answer_coupled.local;
    protocol::to_wire(vp.contact_normal, l.contact_normal);
    protocol::to_wire(vp.normal_gains, l.normal_gains);
    protocol::to_wire(vp.limits, l.limits);
    l.max_contact_stiffness = vp.max_contact_stiffness;
    l.contacts = vp.contacts;
    l.contacts_rejected = vp.contacts_rejected;
  }
  a.cycle = vp.cycle;
  a.echo_sequence = static_cast<std::uint32_t>(vp.echo_client_sequence);
  a.echo_time_ns = vp.echo_client_time_ns;
  a.state_word = vp.state_word;
  a.core_state = vp.core_state;
  a.stop_reason = vp.stop_reason;
  a.command_type = vp.command_type;
  if ((view.features & HCP_FEATURE_LINK_STATS) != 0) {
    a.control_received = control_received_shared_.load(std::memory_order_relaxed);
  }
  protocol::to_wire(vp.object_wrench, a.coupling_wrench);
  protocol::to_wire(vp.client_handle_pose, a.handle_pose);
  protocol::to_wire(vp.client_handle_twist, a.handle_twist);
  if ((view.features & HCP_FEATURE_JOINT_STATE) != 0) {
    protocol::to_wire(vp.joint_position, a.joint_position);
    protocol::to_wire(vp.joint_velocity, a.joint_velocity);
  }
  return protocol::encode(f, out);
}

void Session::fill_stats(shm::LinkStatsPayload& out) const noexcept {
  const auto get = [](const std::atomic<std::uint64_t>& c) {
    return c.load(std::memory_order_relaxed);
  };
  out.session_id = session_.token != 0 ? session_number_ : 0;
  out.peer_ipv4 = session_.token != 0 ? ntohl(session_.peer.address.sin_addr.s_addr) : 0;
  out.peer_port = session_.token != 0 ? session_.peer.port() : 0;
  out.watchdog_ms = session_.token != 0 ? watchdog_ms_ : 0;
  out.features = session_.features;
  out.frames_in = get(counters_.frames_in);
  out.frames_out = get(counters_.frames_out);
  out.control_accepted = get(counters_.control_accepted);
  out.params_applied = get(counters_.params_applied);
  out.param_duplicates = get(counters_.param_duplicates);
  out.params_rejected = get(counters_.params_rejected);
  out.sessions_opened = get(counters_.sessions_opened);
  out.sessions_closed = get(counters_.sessions_closed);
  out.watchdog_expiries = get(counters_.watchdog_expiries);
  out.refused_busy = get(counters_.refused_busy);
  out.refused_version = get(counters_.refused_version);
  out.send_failures = get(counters_.send_failures);
  for (std::size_t i = 0; i < shm::kLinkDropCount; ++i) {
    out.dropped[i] = get(counters_.dropped[i]);
  }
  const LinkFigures link = session_.token != 0 ? ingest_.link() : LinkFigures{};
  out.link_delay_ns = to_ns(link.delay);
  out.link_jitter_ns = to_ns(link.jitter);
  out.link_loss_ppm = link.loss_ppm;
}

}  // namespace hapticctrl::udp_bridge
