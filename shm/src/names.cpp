// Implements names.hpp: human-readable names of the codes carried in the regions (core state, stop
// reason, RT mode, events), shared by every process that reports them.
#include "hapticctrl/shm/names.hpp"

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::shm {

const char* core_state_name(std::uint64_t core_state) noexcept {
  switch (core_state) {
    case static_cast<std::uint64_t>(CoreState::kStarting):
      return "starting";
    case static_cast<std::uint64_t>(CoreState::kRunning):
      return "running";
    case static_cast<std::uint64_t>(CoreState::kFailSafe):
      return "fail-safe";
    case static_cast<std::uint64_t>(CoreState::kStopping):
      return "stopping";
    case static_cast<std::uint64_t>(CoreState::kStopped):
      return "stopped";
    default:
      return "unknown state";
  }
}

const char* stop_reason_name(std::uint64_t stop_reason) noexcept {
  switch (stop_reason) {
    case static_cast<std::uint64_t>(StopReason::kNone):
      return "none";
    case static_cast<std::uint64_t>(StopReason::kConsecutiveMisses):
      return "5 consecutive deadline misses";
    case static_cast<std::uint64_t>(StopReason::kStopRequested):
      return "stop requested";
    case static_cast<std::uint64_t>(StopReason::kSignal):
      return "stopped by signal";
    case static_cast<std::uint64_t>(StopReason::kChronicMisses):
      return "chronic deadline misses over the configured threshold";
    case static_cast<std::uint64_t>(StopReason::kArmFault):
      return "arm I/O fault";
    case static_cast<std::uint64_t>(StopReason::kDurationElapsed):
      return "duration elapsed";
    case static_cast<std::uint64_t>(StopReason::kVelocityLimit):
      return "velocity above the safety threshold";
    case static_cast<std::uint64_t>(StopReason::kCoreLost):
      return "the controller process is gone (killed or crashed)";
    default:
      return "unknown reason";
  }
}

const char* rt_mode_name(std::uint64_t rt_mode) noexcept {
  switch (rt_mode) {
    case static_cast<std::uint64_t>(RtMode::kNone):
      return "none";
    case static_cast<std::uint64_t>(RtMode::kFifo):
      return "SCHED_FIFO";
    case static_cast<std::uint64_t>(RtMode::kFifoLocked):
      return "SCHED_FIFO+mlockall";
    case static_cast<std::uint64_t>(RtMode::kFifoLockedRt):
      return "SCHED_FIFO+mlockall+PREEMPT_RT";
    default:
      return "unknown";
  }
}

std::string describe_event(const Event& e) {
  const bool on = e.code != 0;
  switch (e.kind) {
    case EventKind::kCoreState: {
      std::string text = core_state_name(e.code);
      return e.value == 0 ? text : text + ": " + stop_reason_name(e.value);
    }
    case EventKind::kPower:
      return on ? "power on" : "power off";
    case EventKind::kEmergencyStop:
      return on ? "emergency stop latched" : "emergency stop reset";
    case EventKind::kDegraded:
      return on ? "degraded SERVO ran (main SERVO late)" : "main SERVO back";
    case EventKind::kClientSession:
      return e.value != 0 ? "client session " + std::to_string(e.value) + " started"
                          : "no client session";
    case EventKind::kClientStale: {
      std::string text = on ? "client data stale (extrapolating, fading)" : "client data fresh";
      return e.value == 0
                 ? text
                 : text + " (" + std::to_string(e.value) + " shorter lapses since the last)";
    }
    case EventKind::kCoupling:
      return on ? "coupling active" : "coupling inactive";
    case EventKind::kNone:
      break;
  }
  return "unknown event";
}

}  // namespace hapticctrl::shm
