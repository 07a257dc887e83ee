// Tests of black_box_ring.hpp: the core's last cycles in the segment, for whoever maps it after
// the core is gone.
#include "hapticctrl/shm/black_box_ring.hpp"

#include <gtest/gtest.h>

#include <atomic>
#include <memory>
#include <sstream>
#include <string>
#include <thread>

namespace hapticctrl::shm {
namespace {

/// A record whose every field follows from its cycle, so that a torn copy shows.
CycleRecord record_of(std::uint64_t cycle) {
  CycleRecord r;
  r.cycle = cycle;
  r.scheduled = static_cast<std::int64_t>(cycle) * 1000;
  r.wake_latency = static_cast<std::int64_t>(cycle % 97);
  r.state_word = static_cast<std::uint32_t>(cycle * 3);
  for (std::size_t j = 0; j < 6; ++j) {
    r.joint_position[j] = static_cast<double>(cycle) + static_cast<double>(j) * 0.5;
    r.joint_torque[j] = -static_cast<double>(cycle);
  }
  return r;
}

bool consistent(const CycleRecord& r) {
  const CycleRecord expected = record_of(r.cycle);
  return r.scheduled == expected.scheduled && r.wake_latency == expected.wake_latency &&
         r.state_word == expected.state_word && r.joint_position == expected.joint_position &&
         r.joint_torque == expected.joint_torque;
}

TEST(BlackBoxRing, KeepsEveryRecordInOrderUntilItComesRound) {
  auto ring = std::make_unique<BlackBoxRing>();
  EXPECT_TRUE(read_cycle_records(*ring).empty());
  for (std::uint64_t c = 1; c <= 10; ++c) {
    push_cycle_record(*ring, record_of(c));
  }
  const auto records = read_cycle_records(*ring);
  ASSERT_EQ(records.size(), 10U);
  for (std::size_t i = 0; i < records.size(); ++i) {
    EXPECT_EQ(records[i].cycle, i + 1);
    EXPECT_TRUE(consistent(records[i]));
  }
}

TEST(BlackBoxRing, KeepsTheNewestWhenItHasComeRound) {
  auto ring = std::make_unique<BlackBoxRing>();
  for (std::uint64_t c = 1; c <= kBlackBoxSlots + 5; ++c) {
    push_cycle_record(*ring, record_of(c));
  }
  const auto records = read_cycle_records(*ring);
  ASSERT_EQ(records.size(), kBlackBoxSlots);
  EXPECT_EQ(records.front().cycle, 6U);
  EXPECT_EQ(records.back().cycle, kBlackBoxSlots + 5);
}

TEST(BlackBoxRing, ASlotBeingRewrittenIsLeftOutNotTorn) {
  // A core killed in the middle of a record leaves that slot unstamped.
  auto ring = std::make_unique<BlackBoxRing>();
  for (std::uint64_t c = 1; c <= 3; ++c) {
    push_cycle_record(*ring, record_of(c));
  }
  ring->slots[1].stamp.store(0);
  const auto records = read_cycle_records(*ring);
  ASSERT_EQ(records.size(), 2U);
  EXPECT_EQ(records[0].cycle, 1U);
  EXPECT_EQ(records[1].cycle, 3U);
}

TEST(BlackBoxRing, AReaderBesideTheWriterNeverGetsATornRecord) {
  auto ring = std::make_unique<BlackBoxRing>();
  std::atomic<bool> stop{false};
  std::atomic<std::uint64_t> written{0};
  std::thread writer([&] {
    for (std::uint64_t c = 1; c <= 50'000'000 && !stop.load(std::memory_order_relaxed); ++c) {
      push_cycle_record(*ring, record_of(c));
      written.store(c, std::memory_order_relaxed);
    }
  });
  while (written.load() < kBlackBoxSlots) {
    std::this_thread::yield();
  }
  std::size_t checked = 0;
  for (int round = 0; round < 200; ++round) {  // each round reads the writer's newest 4096
    for (const CycleRecord& r : read_cycle_records(*ring)) {
      ASSERT_TRUE(consistent(r)) << "cycle " << r.cycle;
      ++checked;
    }
  }
  stop = true;
  writer.join();
  EXPECT_GT(checked, 0U);
}

TEST(BlackBoxRing, WritesTheBlackBoxCsvFormat) {
  CycleRecord stall;
  stall.cycle = 8;
  stall.flags = kRecordMiss | kRecordStall;
  stall.skipped = 12;
  std::istringstream csv(cycle_records_csv({stall}));
  std::string header;
  std::string line;
  std::getline(csv, header);
  std::getline(csv, line);
  EXPECT_EQ(header.rfind("cycle,scheduled_ns,wake_latency_ns,servo_start_delay_ns", 0), 0U);
  EXPECT_NE(header.find(",q1,q2,q3,q4,q5,q6,tau1,"), std::string::npos) << header;
  EXPECT_EQ(line.rfind("8,0,0,-1,-1,1,0,1,12,", 0), 0U) << line;
}

}  // namespace
}  // namespace hapticctrl::shm
