// Implements status.hpp: what the operator panel shows, read from an instance's regions in one go,
// and its JSON form (`hapticctrl-hmi status --json`).
#include "hapticctrl/hmi/status.hpp"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/payload_text.hpp"

namespace hapticctrl::hmi {
namespace {

/// A JSON number, or null for what JSON cannot carry: "-nan" made the whole document unreadable
/// (2026-12-03), and writing 0 instead would hide a fault.
struct JsonNumber {
  double value;
};
std::ostream& operator<<(std::ostream& out, JsonNumber n) {
  if (std::isfinite(n.value)) {
    return out << n.value;
  }
  return out << "null";
}

template <std::size_t N>
void json_array(std::ostringstream& out, const char* name, const std::array<double, N>& values) {
  out << "\"" << name << "\":[";
  for (std::size_t i = 0; i < N; ++i) {
    out << (i == 0 ? "" : ",") << JsonNumber{values[i]};
  }
  out << "]";
}

/// `,"regions":{...}`: every field of each region read, as its table describes it (a region that
/// could not be read is null).
std::string regions_json(const ControllerStatus& s) {
  std::string out = ",\"regions\":{";
  const auto add = [&out](const char* name, bool ok, const auto& payload) {
    out += out.back() == '{' ? "\"" : ",\"";
    out += name;
    out += "\":" + (ok ? shm::fields_json(payload) : std::string("null"));
  };
  add("position", s.position_ok, s.position);
  add("vp", s.vp_ok, s.vp);
  add("vpr", s.vpr_ok, s.vpr);
  add("telemetry", s.telemetry_ok, s.telemetry);
  add("link_stats", s.link_ok, s.link);
  return out + "}";
}

}  // namespace

double ControllerStatus::client_age_ms() const noexcept {
  if (!client_connected() || !vpr_ok || vpr.session_id == 0) {
    return -1.0;
  }
  return to_seconds(read_at - time_point_from_ns(vpr.received_time_ns)) * 1e3;
}

ControllerStatus read_status(const shm::Segment& segment, TimePoint now) {
  ControllerStatus s;
  s.instance = segment.instance();
  s.read_at = now;
  s.position_ok = segment.region<shm::RegionId::kPosition>().read(s.position).ok();
  s.vp_ok = segment.region<shm::RegionId::kVp>().read(s.vp).ok();
  s.telemetry_ok = segment.region<shm::RegionId::kTelemetry>().read(s.telemetry).ok();
  s.link_ok = segment.region<shm::RegionId::kLinkStats>().read(s.link).ok();
  s.vpr_ok = segment.region<shm::RegionId::kVpr>().read(s.vpr).ok();
  shm::ForcePayload force;
  if (segment.region<shm::RegionId::kForce>().read(force).ok()) {
    s.requested_force = force.wrench;
  }
  return s;
}

double control_frames_per_cycle(const ControllerStatus& before,
                                const ControllerStatus& after) noexcept {
  if (!before.client_connected() || !after.client_connected() ||
      before.link.session_id != after.link.session_id || !before.vp_ok || !after.vp_ok ||
      after.vp.cycle <= before.vp.cycle) {
    return -1.0;
  }
  const auto frames = after.link.control_accepted - before.link.control_accepted;
  return static_cast<double>(frames) / static_cast<double>(after.vp.cycle - before.vp.cycle);
}

std::string status_json(const ControllerStatus& s) {
  std::ostringstream out;
  out << std::setprecision(9);
  const shm::TelemetryPayload& t = s.telemetry;
  out << "{\"instance\":\"" << s.instance << "\",\"cycle\":" << s.vp.cycle << ",\"core_state\":\""
      << shm::core_state_name(s.vp.core_state) << "\",\"stop_reason\":\""
      << shm::stop_reason_name(s.vp.stop_reason) << "\",\"powered\":" << std::boolalpha
      << s.powered() << ",\"emergency_stop\":" << s.emergency_stop()
      << ",\"awaiting_operator\":" << s.has_state_bit(shm::state_bits::kAwaitingOperator)
      << ",\"fail_safe\":" << s.has_state_bit(shm::state_bits::kFailSafe)
      << ",\"degraded\":" << s.has_state_bit(shm::state_bits::kDegraded)
      << ",\"coupled\":" << s.has_state_bit(shm::state_bits::kCoupled)
      << ",\"command_type\":" << s.vp.command_type << ",";
  json_array(out, "handle_pose", s.position.handle_pose);
  out << ",";
  json_array(out, "handle_twist", s.position.handle_twist);
  out << ",";
  json_array(out, "joint_position", s.position.joint_position);
  out << ",";
  json_array(out, "joint_torque", s.position.joint_torque);
  out << ",";
  json_array(out, "operator_wrench", s.position.operator_wrench);
  out << ",";
  json_array(out, "requested_force", s.requested_force);
  out << ",";
  json_array(out, "object_wrench", s.vp.object_wrench);
  out << ",\"cycle_health\":{\"period_ns\":" << t.period_ns << ",\"rt_mode\":\""
      << shm::rt_mode_name(t.rt_mode) << "\",\"wake_p99_ns\":" << t.wake_latency.p99_ns
      << ",\"wake_max_ns\":" << t.wake_latency.max_ns
      << ",\"servo_execution_p99_ns\":" << t.servo_execution.p99_ns
      << ",\"misses_total\":" << t.misses_total
      << ",\"consecutive_misses\":" << t.consecutive_misses
      << ",\"would_fail_safe\":" << t.would_fail_safe
      << ",\"degraded_cycles\":" << t.degraded_cycles
      << "},\"client\":{\"connected\":" << s.client_connected();
  if (s.client_connected()) {
    out << ",\"peer\":\"" << shm::ipv4_text(s.link.peer_ipv4) << ":" << s.link.peer_port
        << "\",\"session_id\":" << s.link.session_id << ",\"sample_age_ms\":" << s.client_age_ms()
        << ",\"control_accepted\":" << s.link.control_accepted
        << ",\"stale\":" << s.has_state_bit(shm::state_bits::kClientStale)
        << ",\"loop_delay_ms\":" << static_cast<double>(s.vp.loop_delay_ns) / 1e6
        << ",\"link_delay_ms\":" << static_cast<double>(s.link.link_delay_ns) / 1e6
        << ",\"link_jitter_ms\":" << static_cast<double>(s.link.link_jitter_ns) / 1e6
        << ",\"link_loss\":" << static_cast<double>(s.link.link_loss_ppm) / 1e6
        << ",\"channel_energy_in\":" << JsonNumber{s.vp.channel_energy_in}
        << ",\"channel_energy_out\":" << JsonNumber{s.vp.channel_energy_out}
        << ",\"client_energy_in\":" << JsonNumber{s.vpr.client_energy_in}
        << ",\"contacts\":" << s.vp.contacts << ",\"contacts_rejected\":" << s.vp.contacts_rejected
        << ",";
    json_array(out, "contact_normal", s.vp.contact_normal);
    out << ",";
    json_array(out, "normal_gains", s.vp.normal_gains);
    out << ",";
    json_array(out, "gains", s.vp.gains);
    out << ",\"surface\":{\"depth_mm\":" << JsonNumber{s.vp.surface_depth * 1e3}
        << ",\"force\":" << JsonNumber{s.vp.surface_force}
        << ",\"hidden_mm\":" << JsonNumber{s.vp.surface_hidden * 1e3}
        << ",\"withheld_j\":" << JsonNumber{s.vp.surface_withheld} << ",\"contact_age_ms\":"
        << (s.vp.contact_age_ns >= 0 ? static_cast<double>(s.vp.contact_age_ns) / 1e6 : -1.0)
        << ",";
    json_array(out, "point", s.vp.surface_point);
    out << ",";
    json_array(out, "normal", s.vp.surface_normal);
    out << "}";
  }
  std::uint64_t dropped = 0;
  for (const auto d : s.link.dropped) {
    dropped += d;
  }
  out << ",\"frames_dropped\":" << dropped << ",\"watchdog_expiries\":" << s.link.watchdog_expiries
      << "}" << regions_json(s) << "}";
  return out.str();
}

}  // namespace hapticctrl::hmi
