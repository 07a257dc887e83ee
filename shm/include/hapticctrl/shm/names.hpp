#pragma once
/// @file names.hpp
/// Human-readable names of the codes carried in the regions (core state, stop reason, RT mode,
/// events), shared by every process that reports them. Codes come from shared memory, so any
/// value is accepted: an unknown one gets an "unknown ..." name, never undefined behaviour.
#include <cstdint>
#include <string>

#include "hapticctrl/shm/events.hpp"

namespace hapticctrl::shm {

/// "starting", "running", "fail-safe", "stopping", "stopped". Real-time safe (no allocation).
[[nodiscard]] const char* core_state_name(std::uint64_t core_state) noexcept;
/// "none", "5 consecutive deadline misses", "stop requested", ... Real-time safe.
[[nodiscard]] const char* stop_reason_name(std::uint64_t stop_reason) noexcept;
/// "none", "SCHED_FIFO", "SCHED_FIFO+mlockall", "SCHED_FIFO+mlockall+PREEMPT_RT". Real-time safe.
[[nodiscard]] const char* rt_mode_name(std::uint64_t rt_mode) noexcept;
/// One line for an event ("power on", "fail-safe: 5 consecutive deadline misses", ...).
/// Allocates: not for the cycle.
[[nodiscard]] std::string describe_event(const Event& e);

}  // namespace hapticctrl::shm
