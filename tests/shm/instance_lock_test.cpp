// The instance lock (instance_lock.cpp): one live core per instance, named when another starts;
// the record a killed core leaves is taken over by the next.
#include <unistd.h>

#include <gtest/gtest.h>

#include <csignal>
#include <string>

#include "hapticctrl/shm/segment.hpp"
#include "support/child_process.hpp"
#include "support/segment_fixtures.hpp"

namespace hapticctrl::shm {
namespace {

using test::Child;
using test::exists;
using test::expect_shm_error;
using test::paths_of;
using test::unique_instance;

TEST(InstanceLock, SecondLiveCoreIsRefusedWithThePid) {
  const std::string name = unique_instance("dup");
  Segment core = Segment::create({.instance = name});
  expect_shm_error([&] { Segment::create({.instance = name}); }, ShmErrc::kAlreadyRunning,
                   "already running (core pid " + std::to_string(getpid()) + ")");
}

TEST(InstanceLock, SegmentOfDeadCoreIsDetectedThenReplaced) {
  const std::string name = unique_instance("stale");
  Child dead_core([&] {
    Segment core = Segment::create({.instance = name});
    raise(SIGKILL);  // dies holding the segment: no cleanup runs
    return 0;
  });
  ASSERT_EQ(dead_core.wait(), 128 + SIGKILL);
  ASSERT_TRUE(exists(paths_of(name).socket)) << "nothing removed it";
  expect_shm_error([&] { Segment::attach(name); }, ShmErrc::kNoController,
                   "left by a core that is gone");

  Segment core = Segment::create({.instance = name});
  EXPECT_EQ(core.header().generation, 2U);
  EXPECT_NO_THROW(Segment::attach(name));
}

}  // namespace
}  // namespace hapticctrl::shm
