// Implements core_report.hpp: human and machine-readable reports of the core's figures.
#include "hapticctrl/rt_core/core_report.hpp"

#include <sstream>

#include "hapticctrl/shm/names.hpp"

namespace hapticctrl::rt_core {
namespace {

void latency_json(std::ostringstream& out, const char* name, const shm::LatencySummary& s) {
  out << "\"" << name << "\":{\"min_ns\":" << s.min_ns << ",\"avg_ns\":" << s.avg_ns
      << ",\"max_ns\":" << s.max_ns << ",\"p50_ns\":" << s.p50_ns << ",\"p99_ns\":" << s.p99_ns
      << ",\"p999_ns\":" << s.p999_ns << ",\"samples\":" << s.samples
      << ",\"overflows\":" << s.overflows << "}";
}

}  // namespace

std::string telemetry_json(const shm::TelemetryPayload& t) {
  std::ostringstream out;
  out << "{\"cycles\":" << t.cycle << ",\"period_ns\":" << t.period_ns << ",\"rt_mode\":\""
      << shm::rt_mode_name(t.rt_mode) << "\",\"stop_reason\":\""
      << shm::stop_reason_name(t.stop_reason) << "\",\"stop_reason_code\":" << t.stop_reason
      << ",\"misses_total\":" << t.misses_total
      << ",\"consecutive_misses\":" << t.consecutive_misses
      << ",\"degraded_cycles\":" << t.degraded_cycles << ",\"skipped_slots\":" << t.skipped_slots
      << ",\"would_fail_safe\":" << t.would_fail_safe
      << ",\"first_would_fail_safe_cycle\":" << t.first_would_fail_safe_cycle
      << ",\"late_servo_discarded\":" << t.late_servo_discarded
      << ",\"window_miss_ppm\":" << t.window_miss_ppm
      << ",\"leaky_bucket_score\":" << t.leaky_bucket_score << ",";
  latency_json(out, "wake_latency", t.wake_latency);
  out << ",";
  latency_json(out, "servo_start_delay", t.servo_start_delay);
  out << ",";
  latency_json(out, "servo_execution", t.servo_execution);
  out << ",";
  latency_json(out, "measured_period", t.measured_period);
  out << ",\"vpr_torn\":" << t.vpr_torn << ",\"vpr_stale\":" << t.vpr_stale
      << ",\"vpr_rejected\":" << t.vpr_rejected << ",\"force_rejected\":" << t.force_rejected
      << ",\"ctrl_accepted\":" << t.ctrl_accepted << ",\"ctrl_rejected\":" << t.ctrl_rejected
      << "}";
  return out.str();
}

}  // namespace hapticctrl::rt_core
