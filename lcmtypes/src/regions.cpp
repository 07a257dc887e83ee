// Implements regions.hpp: position, telemetry and link_stats as their LCM messages and back.
#include "hapticctrl/lcmtypes/regions.hpp"

#include <arpa/inet.h>

#include <algorithm>
#include <string>

#include "hapticctrl/shm/payload_text.hpp"

namespace hapticctrl::lcmtypes {
namespace {

// NOLINTBEGIN(*-avoid-c-arrays): lcm-gen's arrays
template <typename T, std::size_t N, typename U>
void copy(const std::array<U, N>& from, T (&to)[N]) {
  std::transform(from.begin(), from.end(), to, [](U v) { return static_cast<T>(v); });
}
template <typename T, std::size_t N, typename U>
void copy(const U (&from)[N], std::array<T, N>& to) {
  std::transform(from, from + N, to.begin(), [](U v) { return static_cast<T>(v); });
}
// NOLINTEND(*-avoid-c-arrays)

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

shm::LatencySummary from_latency(const hapticctrl_lcm::latency_t& l) noexcept {
  shm::LatencySummary s;
  s.min_ns = l.min_ns;
  s.avg_ns = l.avg_ns;
  s.max_ns = l.max_ns;
  s.p50_ns = l.p50_ns;
  s.p99_ns = l.p99_ns;
  s.p999_ns = l.p999_ns;
  s.samples = static_cast<std::uint64_t>(l.samples);
  s.overflows = static_cast<std::uint64_t>(l.overflows);
  return s;
}

void read_peer(const std::string& peer, shm::LinkStatsPayload& s) {
  const auto colon = peer.rfind(':');
  in_addr a{};
  if (colon == std::string::npos || ::inet_pton(AF_INET, peer.substr(0, colon).c_str(), &a) != 1) {
    return;
  }
  try {
    const unsigned long port = std::stoul(peer.substr(colon + 1));
    s.peer_port = port <= 65535 ? static_cast<std::uint32_t>(port) : 0;
    s.peer_ipv4 = ntohl(a.s_addr);
  } catch (const std::exception&) {  // not a number: no peer
    s.peer_port = 0;
    s.peer_ipv4 = 0;
  }
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

shm::PositionPayload from_arm_state(const hapticctrl_lcm::arm_state_t& m) noexcept {
  shm::PositionPayload p;
  p.cycle = static_cast<std::uint64_t>(m.cycle);
  p.state_word = static_cast<std::uint32_t>(m.state_word);
  p.core_state = static_cast<std::uint32_t>(m.core_state);
  copy(m.joint_position, p.joint_position);
  copy(m.joint_velocity, p.joint_velocity);
  copy(m.joint_torque, p.joint_torque);
  copy(m.handle_pose, p.handle_pose);
  copy(m.handle_twist, p.handle_twist);
  copy(m.operator_wrench, p.operator_wrench);
  copy(m.rendered_wrench, p.rendered_wrench);
  return p;
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
  m.would_fail_safe = static_cast<std::int64_t>(t.would_fail_safe);
  m.first_would_fail_safe_cycle = static_cast<std::int64_t>(t.first_would_fail_safe_cycle);
  copy(shm::kLatencyBucketEdgesUs, m.histogram_edges_us);
  copy(t.wake_histogram, m.wake_histogram);
  return m;
}

shm::TelemetryPayload from_cycle_stats(const hapticctrl_lcm::cycle_stats_t& m) noexcept {
  shm::TelemetryPayload t;
  t.cycle = static_cast<std::uint64_t>(m.cycle);
  t.period_ns = m.period_ns;
  t.rt_mode = static_cast<std::uint32_t>(m.rt_mode);
  t.core_state = static_cast<std::uint32_t>(m.core_state);
  t.stop_reason = static_cast<std::uint32_t>(m.stop_reason);
  t.consecutive_misses = static_cast<std::uint32_t>(m.consecutive_misses);
  t.misses_total = static_cast<std::uint64_t>(m.misses_total);
  t.degraded_cycles = static_cast<std::uint64_t>(m.degraded_cycles);
  t.skipped_slots = static_cast<std::uint64_t>(m.skipped_slots);
  t.late_servo_discarded = static_cast<std::uint64_t>(m.late_servo_discarded);
  t.window_miss_ppm = static_cast<std::uint32_t>(m.window_miss_ppm);
  t.leaky_bucket_score = static_cast<std::uint32_t>(m.leaky_bucket_score);
  t.wake_latency = from_latency(m.wake_latency);
  t.servo_start_delay = from_latency(m.servo_start_delay);
  t.servo_execution = from_latency(m.servo_execution);
  t.measured_period = from_latency(m.measured_period);
  t.vpr_torn = static_cast<std::uint64_t>(m.vpr_torn);
  t.vpr_stale = static_cast<std::uint64_t>(m.vpr_stale);
  t.vpr_rejected = static_cast<std::uint64_t>(m.vpr_rejected);
  t.force_rejected = static_cast<std::uint64_t>(m.force_rejected);
  t.ctrl_accepted = static_cast<std::uint64_t>(m.ctrl_accepted);
  t.ctrl_rejected = static_cast<std::uint64_t>(m.ctrl_rejected);
  t.would_fail_safe = static_cast<std::uint64_t>(m.would_fail_safe);
  t.first_would_fail_safe_cycle = static_cast<std::uint64_t>(m.first_would_fail_safe_cycle);
  copy(m.wake_histogram, t.wake_histogram);
  return t;
}

hapticctrl_lcm::bridge_stats_t to_bridge_stats(const shm::LinkStatsPayload& s, std::int64_t utime) {
  hapticctrl_lcm::bridge_stats_t m{};
  m.utime = utime;
  m.session_id = static_cast<std::int64_t>(s.session_id);
  if (s.session_id != 0) {
    m.peer = shm::ipv4_text(s.peer_ipv4) + ":" + std::to_string(s.peer_port);
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
  m.link_delay_ns = s.link_delay_ns;
  m.link_jitter_ns = s.link_jitter_ns;
  m.link_loss_ppm = static_cast<std::int32_t>(s.link_loss_ppm);
  return m;
}

shm::LinkStatsPayload from_bridge_stats(const hapticctrl_lcm::bridge_stats_t& m) {
  shm::LinkStatsPayload s;
  s.session_id = static_cast<std::uint64_t>(m.session_id);
  read_peer(m.peer, s);
  s.watchdog_ms = static_cast<std::uint32_t>(m.watchdog_ms);
  s.features = static_cast<std::uint32_t>(m.features);
  s.frames_in = static_cast<std::uint64_t>(m.frames_in);
  s.frames_out = static_cast<std::uint64_t>(m.frames_out);
  s.control_accepted = static_cast<std::uint64_t>(m.control_accepted);
  s.params_applied = static_cast<std::uint64_t>(m.params_applied);
  s.param_duplicates = static_cast<std::uint64_t>(m.param_duplicates);
  s.params_rejected = static_cast<std::uint64_t>(m.params_rejected);
  s.sessions_opened = static_cast<std::uint64_t>(m.sessions_opened);
  s.sessions_closed = static_cast<std::uint64_t>(m.sessions_closed);
  s.watchdog_expiries = static_cast<std::uint64_t>(m.watchdog_expiries);
  s.refused_busy = static_cast<std::uint64_t>(m.refused_busy);
  s.refused_version = static_cast<std::uint64_t>(m.refused_version);
  s.send_failures = static_cast<std::uint64_t>(m.send_failures);
  const std::size_t named = std::min(m.drop_names.size(), m.dropped.size());
  for (std::size_t i = 0; i < named; ++i) {
    const auto it = std::find(shm::kLinkDropNames.begin(), shm::kLinkDropNames.end(),
                              std::string_view(m.drop_names[i]));
    if (it != shm::kLinkDropNames.end()) {
      s.dropped[static_cast<std::size_t>(it - shm::kLinkDropNames.begin())] =
          static_cast<std::uint64_t>(m.dropped[i]);
    }
  }
  s.link_delay_ns = m.link_delay_ns;
  s.link_jitter_ns = m.link_jitter_ns;
  s.link_loss_ppm = static_cast<std::uint32_t>(m.link_loss_ppm);
  return s;
}

}  // namespace hapticctrl::lcmtypes
