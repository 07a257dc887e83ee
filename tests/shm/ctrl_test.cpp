// Tests of ctrl.hpp: the `ctrl` region: control commands from several writer processes to the core.
#include "hapticctrl/shm/ctrl.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <thread>
#include <vector>

namespace hapticctrl::shm {
namespace {

CtrlCode expected_code(std::uint32_t i) {
  return i % 97 == 0 ? CtrlCode::kEmergencyStop : CtrlCode::kPowerOn;
}

struct Mailbox {
  std::unique_ptr<CtrlRegion> region = std::make_unique<CtrlRegion>();
  std::unique_ptr<CtrlAckRegion> acks = std::make_unique<CtrlAckRegion>();
  CtrlWriter writer(std::size_t slot) {
    return CtrlWriter(region->slots[slot], acks->slots[slot], slot);
  }
  CtrlReader reader() { return CtrlReader(*region, *acks); }
};

std::vector<CtrlCommand> drain_all(CtrlReader reader) {
  std::vector<CtrlCommand> seen;
  reader.drain([&](const CtrlCommand& c) {
    seen.push_back(c);
    return true;
  });
  return seen;
}

TEST(Ctrl, CommandsArriveInOrderWithArguments) {
  Mailbox box;
  CtrlWriter w = box.writer(2);
  ASSERT_EQ(w.send(CtrlCode::kPowerOn, 0, 10), CtrlSendStatus::kQueued);
  ASSERT_EQ(w.send(CtrlCode::kInjectOverrun, 7, 11), CtrlSendStatus::kQueued);
  ASSERT_EQ(w.send(CtrlCode::kPowerOff, 0, 12), CtrlSendStatus::kQueued);
  const auto seen = drain_all(box.reader());
  ASSERT_EQ(seen.size(), 3U);
  EXPECT_EQ(seen[0].code, CtrlCode::kPowerOn);
  EXPECT_EQ(seen[1].code, CtrlCode::kInjectOverrun);
  EXPECT_EQ(seen[1].arg, 7U);
  EXPECT_EQ(seen[1].issued_ns, 11);
  EXPECT_EQ(seen[2].code, CtrlCode::kPowerOff);
  for (const auto& c : seen) {
    EXPECT_EQ(c.slot, 2U);
  }
  EXPECT_TRUE(drain_all(box.reader()).empty()) << "commands are consumed once";
}

TEST(Ctrl, WriterSeesConsumptionAndRejections) {
  Mailbox box;
  CtrlWriter w = box.writer(0);
  std::uint64_t index = 0;
  ASSERT_EQ(w.send(static_cast<CtrlCode>(77), 0, 0, &index), CtrlSendStatus::kQueued);
  EXPECT_FALSE(w.consumed(index));
  box.reader().drain([](const CtrlCommand& c) { return c.code != static_cast<CtrlCode>(77); });
  EXPECT_TRUE(w.consumed(index));
  EXPECT_EQ(w.rejected(), 1U);
  EXPECT_EQ(box.acks->slots[0].last_rejected_code.load(), 77U);
}

TEST(Ctrl, FullRingRefusesOrdinaryCommandsInsteadOfLosingThem) {
  Mailbox box;
  CtrlWriter w = box.writer(0);
  for (std::size_t i = 0; i < kCtrlRingSize; ++i) {
    ASSERT_EQ(w.send(CtrlCode::kPowerOn, static_cast<std::uint32_t>(i), 0),
              CtrlSendStatus::kQueued);
  }
  EXPECT_EQ(w.send(CtrlCode::kPowerOff, 0, 0), CtrlSendStatus::kFull);
  const auto seen = drain_all(box.reader());
  ASSERT_EQ(seen.size(), kCtrlRingSize);
  for (std::size_t i = 0; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].arg, i);
  }
  EXPECT_EQ(w.send(CtrlCode::kPowerOff, 0, 0), CtrlSendStatus::kQueued);
}

TEST(Ctrl, EmergencyStopOnFullRingIsDeliveredAtItsPlaceInTheSequence) {
  Mailbox box;
  CtrlWriter w = box.writer(1);
  for (std::size_t i = 0; i < kCtrlRingSize; ++i) {
    ASSERT_EQ(w.send(CtrlCode::kEmergencyReset, 0, 0), CtrlSendStatus::kQueued);
  }
  ASSERT_EQ(w.send(CtrlCode::kEmergencyStop, 0, 0), CtrlSendStatus::kQueued);
  // While the overflowed stop is pending, nothing may overtake it.
  EXPECT_EQ(w.send(CtrlCode::kEmergencyReset, 0, 0), CtrlSendStatus::kFull);
  const auto seen = drain_all(box.reader());
  ASSERT_EQ(seen.size(), kCtrlRingSize + 1);
  EXPECT_EQ(seen.back().code, CtrlCode::kEmergencyStop) << "the stop follows every earlier reset";
  ASSERT_EQ(w.send(CtrlCode::kEmergencyReset, 0, 0), CtrlSendStatus::kQueued);
  const auto after = drain_all(box.reader());
  ASSERT_EQ(after.size(), 1U);
  EXPECT_EQ(after[0].code, CtrlCode::kEmergencyReset);
}

TEST(Ctrl, OverrunByMisbehavingWriterIsCountedNotFatal) {
  Mailbox box;
  // A writer that ignores the acks and jumps its head far ahead.
  box.region->slots[3].head.store(kCtrlRingSize * 3);
  const auto seen = drain_all(box.reader());
  EXPECT_EQ(seen.size(), kCtrlRingSize);
  EXPECT_EQ(box.acks->slots[3].rejected.load(), 2 * kCtrlRingSize);
}

TEST(Ctrl, SlotsAreIndependent) {
  Mailbox box;
  CtrlWriter a = box.writer(0);
  CtrlWriter b = box.writer(5);
  a.send(CtrlCode::kPowerOn, 1, 0);
  b.send(CtrlCode::kEmergencyStop, 2, 0);
  a.send(CtrlCode::kPowerOff, 3, 0);
  const auto seen = drain_all(box.reader());
  ASSERT_EQ(seen.size(), 3U);
  std::vector<std::uint32_t> from_a;
  for (const auto& c : seen) {
    if (c.slot == 0) {
      from_a.push_back(c.arg);
    }
  }
  EXPECT_EQ(from_a, (std::vector<std::uint32_t>{1, 3}));
}

// Runs under ThreadSanitizer in CI: writers on several threads, the core draining concurrently;
// every writer's commands arrive complete and in order.
TEST(Ctrl, ConcurrentWritersLoseAndReorderNothing) {
  Mailbox box;
  constexpr std::uint32_t kPerWriter = 5000;
  constexpr std::size_t kWriters = 4;
  std::atomic<std::size_t> finished{0};
  std::vector<std::thread> writers;
  for (std::size_t s = 0; s < kWriters; ++s) {
    writers.emplace_back([&, s] {
      CtrlWriter w = box.writer(s);
      for (std::uint32_t i = 0; i < kPerWriter; ++i) {
        while (w.send(expected_code(i), i, 0) != CtrlSendStatus::kQueued) {
          std::this_thread::yield();
        }
      }
      finished.fetch_add(1);
    });
  }
  std::array<std::uint32_t, kWriters> next_arg{};
  std::array<std::uint32_t, kWriters> disorder{};
  std::size_t received = 0;
  auto handle = [&](const CtrlCommand& c) {
    const std::uint32_t want = next_arg[c.slot];
    // An overflowed e-stop carries no argument; it must still sit at its own position.
    const bool arg_ok = c.arg == want || (c.code == CtrlCode::kEmergencyStop && c.arg == 0);
    if (c.code != expected_code(want) || !arg_ok) {
      ++disorder[c.slot];
    }
    next_arg[c.slot] = next_arg[c.slot] + 1;
    ++received;
    return true;
  };
  CtrlReader reader = box.reader();
  while (finished.load() < kWriters) {
    reader.drain(handle);
  }
  reader.drain(handle);
  for (auto& t : writers) {
    t.join();
  }
  EXPECT_EQ(received, kWriters * kPerWriter);
  for (std::size_t s = 0; s < kWriters; ++s) {
    EXPECT_EQ(disorder[s], 0U) << "slot " << s;
  }
}

}  // namespace
}  // namespace hapticctrl::shm
