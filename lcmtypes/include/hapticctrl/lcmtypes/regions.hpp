#pragma once
/// @file regions.hpp
/// The region payloads (shm/payloads.hpp) that LCM carries one for one, both ways: position as
/// arm_state_t, telemetry as cycle_stats_t, link_stats as bridge_stats_t. The LCM bridge
/// publishes with `to_*`; the log's CSV files and the web page read a message back with
/// `from_*` and write it through the payload's field table (payload_text.hpp), so a field added
/// to a payload and mapped here reaches all three. A test checks that every field of the
/// tables survives the round trip.
///
/// Pure conversions, no I/O. Not for a real-time cycle (bridge_stats_t holds strings).

#include <cstdint>

#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/bridge_stats_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"

namespace hapticctrl::lcmtypes {

[[nodiscard]] hapticctrl_lcm::arm_state_t to_arm_state(const shm::PositionPayload& p,
                                                       std::int64_t utime);
[[nodiscard]] shm::PositionPayload from_arm_state(const hapticctrl_lcm::arm_state_t& m) noexcept;

[[nodiscard]] hapticctrl_lcm::cycle_stats_t to_cycle_stats(const shm::TelemetryPayload& t,
                                                           std::int64_t utime);
/// Histogram bins beyond the message's or the payload's count are left out.
[[nodiscard]] shm::TelemetryPayload from_cycle_stats(
    const hapticctrl_lcm::cycle_stats_t& m) noexcept;

[[nodiscard]] hapticctrl_lcm::bridge_stats_t to_bridge_stats(const shm::LinkStatsPayload& s,
                                                             std::int64_t utime);
/// The peer "a.b.c.d:port" back to address and port (0 when absent or unreadable); drop
/// counters matched by name, so a log written with other drop reasons still reads.
[[nodiscard]] shm::LinkStatsPayload from_bridge_stats(const hapticctrl_lcm::bridge_stats_t& m);

}  // namespace hapticctrl::lcmtypes
