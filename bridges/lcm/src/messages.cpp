// Implements messages.hpp: the coupling and the events as LCM messages.
#include "hapticctrl/lcm_bridge/messages.hpp"

#include <algorithm>

#include "hapticctrl/shm/names.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

template <typename From, typename To, std::size_t N>
void copy(const From& from, To (&to)[N]) {  // NOLINT(*-avoid-c-arrays): lcm-gen's arrays
  std::copy_n(from.begin(), N, to);
}

}  // namespace

hapticctrl_lcm::coupling_t to_coupling(const shm::VpPayload& vp, const shm::VprPayload& vpr,
                                       const shm::TelemetryPayload& t, TimePoint now,
                                       std::int64_t utime) {
  hapticctrl_lcm::coupling_t m{};
  m.utime = utime;
  m.cycle = static_cast<std::int64_t>(vp.cycle);
  m.session_id = static_cast<std::int64_t>(vpr.session_id);
  m.command_type = static_cast<std::int32_t>(vp.command_type);
  m.object_attached = (vpr.flags & shm::vpr_flags::kObjectAttached) != 0 ? 1 : 0;
  copy(vpr.object_pose, m.object_pose);
  copy(vpr.object_twist, m.object_twist);
  copy(vp.object_wrench, m.object_wrench);
  copy(vp.client_handle_pose, m.client_handle_pose);
  m.client_sequence = static_cast<std::int64_t>(vp.echo_client_sequence);
  m.client_age_ms =
      vpr.session_id != 0 ? to_seconds(now - time_point_from_ns(vpr.received_time_ns)) * 1e3 : 0.0;
  m.client_stale = (vp.state_word & shm::state_bits::kClientStale) != 0 ? 1 : 0;
  m.vpr_stale_cycles = static_cast<std::int64_t>(t.vpr_stale);
  m.sample_age_ms = static_cast<double>(vp.sample_age_ns) / 1e6;
  m.loop_delay_ms = static_cast<double>(vp.loop_delay_ns) / 1e6;
  // The link as the UDP bridge measured it for the core's gains (VPr).
  m.link_delay_ms = static_cast<double>(vpr.link_delay_ns) / 1e6;
  m.link_jitter_ms = static_cast<double>(vpr.link_jitter_ns) / 1e6;
  m.link_loss = static_cast<double>(vpr.link_loss_ppm) / 1e6;
  copy(vp.gains, m.gains);
  m.channel_energy_in = vp.channel_energy_in;
  m.channel_energy_out = vp.channel_energy_out;
  m.client_energy_in = vpr.client_energy_in;
  m.contacts = static_cast<std::int32_t>(vp.contacts);
  copy(vp.surface_point, m.surface_point);
  copy(vp.surface_normal, m.surface_normal);
  m.surface_depth_mm = vp.surface_depth * 1e3;
  m.surface_force = vp.surface_force;
  m.surface_hidden_mm = vp.surface_hidden * 1e3;
  m.surface_withheld = vp.surface_withheld;
  m.contact_age_ms = vp.contact_age_ns >= 0 ? static_cast<double>(vp.contact_age_ns) / 1e6 : -1.0;
  return m;
}

hapticctrl_lcm::event_t to_event(const shm::Event& e, std::uint64_t lost_before,
                                 TimePoint monotonic_now, std::int64_t wall_now_us) {
  hapticctrl_lcm::event_t m{};
  m.utime = wall_now_us - (to_ns(monotonic_now) - e.time_ns) / 1000;
  m.index = static_cast<std::int64_t>(e.index);
  m.cycle = static_cast<std::int64_t>(e.cycle);
  m.time_ns = e.time_ns;
  m.kind = shm::event_kind_name(e.kind);
  m.code = static_cast<std::int32_t>(e.code);
  m.value = static_cast<std::int64_t>(e.value);
  m.text = shm::describe_event(e);
  m.lost_before = static_cast<std::int64_t>(lost_before);
  return m;
}

}  // namespace hapticctrl::lcm_bridge
