// Tests of events.hpp: the `events` region: a ring of the core's state transitions and faults, so
// that monitors (the LCM bridge) see every event even if they read only every few cycles.
#include "hapticctrl/shm/events.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

namespace hapticctrl::shm {
namespace {

std::vector<Event> drain(EventReader& r) {
  std::vector<Event> out;
  r.poll([&](const Event& e) { out.push_back(e); });
  return out;
}

TEST(Events, ReaderSeesEachEventOnceInOrder) {
  auto ring = std::make_unique<EventRing>();
  push_event(*ring, 1, 10, EventKind::kPower, 1, 0);
  EventReader reader(*ring);  // starts after what is already there
  push_event(*ring, 2, 20, EventKind::kEmergencyStop, 1, 0);
  push_event(*ring, 3, 30, EventKind::kClientSession, 0, 7);
  const auto seen = drain(reader);
  ASSERT_EQ(seen.size(), 2U);
  EXPECT_EQ(seen[0].kind, EventKind::kEmergencyStop);
  EXPECT_EQ(seen[0].index, 2U);
  EXPECT_EQ(seen[1].value, 7U);
  EXPECT_EQ(seen[1].time_ns, 30);
  EXPECT_TRUE(drain(reader).empty());
  EXPECT_EQ(reader.lost(), 0U);
  EventReader from_start(*ring, true);
  EXPECT_EQ(drain(from_start).size(), 3U);
}

TEST(Events, ALappedReaderCountsWhatItLostAndKeepsTheRest) {
  auto ring = std::make_unique<EventRing>();
  EventReader reader(*ring);
  const std::uint64_t total = kEventRingSize + 40;
  for (std::uint64_t i = 0; i < total; ++i) {
    push_event(*ring, i, 0, EventKind::kDegraded, static_cast<std::uint32_t>(i % 2), i);
  }
  const auto seen = drain(reader);
  EXPECT_EQ(reader.lost(), 40U);
  ASSERT_EQ(seen.size(), kEventRingSize);
  EXPECT_EQ(seen.front().value, 40U);
  EXPECT_EQ(seen.back().value, total - 1);
}

TEST(Events, ConcurrentReaderNeverSeesATornEvent) {
  auto ring = std::make_unique<EventRing>();
  EventReader reader(*ring);
  std::atomic<bool> done{false};
  constexpr std::uint64_t kCount = 200'000;
  std::thread writer([&] {
    for (std::uint64_t i = 0; i < kCount; ++i) {
      // Every field derives from i, so a mixed copy is detectable.
      push_event(*ring, i, static_cast<std::int64_t>(i) * 3, EventKind::kCoupling,
                 static_cast<std::uint32_t>(i & 0xFFFF), i * 7);
    }
    done = true;
  });
  std::uint64_t delivered = 0;
  std::uint64_t bad = 0;
  const auto check = [&](const Event& e) {
    const std::uint64_t i = e.index - 1;
    bad += (e.cycle != i || e.time_ns != static_cast<std::int64_t>(i) * 3 ||
            e.code != (i & 0xFFFF) || e.value != i * 7)
               ? 1U
               : 0U;
    ++delivered;
  };
  while (!done.load()) {
    reader.poll(check);
  }
  writer.join();
  reader.poll(check);
  EXPECT_EQ(bad, 0U);
  EXPECT_EQ(delivered + reader.lost(), kCount) << "every event delivered or counted as lost";
}

TEST(Events, KindsHaveNames) {
  EXPECT_STREQ(event_kind_name(EventKind::kCoreState), "core_state");
  EXPECT_STREQ(event_kind_name(static_cast<EventKind>(99)), "none");
}

}  // namespace
}  // namespace hapticctrl::shm
