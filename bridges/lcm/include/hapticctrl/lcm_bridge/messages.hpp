#pragma once
/// @file messages.hpp
/// The shared-memory payloads that LCM carries combined or described (coupling from VP, VPr and
/// telemetry; events), and the instance's channel names. The regions carried one for one
/// (position, telemetry, link_stats) are mapped in lcmtypes/regions.hpp. Pure conversions: no I/O.
/// Not for a hard-RT cycle (event texts are std::string).
#include <string>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/lcmtypes/channels.hpp"
#include "hapticctrl/shm/events.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl_lcm/coupling_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"

namespace hapticctrl::lcm_bridge {

using lcmtypes::Channels;

/// `now` dates the client sample's age (VPr.received_time_ns is the bridge's receive time).
[[nodiscard]] hapticctrl_lcm::coupling_t to_coupling(const shm::VpPayload& vp,
                                                     const shm::VprPayload& vpr,
                                                     const shm::TelemetryPayload& t, TimePoint now,
                                                     std::int64_t utime);
/// An event with its utime: when the core recorded it, in microseconds since the epoch (its
/// time_ns on this host's CLOCK_MONOTONIC moved onto the wall clock, `monotonic_now` and
/// `wall_now_us` read together), so that a page or a log says when the controller did it, not
/// when a bridge passed it on.
[[nodiscard]] hapticctrl_lcm::event_t to_event(const shm::Event& e, std::uint64_t lost_before,
                                               TimePoint monotonic_now, std::int64_t wall_now_us);

}  // namespace hapticctrl::lcm_bridge
