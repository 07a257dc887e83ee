#pragma once
/// @file telemetry_view.hpp
/// The web bridge's picture of the controller, built from LCM telemetry, and the JSON frames
/// it pushes to pages. Receive times are the bridge's own (monotonic), so a page can tell a
/// silent controller from a quiet one. Thread-safe (one mutex): the LCM thread feeds it, the
/// push thread and the server's threads read it.
///
/// Real-time contract: soft-RT only (allocates, locks a mutex); never in a hard-RT cycle.
#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <mutex>
#include <optional>
#include <string>

#include "hapticctrl/base/time.hpp"
#include "hapticctrl_lcm/arm_state_t.hpp"
#include "hapticctrl_lcm/coupling_t.hpp"
#include "hapticctrl_lcm/cycle_stats_t.hpp"
#include "hapticctrl_lcm/event_t.hpp"
#include "hapticctrl_lcm/scene_t.hpp"
#include "hapticctrl_lcm/world_t.hpp"

namespace hapticctrl::web_bridge {

/// Messages older than this make the page say the controller is silent (arm state comes at
/// 100 Hz by default, statistics at 10 Hz).
inline constexpr Duration kSilentAfter = std::chrono::milliseconds(500);

/// What happened between two cycle_stats messages, from the differences of their counters.
struct StatsInterval {
  std::int64_t cycles = 0;
  std::int64_t misses = 0;
  std::int64_t skipped_slots = 0;
  /// Upper edge (µs) of the highest wake-latency bucket hit in the interval; -1 for the last,
  /// open bucket (10 ms and beyond), 0 when no cycle ran.
  std::int64_t wake_max_us_at_most = 0;
};

/// The interval between two statistics messages of one core. Counters that went backwards (a
/// new core) give the later message's totals.
[[nodiscard]] StatsInterval interval_between(const hapticctrl_lcm::cycle_stats_t& before,
                                             const hapticctrl_lcm::cycle_stats_t& after) noexcept;

/// Both intervals as one (sums; the larger wake bound, -1 counting as the largest).
[[nodiscard]] StatsInterval merged(const StatsInterval& a, const StatsInterval& b) noexcept;

/// Whether an encoded event_t's two strings declare lengths that fit the message. Debian's
/// lcm-gen decoder trusts them (a negative one makes it copy gigabytes): check before decode().
[[nodiscard]] bool event_strings_sound(const void* data, std::size_t size) noexcept;

/// Whether a decoded world_t's counts fit its arrays (geom_count within geoms, contact_count
/// within contacts, geoms_total not below geom_count): the page draws only what they say.
[[nodiscard]] bool world_counts_sound(const hapticctrl_lcm::world_t& m) noexcept;

class TelemetryView {
 public:
  explicit TelemetryView(std::size_t event_history = 20);

  void on_arm_state(const hapticctrl_lcm::arm_state_t& m, TimePoint now);
  void on_coupling(const hapticctrl_lcm::coupling_t& m, TimePoint now);
  void on_cycle_stats(const hapticctrl_lcm::cycle_stats_t& m, TimePoint now);
  void on_event(const hapticctrl_lcm::event_t& m, TimePoint now);
  void on_scene(const hapticctrl_lcm::scene_t& m, TimePoint now);
  /// A physics engine client's world (hapticctrl-mujoco); counts checked by world_counts_sound.
  void on_world(const hapticctrl_lcm::world_t& m, TimePoint now);

  /// The next state frame: the latest arm state, coupling, scene and world, each message's age,
  /// and
  /// the statistics and events that arrived since the previous frame (so plots get each sample
  /// once). {"type":"state",...}; docs/web.md lists the fields.
  [[nodiscard]] std::string next_frame(TimePoint now);
  /// {"type":"history","events":[...]}: the recent events, for a page that just connected.
  [[nodiscard]] std::string history_frame() const;

 private:
  struct Received {
    TimePoint at;
    bool any = false;
  };

  mutable std::mutex mutex_;
  std::size_t event_history_;
  std::optional<hapticctrl_lcm::arm_state_t> arm_;
  std::optional<hapticctrl_lcm::coupling_t> coupling_;
  std::optional<hapticctrl_lcm::cycle_stats_t> stats_;
  std::optional<StatsInterval> interval_;  ///< since the previous frame, over all stats
  std::optional<hapticctrl_lcm::scene_t> scene_;
  std::optional<hapticctrl_lcm::world_t> world_;
  bool stats_fresh_ = false;
  std::deque<hapticctrl_lcm::event_t> events_;  ///< the last event_history_
  std::size_t events_unsent_ = 0;
  std::array<Received, 6> received_{};  ///< arm, coupling, stats, events, scene, world
};

}  // namespace hapticctrl::web_bridge
