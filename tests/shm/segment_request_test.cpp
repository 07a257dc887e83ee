// The attacher's side of the handoff (segment_request.cpp): what a reader is handed, and the
// errors that say why an attach failed (no controller, permission, a planted controller).
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/shm/segment_handoff.hpp"
#include "support/child_process.hpp"
#include "support/segment_fixtures.hpp"

namespace hapticctrl::shm {
namespace {

using test::become_nobody;
using test::Child;
using test::expect_shm_error;
using test::paths_of;
using test::ReadyPipe;
using test::RuntimeDirectory;
using test::unique_instance;

TEST(SegmentRequest, AReaderHoldsAReadOnlyDescriptor) {
  const std::string name = unique_instance("rofd");
  Segment core = Segment::create({.instance = name});
  HandedSegment reader = request_segment(name, false);
  EXPECT_EQ(fcntl(reader.segment.get(), F_GETFL) & O_ACCMODE, O_RDONLY);
  EXPECT_EQ(mmap(nullptr, kPageSize, PROT_READ | PROT_WRITE, MAP_SHARED, reader.segment.get(), 0),
            MAP_FAILED);
  EXPECT_EQ(reader.core_pid, getpid());
  EXPECT_EQ(reader.core_uid, geteuid());
}

TEST(SegmentRequest, AttachWithoutControllerSaysSo) {
  expect_shm_error([] { Segment::attach(unique_instance("none")); }, ShmErrc::kNoController,
                   "no controller is running");
}

TEST(SegmentRequest, PermissionDeniedIsExplained) {
  const std::string name = unique_instance("perm");
  Segment core = Segment::create({.instance = name});
  Child other_user([&] {
    if (geteuid() == 0) {
      if (!become_nobody()) {
        return 3;
      }
    } else {
      chmod(paths_of(name).socket.c_str(), 0);
    }
    try {
      Segment::attach(name);
    } catch (const ShmError& e) {
      return e.code() == ShmErrc::kPermissionDenied &&
                     std::strstr(e.what(), "permission denied") != nullptr
                 ? 0
                 : 2;
    }
    return 1;
  });
  EXPECT_EQ(other_user.wait(), 0);
}

TEST(SegmentRequest, AControllerPlantedByAnotherUserIsRefused) {
  if (geteuid() != 0) {
    GTEST_SKIP() << "needs root to play another user";
  }
  // An unprivileged user makes a directory of its own and starts a "core" there, hoping that
  // root's tools attach to it.
  const RuntimeDirectory directory("/tmp/hapticctrl-test-" + std::to_string(getpid()) + "-plant");
  const std::string name = unique_instance("plant");
  ReadyPipe ready;
  Child planter([&] {
    if (!become_nobody()) {
      return 3;
    }
    Segment planted = Segment::create({.instance = name});
    ready.signal();
    pause();
    return 0;
  });
  ASSERT_EQ(ready.wait(), 'r');
  expect_shm_error([&] { Segment::attach(name); }, ShmErrc::kInsecure,
                   "belongs to uid 65534, which is neither root nor this process's user");
  expect_shm_error([&] { Segment::create({.instance = name}); }, ShmErrc::kInsecure,
                   "could have been planted");
}

}  // namespace
}  // namespace hapticctrl::shm
