// Tests of telemetry_view.hpp: the web bridge's picture of the controller, built from LCM
// telemetry, and the JSON frames it pushes to pages.
#include "hapticctrl/web_bridge/telemetry_view.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <tuple>

namespace hapticctrl::web_bridge {
namespace {

using Json = nlohmann::json;
using namespace std::chrono_literals;

/// The moment `t` after the clock's origin.
TimePoint at(Duration t) {
  return TimePoint{t};
}

hapticctrl_lcm::cycle_stats_t stats_at(std::int64_t cycle, std::int64_t misses) {
  hapticctrl_lcm::cycle_stats_t s{};
  s.cycle = cycle;
  s.misses_total = misses;
  s.core_state = 1;
  s.period_ns = 1'000'000;
  const std::int64_t edges[12] = {2, 5, 10, 20, 50, 100, 200, 500, 1000, 2000, 5000, 10000};
  for (int i = 0; i < 12; ++i) {
    s.histogram_edges_us[i] = edges[i];
  }
  s.wake_histogram[3] = cycle;  // every wake-up within 20 µs
  return s;
}

std::string encoded(const hapticctrl_lcm::event_t& e) {
  std::string b(static_cast<std::size_t>(e.getEncodedSize()), '\0');
  e.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

TEST(TelemetryView, FrameCarriesTheLatestArmStateAndItsAge) {
  TelemetryView view;
  hapticctrl_lcm::arm_state_t arm{};
  arm.cycle = 42;
  arm.state_word = 1;
  arm.joint_position[1] = -0.6;
  arm.handle_pose[6] = 1.0;
  arm.rendered_wrench[2] = -3.5;
  view.on_arm_state(arm, at(1000ms));
  const Json f = Json::parse(view.next_frame(at(1010ms)));
  EXPECT_EQ(f["type"], "state");
  EXPECT_EQ(f["arm"]["cycle"], 42);
  EXPECT_EQ(f["arm"]["joint_position"][1], -0.6);
  EXPECT_EQ(f["arm"]["rendered_wrench"][2], -3.5);
  EXPECT_DOUBLE_EQ(f["age_ms"]["arm"].get<double>(), 10.0);
  EXPECT_TRUE(f["age_ms"]["scene"].is_null());
  EXPECT_FALSE(f["controller_silent"].get<bool>());
}

TEST(TelemetryView, AControllerWithoutArmStateForHalfASecondIsSilent) {
  TelemetryView view;
  EXPECT_TRUE(Json::parse(view.next_frame(TimePoint{}))["controller_silent"].get<bool>());
  view.on_arm_state({}, at(100ms));
  EXPECT_FALSE(Json::parse(view.next_frame(at(599ms)))["controller_silent"].get<bool>());
  EXPECT_TRUE(Json::parse(view.next_frame(at(600ms)))["controller_silent"].get<bool>());
}

TEST(TelemetryView, StatisticsAndEventsGoOutOnceEach) {
  TelemetryView view;
  view.on_cycle_stats(stats_at(1000, 0), at(0ms));
  view.on_cycle_stats(stats_at(1100, 2), at(100ms));
  hapticctrl_lcm::event_t e{};
  e.utime = 1'700'000'000'123'456;  // when the core recorded it: the page's banner says so
  e.index = 3;
  e.kind = "power";
  e.text = "power on";
  view.on_event(e, at(100ms));
  const Json first = Json::parse(view.next_frame(at(110ms)));
  ASSERT_TRUE(first.contains("stats"));
  EXPECT_EQ(first["stats"]["core_state_name"], "running");
  EXPECT_EQ(first["stats"]["interval"]["cycles"], 100);
  EXPECT_EQ(first["stats"]["interval"]["misses"], 2);
  EXPECT_EQ(first["stats"]["interval"]["wake_max_us_at_most"], 20);
  ASSERT_EQ(first["events"].size(), 1U);
  EXPECT_EQ(first["events"][0]["text"], "power on");
  EXPECT_EQ(first["events"][0]["utime"], 1'700'000'000'123'456);
  const Json second = Json::parse(view.next_frame(at(120ms)));
  EXPECT_FALSE(second.contains("stats"));
  EXPECT_TRUE(second["events"].empty());
  const Json history = Json::parse(view.history_frame());
  EXPECT_EQ(history["events"].size(), 1U);
}

TEST(TelemetryView, KeepsTheLastEventsOnly) {
  TelemetryView view(3);
  for (int i = 1; i <= 5; ++i) {
    hapticctrl_lcm::event_t e{};
    e.index = i;
    view.on_event(e, TimePoint{});
  }
  const Json f = Json::parse(view.next_frame(TimePoint{}));
  ASSERT_EQ(f["events"].size(), 3U);
  EXPECT_EQ(f["events"][0]["index"], 3);
  EXPECT_EQ(f["events"][2]["index"], 5);
}

TEST(TelemetryView, InvalidUtf8FromTheBusIsReplacedNotThrown) {
  TelemetryView view;
  hapticctrl_lcm::event_t e{};
  e.text = "bad \xff\xfe bytes";
  view.on_event(e, TimePoint{});
  EXPECT_TRUE(Json::accept(view.next_frame(TimePoint{})));
}

TEST(StatsInterval, CountsTheDifferenceAndTheWorstBucket) {
  hapticctrl_lcm::cycle_stats_t before = stats_at(1000, 1);
  hapticctrl_lcm::cycle_stats_t after = stats_at(1100, 4);
  after.skipped_slots = 2;
  after.wake_histogram[12] = 1;  // one wake-up beyond 10 ms
  const StatsInterval i = interval_between(before, after);
  EXPECT_EQ(i.cycles, 100);
  EXPECT_EQ(i.misses, 3);
  EXPECT_EQ(i.skipped_slots, 2);
  EXPECT_EQ(i.wake_max_us_at_most, -1);
  EXPECT_EQ(interval_between(after, after).wake_max_us_at_most, 0);  // no cycle ran
}

TEST(StatsInterval, ANewCoreStartsFromItsOwnTotals) {
  const StatsInterval i = interval_between(stats_at(5000, 7), stats_at(200, 0));
  EXPECT_EQ(i.cycles, 200);
  EXPECT_EQ(i.misses, 0);
}

TEST(StatsInterval, MergingAddsAndKeepsTheWorst) {
  const StatsInterval m = merged({10, 1, 0, 50}, {20, 2, 1, 20});
  EXPECT_EQ(m.cycles, 30);
  EXPECT_EQ(m.misses, 3);
  EXPECT_EQ(m.wake_max_us_at_most, 50);
  EXPECT_EQ(merged({1, 0, 0, 50}, {1, 0, 0, -1}).wake_max_us_at_most, -1);
}

TEST(EventStrings, SoundEventsPass) {
  hapticctrl_lcm::event_t e{};
  e.kind = "core_state";
  e.text = "fail-safe";
  const auto b = encoded(e);
  EXPECT_TRUE(event_strings_sound(b.data(), b.size()));
}

TEST(EventStrings, LyingLengthsAndTruncationFail) {
  hapticctrl_lcm::event_t e{};
  e.kind = "kind";
  e.text = "text";
  auto b = encoded(e);
  constexpr std::size_t kKindLength = 8 + 32;          // fingerprint + four int64
  for (const char first : {'\x80', '\x7f', '\x00'}) {  // INT32_MIN-ish, huge, zero
    std::string lying = b;
    lying.replace(kKindLength, 4, std::string{first, 0, 0, 0});
    EXPECT_FALSE(event_strings_sound(lying.data(), lying.size())) << int{first};
  }
  EXPECT_FALSE(event_strings_sound(b.data(), b.size() - 1));
  EXPECT_FALSE(event_strings_sound(b.data(), 10));
  std::string unterminated = b;
  unterminated.replace(kKindLength + 4 + 4, 1, "x");  // the kind's NUL
  EXPECT_FALSE(event_strings_sound(unterminated.data(), unterminated.size()));
}

TEST(TelemetryView, AWorldGoesOutWithItsGeomsAndContactsUpToItsCounts) {
  TelemetryView view;
  hapticctrl_lcm::world_t w{};
  w.steps = 12;
  w.geom_count = 2;
  w.geoms_total = 3;
  w.geoms[1].type = 2;
  w.geoms[1].size[0] = 0.03;
  w.geoms[1].pose[0] = 0.4;
  w.geoms[1].rgba[3] = 1.0F;
  w.geoms[1].coupled = true;
  w.geoms[2].type = 6;  // beyond the count: not sent
  w.contact_count = 1;
  w.contacts[0].normal[2] = 1.0;
  w.contacts[0].distance = -0.002;
  view.on_world(w, at(10ms));
  const Json f = Json::parse(view.next_frame(at(25ms)));
  EXPECT_DOUBLE_EQ(f["age_ms"]["world"].get<double>(), 15.0);
  const Json& world = f["world"];
  EXPECT_EQ(world["steps"], 12);
  EXPECT_EQ(world["geoms_total"], 3);
  ASSERT_EQ(world["geoms"].size(), 2U);
  EXPECT_EQ(world["geoms"][1]["type"], 2);
  EXPECT_DOUBLE_EQ(world["geoms"][1]["pose"][0].get<double>(), 0.4);
  EXPECT_EQ(world["geoms"][1]["coupled"], true);
  ASSERT_EQ(world["contacts"].size(), 1U);
  EXPECT_DOUBLE_EQ(world["contacts"][0]["distance"].get<double>(), -0.002);
}

TEST(WorldCounts, CountsBeyondTheArraysAreRefusedAndNotShown) {
  hapticctrl_lcm::world_t w{};
  EXPECT_TRUE(world_counts_sound(w));
  for (const auto& [geoms, total, contacts] :
       {std::tuple{-1, 0, 0}, std::tuple{129, 129, 0}, std::tuple{2, 1, 0}, std::tuple{0, 0, 9},
        std::tuple{0, 0, -3}}) {
    w.geom_count = geoms;
    w.geoms_total = total;
    w.contact_count = contacts;
    EXPECT_FALSE(world_counts_sound(w)) << geoms << " " << total << " " << contacts;
    TelemetryView view;
    view.on_world(w, TimePoint{});
    EXPECT_TRUE(Json::parse(view.next_frame(TimePoint{}))["world"].is_null());
  }
  w.geom_count = w.geoms_total = 128;
  w.contact_count = 8;
  EXPECT_TRUE(world_counts_sound(w));
}

}  // namespace
}  // namespace hapticctrl::web_bridge
