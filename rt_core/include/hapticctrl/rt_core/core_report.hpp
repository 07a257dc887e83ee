#pragma once
/// @file core_report.hpp
/// Human and machine-readable reports of the core's figures. Not for the cycle.

#include <string>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

/// The final statistics as one JSON object.
std::string telemetry_json(const shm::TelemetryPayload& t);

}  // namespace hapticctrl::rt_core
