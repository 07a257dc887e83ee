#pragma once
/// @file status.hpp
/// What the operator panel shows, read from an instance's regions in one go, and its JSON form
/// (`hapticctrl-hmi status --json`). Reading is a handful of seqlock snapshots: it never blocks
/// or slows the core. Not for the cycle (allocates).
#include <cstdint>
#include <string>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/segment.hpp"

namespace hapticctrl::hmi {

/// One reading of every region the panel shows. A region that could not be read (never
/// written, or torn three times) keeps its defaults and its `*_ok` flag says so.
struct ControllerStatus {
  std::string instance;
  TimePoint read_at;  ///< when it was read
  bool position_ok = false;
  bool vp_ok = false;
  bool telemetry_ok = false;
  bool link_ok = false;
  bool vpr_ok = false;
  shm::PositionPayload position;
  shm::VpPayload vp;
  shm::TelemetryPayload telemetry;
  shm::LinkStatsPayload link;
  shm::VprPayload vpr;
  shm::Vector6 requested_force{};  ///< last wrench written to `force` (by any writer)

  [[nodiscard]] bool has_state_bit(std::uint32_t bit) const noexcept {
    return vp_ok && (vp.state_word & bit) != 0;
  }
  [[nodiscard]] bool powered() const noexcept { return has_state_bit(shm::state_bits::kPowered); }
  [[nodiscard]] bool emergency_stop() const noexcept {
    return has_state_bit(shm::state_bits::kEmergencyStop);
  }
  [[nodiscard]] bool client_connected() const noexcept { return link_ok && link.session_id != 0; }
  /// Age of the client's last sample when read (ms); negative without a client.
  [[nodiscard]] double client_age_ms() const noexcept;
};

/// Takes one reading at `now` (MonotonicClock: the regions' publish clock).
[[nodiscard]] ControllerStatus read_status(const shm::Segment& segment, TimePoint now);

/// Client frames the controller received per cycle between two readings: 1.0 when the client
/// sends every cycle; the shortfall is the loss the controller sees. Negative when unknown (no
/// session, same session not held in both, or no cycle elapsed).
[[nodiscard]] double control_frames_per_cycle(const ControllerStatus& before,
                                              const ControllerStatus& after) noexcept;

/// The reading as one JSON object (state, reason, pose, joints, wrenches, cycle health, link).
[[nodiscard]] std::string status_json(const ControllerStatus& s);

}  // namespace hapticctrl::hmi
