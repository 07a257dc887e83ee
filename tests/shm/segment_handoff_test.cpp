// The core's side of the handoff (segment_handoff.cpp): a sealed segment nobody can resize, and
// a server that refuses a process outside the core's user and group.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <string>

#include "hapticctrl/shm/segment.hpp"
#include "hapticctrl/shm/segment_handoff.hpp"
#include "support/child_process.hpp"
#include "support/segment_fixtures.hpp"

namespace hapticctrl::shm {
namespace {

using test::become_nobody;
using test::Child;
using test::paths_of;
using test::RuntimeDirectory;
using test::unique_instance;

TEST(SegmentHandoff, TheSegmentCannotBeResizedByAnyone) {
  const std::string name = unique_instance("seal");
  Segment core = Segment::create({.instance = name});
  HandedSegment writer = request_segment(name, true);
  EXPECT_NE(ftruncate(writer.segment.get(), 4096), 0) << "a writer truncating it";
  EXPECT_EQ(errno, EPERM);
  EXPECT_NE(ftruncate(writer.segment.get(), static_cast<off_t>(2 * kSegmentSize)), 0);
  EXPECT_NE(fcntl(writer.segment.get(), F_ADD_SEALS, F_SEAL_WRITE), 0) << "seals are sealed";
  // Even through the core's own descriptor table, as root could.
  const std::string by_path = "/proc/self/fd/" + std::to_string(writer.segment.get());
  const int reopened = open(by_path.c_str(), O_RDWR);
  ASSERT_GE(reopened, 0);
  EXPECT_NE(ftruncate(reopened, 0), 0);
  close(reopened);
  struct stat st {};
  ASSERT_EQ(fstat(writer.segment.get(), &st), 0);
  EXPECT_EQ(static_cast<std::size_t>(st.st_size), kSegmentSize);
  EXPECT_TRUE(Segment::attach(name).still_current());
}

TEST(SegmentHandoff, TheCoreRefusesAProcessOutsideItsUserAndGroup) {
  if (geteuid() != 0) {
    GTEST_SKIP() << "needs root to play another user";
  }
  const RuntimeDirectory directory("/tmp/hapticctrl-test-" + std::to_string(getpid()) + "-peer");
  const std::string name = unique_instance("peer");
  Segment core = Segment::create({.instance = name});
  // Open the file permissions wide, so that only the core's own credential check stands.
  ASSERT_EQ(chmod(directory.path().c_str(), 0755), 0);
  ASSERT_EQ(chmod(paths_of(name).socket.c_str(), 0666), 0);
  Child stranger([&] {
    if (!become_nobody()) {
      return 3;
    }
    try {
      Segment::attach(name);
    } catch (const ShmError& e) {
      return e.code() == ShmErrc::kPermissionDenied &&
                     std::string(e.what()).find("refused this process") != std::string::npos
                 ? 0
                 : 2;
    }
    return 1;
  });
  EXPECT_EQ(stranger.wait(), 0);
  EXPECT_EQ(core.refused_attaches(), 1U);
  EXPECT_NO_THROW(Segment::attach(name)) << "the core's own user is still served";
}

}  // namespace
}  // namespace hapticctrl::shm
