#include "hapticctrl/rt_core/core_report.hpp"

#include <sstream>

namespace hapticctrl::rt_core {
namespace {

void latency_json(std::ostringstream& out, const char* name, const shm::LatencySummary& s) {
  out << "\"" << name << "\":{\"min_ns\":" << s.min_ns << ",\"avg_ns\":" << s.avg_ns
      << ",\"max_ns\":" << s.max_ns << ",\"p50_ns\":" << s.p50_ns << ",\"p99_ns\":" << s.p99_ns
      << ",\"p999_ns\":" << s.p999_ns << ",\"samples\":" << s.samples
      << ",\"overflows\":" << s.overflows << "}";
}

}  // namespace

std::string stop_reason_text(shm::StopReason reason) {
  switch (reason) {
    case shm::StopReason::kNone:
      return "none";
    case shm::StopReason::kConsecutiveMisses:
      return "5 consecutive deadline misses";
    case shm::StopReason::kStopRequested:
      return "stop requested";
    case shm::StopReason::kSignal:
      return "stopped by signal";
    case shm::StopReason::kChronicMisses:
      return "chronic deadline misses over the configured threshold";
    case shm::StopReason::kArmFault:
      return "arm I/O fault";
    case shm::StopReason::kDurationElapsed:
      return "duration elapsed";
    case shm::StopReason::kVelocityLimit:
      return "velocity above the safety threshold";
  }
  return "unknown reason " + std::to_string(static_cast<unsigned>(reason));
}

std::string rt_mode_text(shm::RtMode mode) {
  switch (mode) {
    case shm::RtMode::kNone:
      return "none";
    case shm::RtMode::kFifo:
      return "SCHED_FIFO";
    case shm::RtMode::kFifoLocked:
      return "SCHED_FIFO+mlockall";
    case shm::RtMode::kFifoLockedRt:
      return "SCHED_FIFO+mlockall+PREEMPT_RT";
  }
  return "unknown";
}

std::string telemetry_json(const shm::TelemetryPayload& t) {
  std::ostringstream out;
  const auto reason = static_cast<shm::StopReason>(t.stop_reason);
  out << "{\"cycles\":" << t.cycle << ",\"period_ns\":" << t.period_ns << ",\"rt_mode\":\""
      << rt_mode_text(static_cast<shm::RtMode>(t.rt_mode)) << "\",\"stop_reason\":\""
      << stop_reason_text(reason) << "\",\"stop_reason_code\":" << t.stop_reason
      << ",\"misses_total\":" << t.misses_total
      << ",\"consecutive_misses\":" << t.consecutive_misses
      << ",\"degraded_cycles\":" << t.degraded_cycles << ",\"skipped_slots\":" << t.skipped_slots
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
      << ",\"ctrl_accepted\":" << t.ctrl_accepted << ",\"ctrl_rejected\":" << t.ctrl_rejected
      << "}";
  return out.str();
}

}  // namespace hapticctrl::rt_core
