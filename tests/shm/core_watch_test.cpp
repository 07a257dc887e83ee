// Tests of core_watch.hpp: how an attached process (the bridges) follows the core's cycles and
// notices within a few milliseconds that the core is gone: killed, crashed or replaced by a new
// core.
#include "hapticctrl/shm/core_watch.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <optional>
#include <thread>

#include "hapticctrl/base/time.hpp"
#include "support/child_process.hpp"

namespace hapticctrl::shm {
namespace {

using namespace std::chrono_literals;

/// A core (the creator, here in-process: flock locks belong to open file descriptions, so the
/// attacher's probe meets the creator's lock like another process's) and an attached watcher.
struct Rig {
  std::string instance = test::unique_instance("watch");
  std::optional<Segment> core{Segment::create({instance, "", 1'000'000})};
  Segment attached = Segment::attach(instance);
  CoreWatch watch{attached, 2ms};

  void beat(std::uint64_t cycle, std::int64_t at_ns) {
    core->header_for_writing().heartbeat_cycle.store(cycle);
    core->header_for_writing().heartbeat_ns.store(at_ns);
  }
};

TEST(CoreWatch, APublishEndsTheWaitAsACycle) {
  Rig rig;
  CoreWatch patient(rig.attached, 5s);
  std::atomic<bool> done{false};
  std::thread cycles([&] {  // a core cycling every millisecond, for at most 5 s
    for (int i = 0; i < 5000 && !done.load(); ++i) {
      rig.core->writable<RegionId::kVp>().publish(VpPayload{}, to_ns(MonotonicClock::now()));
      std::this_thread::sleep_for(1ms);
    }
  });
  EXPECT_EQ(patient.wait(), CoreWatch::Wake::kCycle);
  done = true;
  cycles.join();
}

TEST(CoreWatch, ALiveCoreThatPublishesNothingIsSilentNotGone) {
  Rig rig;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(rig.watch.wait(), CoreWatch::Wake::kSilent);
  }
  EXPECT_TRUE(rig.attached.core_alive());
}

TEST(CoreWatch, ACoreWithoutAStopReasonIsLostAndTheAgeOfItsLastHeartbeatIsKept) {
  Rig rig;
  rig.beat(42, to_ns(MonotonicClock::now()) - 5'000'000);
  rig.core.reset();  // the lock is released, as when the kernel ends a killed process
  ASSERT_EQ(rig.watch.wait(), CoreWatch::Wake::kCoreGone);
  EXPECT_EQ(rig.watch.last_cycle(), 42U);
  EXPECT_EQ(rig.watch.stop_reason(), static_cast<std::uint32_t>(StopReason::kCoreLost));
  EXPECT_GE(rig.watch.heartbeat_age_at_loss(), std::chrono::milliseconds(5));
  EXPECT_LT(rig.watch.heartbeat_age_at_loss(), std::chrono::seconds(1));
}

TEST(CoreWatch, ACoreThatStoppedInOrderKeepsItsReason) {
  Rig rig;
  rig.core->header_for_writing().stop_reason.store(
      static_cast<std::uint32_t>(StopReason::kStopRequested));
  rig.core.reset();
  ASSERT_EQ(rig.watch.wait(), CoreWatch::Wake::kCoreGone);
  EXPECT_EQ(rig.watch.stop_reason(), static_cast<std::uint32_t>(StopReason::kStopRequested));
}

TEST(CoreWatch, ACoreReplacedByANewOneIsGoneForTheOldSegment) {
  Rig rig;
  rig.core.reset();
  Segment next = Segment::create({rig.instance, "", 1'000'000});  // holds the lock again
  EXPECT_EQ(rig.watch.wait(), CoreWatch::Wake::kCoreGone) << "its segment is not the name's";
}

}  // namespace
}  // namespace hapticctrl::shm
