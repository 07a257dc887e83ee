// Implements messages.hpp: shared-memory payloads to LCM messages (lcmtypes/), and the instance's
// channel names.
#include "hapticctrl/lcm_bridge/messages.hpp"

#include <arpa/inet.h>

#include <algorithm>

#include "hapticctrl/shm/names.hpp"

namespace hapticctrl::lcm_bridge {
namespace {

template <typename From, typename To, std::size_t N>
void copy(const From& from, To (&to)[N]) {  // NOLINT(*-avoid-c-arrays): lcm-gen's arrays
  std::copy_n(from.begin(), N, to);
}

hapticctrl_lcm::latency_t to_latency(const shm::LatencySummary& s) {
  hapticctrl_lcm::latency_t l{};
  l.min_ns = s.min_ns;
  l.avg_ns = s.avg_ns;
  l.max_ns = s.max_ns;
  l.p50_ns = s.p50_ns;
  l.p99_ns = s.p99_ns;
  l.p999_ns = s.p999_ns;
  l.samples = static_cast<std::int64_t>(s.samples);
  l.overflows = static_cast<std::int64_t>(s.overflows);
  return l;
}

}  // namespace

hapticctrl_lcm::arm_state_t to_arm_state(const shm::PositionPayload& p, std::int64_t utime) {
  hapticctrl_lcm::arm_state_t m{};
  m.utime = utime;
  m.cycle = static_cast<std::int64_t>(p.cycle);
  m.state_word = static_cast<std::int32_t>(p.state_word);
  m.core_state = static_cast<std::int32_t>(p.core_state);
  copy(p.joint_position, m.joint_position);
  copy(p.joint_velocity, m.joint_velocity);
  copy(p.joint_torque, m.joint_torque);
  copy(p.handle_pose, m.handle_pose);
  copy(p.handle_twist, m.handle_twist);
  copy(p.operator_wrench, m.operator_wrench);
  copy(p.rendered_wrench, m.rendered_wrench);
  return m;
}

hapticctrl_lcm::coupling_t to_coupling(const shm::VpPayload& vp, const shm::VprPayload& vpr,
                                       const shm::TelemetryPayload& t, std::int64_t now_ns,
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
      vpr.session_id != 0 ? static_cast<double>(now_ns - vpr.received_time_ns) / 1e6 : 0.0;
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

hapticctrl_lcm::cycle_stats_t to_cycle_stats(const shm::TelemetryPayload& t, std::int64_t utime) {
  hapticctrl_lcm::cycle_stats_t m{};
  m.utime = utime;
  m.cycle = static_cast<std::int64_t>(t.cycle);
  m.period_ns = t.period_ns;
  m.rt_mode = static_cast<std::int32_t>(t.rt_mode);
  m.core_state = static_cast<std::int32_t>(t.core_state);
  m.stop_reason = static_cast<std::int32_t>(t.stop_reason);
  m.consecutive_misses = static_cast<std::int32_t>(t.consecutive_misses);
  m.misses_total = static_cast<std::int64_t>(t.misses_total);
  m.degraded_cycles = static_cast<std::int64_t>(t.degraded_cycles);
  m.skipped_slots = static_cast<std::int64_t>(t.skipped_slots);
  m.late_servo_discarded = static_cast<std::int64_t>(t.late_servo_discarded);
  m.window_miss_ppm = static_cast<std::int32_t>(t.window_miss_ppm);
  m.leaky_bucket_score = static_cast<std::int32_t>(t.leaky_bucket_score);
  m.wake_latency = to_latency(t.wake_latency);
  m.servo_start_delay = to_latency(t.servo_start_delay);
  m.servo_execution = to_latency(t.servo_execution);
  m.measured_period = to_latency(t.measured_period);
  m.vpr_torn = static_cast<std::int64_t>(t.vpr_torn);
  m.vpr_stale = static_cast<std::int64_t>(t.vpr_stale);
  m.vpr_rejected = static_cast<std::int64_t>(t.vpr_rejected);
  m.force_rejected = static_cast<std::int64_t>(t.force_rejected);
  m.ctrl_accepted = static_cast<std::int64_t>(t.ctrl_accepted);
  m.ctrl_rejected = static_cast<std::int64_t>(t.ctrl_rejected);
  copy(shm::kLatencyBucketEdgesUs, m.histogram_edges_us);
  for (std::size_t i = 0; i < shm::kLatencyBuckets; ++i) {
    m.wake_histogram[i] = static_cast<std::int64_t>(t.wake_histogram[i]);
  }
  return m;
}

hapticctrl_lcm::bridge_stats_t to_bridge_stats(const shm::LinkStatsPayload& s, std::int64_t utime) {
  hapticctrl_lcm::bridge_stats_t m{};
  m.utime = utime;
  m.session_id = static_cast<std::int64_t>(s.session_id);
  if (s.session_id != 0) {
    in_addr a{htonl(s.peer_ipv4)};
    char text[INET_ADDRSTRLEN] = {};  // NOLINT(*-avoid-c-arrays)
    ::inet_ntop(AF_INET, &a, text, sizeof text);
    m.peer = std::string(text) + ":" + std::to_string(s.peer_port);
  }
  m.watchdog_ms = static_cast<std::int32_t>(s.watchdog_ms);
  m.features = static_cast<std::int32_t>(s.features);
  m.frames_in = static_cast<std::int64_t>(s.frames_in);
  m.frames_out = static_cast<std::int64_t>(s.frames_out);
  m.control_accepted = static_cast<std::int64_t>(s.control_accepted);
  m.params_applied = static_cast<std::int64_t>(s.params_applied);
  m.param_duplicates = static_cast<std::int64_t>(s.param_duplicates);
  m.params_rejected = static_cast<std::int64_t>(s.params_rejected);
  m.sessions_opened = static_cast<std::int64_t>(s.sessions_opened);
  m.sessions_closed = static_cast<std::int64_t>(s.sessions_closed);
  m.watchdog_expiries = static_cast<std::int64_t>(s.watchdog_expiries);
  m.refused_busy = static_cast<std::int64_t>(s.refused_busy);
  m.refused_version = static_cast<std::int64_t>(s.refused_version);
  m.send_failures = static_cast<std::int64_t>(s.send_failures);
  m.drop_reasons = static_cast<std::int32_t>(shm::kLinkDropCount);
  for (std::size_t i = 0; i < shm::kLinkDropCount; ++i) {
    m.drop_names.emplace_back(shm::kLinkDropNames[i]);
    m.dropped.push_back(static_cast<std::int64_t>(s.dropped[i]));
  }
  return m;
}

hapticctrl_lcm::event_t to_event(const shm::Event& e, std::uint64_t lost_before,
                                 std::int64_t monotonic_now_ns, std::int64_t wall_now_us) {
  hapticctrl_lcm::event_t m{};
  m.utime = wall_now_us - (monotonic_now_ns - e.time_ns) / 1000;
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
