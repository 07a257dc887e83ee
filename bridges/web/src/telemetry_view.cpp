// Implements telemetry_view.hpp: the web bridge's picture of the controller, built from LCM
// telemetry, and the JSON frames it pushes to pages.
#include "hapticctrl/web_bridge/telemetry_view.hpp"

#include <cstring>
#include <nlohmann/json.hpp>

#include "hapticctrl/lcmtypes/regions.hpp"
#include "hapticctrl/shm/names.hpp"
#include "hapticctrl/shm/payload_text.hpp"

namespace hapticctrl::web_bridge {
namespace {

using Json = nlohmann::json;

enum Source : std::size_t { kArm, kCoupling, kStats, kEvents, kScene, kWorld };

/// A message's fixed array (double or float) as a JSON array of numbers.
template <typename T, std::size_t N>
Json array_of(const T (&values)[N]) {
  return Json(std::vector<double>(values, values + N));
}

/// A region LCM carries one for one, read back into its payload and written through the
/// payload's field table (shm/payload_text.hpp): the page reads the fields by their names there.
template <typename M, typename P>
Json region_json(const M& m, P (*from)(const M&)) {
  return Json::parse(shm::fields_json(from(m)));
}

Json arm_json(const hapticctrl_lcm::arm_state_t& m) {
  return region_json(m, lcmtypes::from_arm_state);
}

Json coupling_json(const hapticctrl_lcm::coupling_t& m) {
  return {{"session_id", m.session_id},
          {"command_type", m.command_type},
          {"object_attached", m.object_attached},
          {"object_pose", array_of(m.object_pose)},
          {"object_wrench", array_of(m.object_wrench)},
          {"client_age_ms", m.client_age_ms},
          {"client_stale", m.client_stale},
          {"contacts", m.contacts},
          {"surface_point", array_of(m.surface_point)},
          {"surface_normal", array_of(m.surface_normal)},
          {"surface_depth_mm", m.surface_depth_mm},
          {"surface_force", m.surface_force},
          {"surface_hidden_mm", m.surface_hidden_mm},
          {"contact_age_ms", m.contact_age_ms}};
}

Json stats_json(const hapticctrl_lcm::cycle_stats_t& m, const StatsInterval& interval) {
  Json stats = region_json(m, lcmtypes::from_cycle_stats);
  stats["rt_mode_name"] = shm::rt_mode_name(static_cast<std::uint64_t>(m.rt_mode));
  stats["core_state_name"] = shm::core_state_name(static_cast<std::uint64_t>(m.core_state));
  stats["stop_reason_name"] = shm::stop_reason_name(static_cast<std::uint64_t>(m.stop_reason));
  stats["interval"] = {{"cycles", interval.cycles},
                       {"misses", interval.misses},
                       {"skipped_slots", interval.skipped_slots},
                       {"wake_max_us_at_most", interval.wake_max_us_at_most}};
  return stats;
}

Json scene_json(const hapticctrl_lcm::scene_t& m) {
  return {{"steps", m.steps},
          {"fixed_center", array_of(m.fixed_center)},
          {"fixed_radius", m.fixed_radius},
          {"mobile_pose", array_of(m.mobile_pose)},
          {"mobile_radius", m.mobile_radius},
          {"contact_force", array_of(m.contact_force)},
          {"penetration", m.penetration},
          {"applied_wrench", array_of(m.applied_wrench)},
          {"rtt_last_us", m.rtt_last_us},
          {"rtt_mean_us", m.rtt_mean_us},
          {"rtt_max_us", m.rtt_max_us},
          {"answers_received", m.answers_received},
          {"answers_lost", m.answers_lost}};
}

Json world_json(const hapticctrl_lcm::world_t& m) {
  Json geoms = Json::array();
  for (std::int32_t i = 0; i < m.geom_count; ++i) {
    const hapticctrl_lcm::world_geom_t& g = m.geoms[i];
    geoms.push_back({{"type", g.type},
                     {"size", array_of(g.size)},
                     {"pose", array_of(g.pose)},
                     {"rgba", array_of(g.rgba)},
                     {"coupled", g.coupled != 0}});
  }
  Json contacts = Json::array();
  for (std::int32_t i = 0; i < m.contact_count; ++i) {
    const hapticctrl_lcm::world_contact_t& c = m.contacts[i];
    contacts.push_back({{"point", array_of(c.point)},
                        {"normal", array_of(c.normal)},
                        {"distance", c.distance},
                        {"stiffness", c.stiffness}});
  }
  return {{"steps", m.steps},
          {"steps_per_second", m.steps_per_second},
          {"model_steps_per_second", m.model_steps_per_second},
          {"geoms_total", m.geoms_total},
          {"geoms", std::move(geoms)},
          {"contacts", std::move(contacts)},
          {"contact_force", array_of(m.contact_force)}};
}

Json event_json(const hapticctrl_lcm::event_t& m) {
  return {{"utime", m.utime},     {"index", m.index}, {"cycle", m.cycle},
          {"time_ns", m.time_ns}, {"kind", m.kind},   {"code", m.code},
          {"value", m.value},     {"text", m.text},   {"lost_before", m.lost_before}};
}

std::string dump(const Json& j) {
  // Strings come from LCM: replace invalid UTF-8 instead of throwing.
  return j.dump(-1, ' ', false, Json::error_handler_t::replace);
}

/// Reads a big-endian int32 (LCM's encoding) at `at`.
std::int32_t int32_at(const std::uint8_t* p, std::size_t at) noexcept {
  return static_cast<std::int32_t>(
      (static_cast<std::uint32_t>(p[at]) << 24U) | (static_cast<std::uint32_t>(p[at + 1]) << 16U) |
      (static_cast<std::uint32_t>(p[at + 2]) << 8U) | static_cast<std::uint32_t>(p[at + 3]));
}

/// Skips one LCM string at `at` (int32 length with the NUL, then the bytes); false if it does
/// not fit in `size` or is not NUL-terminated.
bool skip_string(const std::uint8_t* p, std::size_t size, std::size_t& at) noexcept {
  if (at + 4 > size) {
    return false;
  }
  const std::int32_t length = int32_at(p, at);
  at += 4;
  if (length <= 0 || static_cast<std::size_t>(length) > size - at) {
    return false;
  }
  at += static_cast<std::size_t>(length);
  return p[at - 1] == 0;
}

}  // namespace

bool world_counts_sound(const hapticctrl_lcm::world_t& m) noexcept {
  constexpr auto kGeoms = static_cast<std::int32_t>(sizeof(m.geoms) / sizeof(m.geoms[0]));
  constexpr auto kContacts = static_cast<std::int32_t>(sizeof(m.contacts) / sizeof(m.contacts[0]));
  return m.geom_count >= 0 && m.geom_count <= kGeoms && m.geoms_total >= m.geom_count &&
         m.contact_count >= 0 && m.contact_count <= kContacts;
}

StatsInterval interval_between(const hapticctrl_lcm::cycle_stats_t& before,
                               const hapticctrl_lcm::cycle_stats_t& after) noexcept {
  const bool same_core = after.cycle >= before.cycle && after.misses_total >= before.misses_total;
  StatsInterval i;
  i.cycles = after.cycle - (same_core ? before.cycle : 0);
  i.misses = after.misses_total - (same_core ? before.misses_total : 0);
  i.skipped_slots = after.skipped_slots - (same_core ? before.skipped_slots : 0);
  constexpr int kOpenBucket = 12;  // 10 ms and beyond
  for (int b = kOpenBucket; b >= 0; --b) {
    const std::int64_t hits = after.wake_histogram[b] - (same_core ? before.wake_histogram[b] : 0);
    if (hits > 0) {
      i.wake_max_us_at_most = b == kOpenBucket ? -1 : after.histogram_edges_us[b];
      break;
    }
  }
  return i;
}

StatsInterval merged(const StatsInterval& a, const StatsInterval& b) noexcept {
  StatsInterval m;
  m.cycles = a.cycles + b.cycles;
  m.misses = a.misses + b.misses;
  m.skipped_slots = a.skipped_slots + b.skipped_slots;
  const bool open = a.wake_max_us_at_most < 0 || b.wake_max_us_at_most < 0;
  m.wake_max_us_at_most = open ? -1 : std::max(a.wake_max_us_at_most, b.wake_max_us_at_most);
  return m;
}

bool event_strings_sound(const void* data, std::size_t size) noexcept {
  const auto* p = static_cast<const std::uint8_t*>(data);
  std::size_t at = 8 + 4 * 8;       // fingerprint, utime, index, cycle, time_ns
  if (!skip_string(p, size, at)) {  // kind
    return false;
  }
  at += 4 + 8;                                        // code, value
  return skip_string(p, size, at) && at + 8 == size;  // text, then lost_before
}

TelemetryView::TelemetryView(std::size_t event_history) : event_history_(event_history) {}

void TelemetryView::on_arm_state(const hapticctrl_lcm::arm_state_t& m, TimePoint now) {
  const std::lock_guard lock(mutex_);
  arm_ = m;
  received_[kArm] = {now, true};
}

void TelemetryView::on_coupling(const hapticctrl_lcm::coupling_t& m, TimePoint now) {
  const std::lock_guard lock(mutex_);
  coupling_ = m;
  received_[kCoupling] = {now, true};
}

void TelemetryView::on_cycle_stats(const hapticctrl_lcm::cycle_stats_t& m, TimePoint now) {
  const std::lock_guard lock(mutex_);
  if (stats_) {
    const StatsInterval step = interval_between(*stats_, m);
    interval_ = interval_ ? merged(*interval_, step) : step;
  }
  stats_ = m;
  stats_fresh_ = true;
  received_[kStats] = {now, true};
}

void TelemetryView::on_event(const hapticctrl_lcm::event_t& m, TimePoint now) {
  const std::lock_guard lock(mutex_);
  events_.push_back(m);
  if (events_.size() > event_history_) {
    events_.pop_front();
  }
  events_unsent_ = std::min(events_unsent_ + 1, events_.size());
  received_[kEvents] = {now, true};
}

void TelemetryView::on_scene(const hapticctrl_lcm::scene_t& m, TimePoint now) {
  const std::lock_guard lock(mutex_);
  scene_ = m;
  received_[kScene] = {now, true};
}

void TelemetryView::on_world(const hapticctrl_lcm::world_t& m, TimePoint now) {
  if (!world_counts_sound(m)) {
    return;  // the LCM input counts it as malformed before it gets here
  }
  const std::lock_guard lock(mutex_);
  world_ = m;
  received_[kWorld] = {now, true};
}

std::string TelemetryView::next_frame(TimePoint now) {
  const std::lock_guard lock(mutex_);
  static constexpr const char* kNames[] = {"arm", "coupling", "stats", "events", "scene", "world"};
  Json age = Json::object();
  for (std::size_t i = 0; i < received_.size(); ++i) {
    age[kNames[i]] =
        received_[i].any ? Json(to_seconds(now - received_[i].at) * 1e3) : Json(nullptr);
  }
  Json frame{{"type", "state"}, {"age_ms", age}};
  const bool arm_live = received_[kArm].any && now - received_[kArm].at < kSilentAfter;
  frame["controller_silent"] = !arm_live;
  frame["arm"] = arm_ ? arm_json(*arm_) : Json(nullptr);
  frame["coupling"] = coupling_ ? coupling_json(*coupling_) : Json(nullptr);
  frame["scene"] = scene_ ? scene_json(*scene_) : Json(nullptr);
  frame["world"] = world_ ? world_json(*world_) : Json(nullptr);
  if (stats_fresh_ && stats_) {
    frame["stats"] = stats_json(*stats_, interval_.value_or(StatsInterval{}));
    stats_fresh_ = false;
    interval_.reset();
  }
  Json events = Json::array();
  for (std::size_t i = events_.size() - events_unsent_; i < events_.size(); ++i) {
    events.push_back(event_json(events_[i]));
  }
  events_unsent_ = 0;
  frame["events"] = std::move(events);
  return dump(frame);
}

std::string TelemetryView::history_frame() const {
  const std::lock_guard lock(mutex_);
  Json events = Json::array();
  for (const auto& e : events_) {
    events.push_back(event_json(e));
  }
  Json frame{{"type", "history"}, {"events", std::move(events)}};
  if (stats_) {
    frame["stats"] = stats_json(*stats_, StatsInterval{});
  }
  return dump(frame);
}

}  // namespace hapticctrl::web_bridge
