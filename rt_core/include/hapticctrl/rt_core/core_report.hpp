#pragma once
/// @file core_report.hpp
/// Human and machine-readable reports of the core's figures. Not for the cycle.

#include <string>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

/// "5 consecutive deadline misses", "stop requested", ...
std::string stop_reason_text(shm::StopReason reason);
/// "none", "SCHED_FIFO", "SCHED_FIFO+mlockall", "SCHED_FIFO+mlockall+PREEMPT_RT".
std::string rt_mode_text(shm::RtMode mode);
/// The final statistics as one JSON object.
std::string telemetry_json(const shm::TelemetryPayload& t);

}  // namespace hapticctrl::rt_core
