// Tests of black_box.hpp: a preallocated ring of the last cycles' records, written out as CSV on
// fail-safe, so that the seconds before a fault can be examined afterwards (the flight-recorder of
// the core).
#include "hapticctrl/rt_core/black_box.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <string>

namespace hapticctrl::rt_core {
namespace {

TEST(BlackBox, KeepsOnlyTheNewestRecordsOldestFirst) {
  BlackBox box(3);
  for (std::uint64_t c = 1; c <= 5; ++c) {
    box.record(CycleRecord{.cycle = c});
  }
  ASSERT_EQ(box.size(), 3U);
  EXPECT_EQ(box.at(0).cycle, 3U);
  EXPECT_EQ(box.at(2).cycle, 5U);
}

TEST(BlackBox, WritesCsvWithHeaderAndOneLinePerRecord) {
  BlackBox box(10);
  box.record(CycleRecord{.cycle = 7, .wake_latency = 1234, .flags = kRecordMiss | kRecordDegraded});
  box.record(CycleRecord{.cycle = 8, .flags = kRecordMiss | kRecordStall, .skipped = 12});
  const std::string path = "/tmp/hapticctrl-bb-test-" + std::to_string(getpid()) + ".csv";
  box.write_csv(path);
  std::ifstream in(path);
  std::string header;
  std::string first;
  std::string second;
  std::getline(in, header);
  std::getline(in, first);
  std::getline(in, second);
  EXPECT_EQ(header.rfind("cycle,scheduled_ns,wake_latency_ns", 0), 0U);
  EXPECT_NE(header.find(",miss,degraded,stall,skipped,consecutive_misses,"), std::string::npos)
      << header;
  EXPECT_EQ(first.rfind("7,0,1234,-1,-1,1,1,0,0,", 0), 0U) << first;
  EXPECT_EQ(second.rfind("8,0,0,-1,-1,1,0,1,12,", 0), 0U) << second;
  std::remove(path.c_str());
}

TEST(BlackBox, UnwritablePathIsAClearError) {
  BlackBox box(1);
  EXPECT_THROW(box.write_csv("/nonexistent-dir/x.csv"), std::runtime_error);
}

}  // namespace
}  // namespace hapticctrl::rt_core
