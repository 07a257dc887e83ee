// Tests of black_box.hpp: a preallocated ring of the last cycles' records, written out as CSV on
// fail-safe, so that the seconds before a fault can be examined afterwards (the flight-recorder of
// the core).
#include "hapticctrl/rt_core/black_box.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <sys/stat.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>

#include "support/temp_directory.hpp"

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
  std::istringstream in(box.csv());
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
}

TEST(BlackBox, IsStoredPrivatelyAndOnlyTheNewestAreKept) {
  test::TempDirectory temp("blackbox");
  const PrivateDirectory dir(temp.path());
  BlackBox box(4);
  box.record(CycleRecord{.cycle = 1});
  std::string last;
  for (int pid = 100; pid < 105; ++pid) {
    last = store_black_box(box, dir, "lab", pid, 3);
  }
  EXPECT_EQ(last, temp / "hapticctrl-blackbox-lab.104.csv");
  const auto kept = dir.files("hapticctrl-blackbox-lab.", ".csv");
  ASSERT_EQ(kept.size(), 3U);
  EXPECT_NE(std::find(kept.begin(), kept.end(), "hapticctrl-blackbox-lab.104.csv"), kept.end());
  struct stat st {};
  ASSERT_EQ(stat(last.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600U);
  // Another instance whose name starts alike keeps its own.
  (void)store_black_box(box, dir, "lab-2", 1, 1);
  (void)store_black_box(box, dir, "lab", 200, 1);
  EXPECT_EQ(dir.files("hapticctrl-blackbox-lab.", ".csv").size(), 1U);
  EXPECT_EQ(dir.files("hapticctrl-blackbox-lab-2.", ".csv").size(), 1U);
}

TEST(BlackBox, ALinkPlantedAtItsNameIsLeftAloneAndNeverFollowed) {
  test::TempDirectory temp("blackbox");
  { std::ofstream(temp / "victim") << "precious"; }
  ASSERT_EQ(symlink((temp / "victim").c_str(), (temp / "hapticctrl-blackbox-lab.42.csv").c_str()),
            0);
  const PrivateDirectory dir(temp.path());
  BlackBox box(1);
  box.record(CycleRecord{.cycle = 9});
  EXPECT_EQ(store_black_box(box, dir, "lab", 42, 20), temp / "hapticctrl-blackbox-lab.42.2.csv");
  std::ifstream victim(temp / "victim");
  std::string text;
  std::getline(victim, text);
  EXPECT_EQ(text, "precious");
}

}  // namespace
}  // namespace hapticctrl::rt_core
