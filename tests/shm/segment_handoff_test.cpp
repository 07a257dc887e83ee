// The core's side of the handoff (segment_handoff.cpp): a sealed segment nobody can resize, and
// a server that refuses a process outside the core's user and group.
#include <fcntl.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <thread>
#include <vector>

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
using test::SilentPeers;
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
                     std::strstr(e.what(), "refused this process") != nullptr
                 ? 0
                 : 2;
    }
    return 1;
  });
  EXPECT_EQ(stranger.wait(), 0);
  EXPECT_EQ(core.refused_attaches(), 1U);
  EXPECT_NO_THROW(Segment::attach(name)) << "the core's own user is still served";
}

TEST(SegmentHandoff, SilentPeersAndAGarbageSenderDoNotHoldUpAnAttach) {
  // Served one at a time (backlog 16, 200 ms per silent peer), 16 silent connections made
  // `hapticctrl-hmi status` fail 2 times of 3 (J4 review of f3c5aec). Now every peer is served
  // at once: an attach beside 64 silent peers takes what it takes alone.
  const std::string name = unique_instance("silent");
  Segment core = Segment::create({.instance = name});
  SilentPeers held(name, 64);
  ASSERT_EQ(held.connected(), held.size());
  SilentPeers others(name, 2);  // a garbage sender, and half a request then nothing
  ASSERT_EQ(others.connected(), others.size());
  const std::array<unsigned char, 64> junk{0xde, 0xad, 0xbe, 0xef};
  ASSERT_EQ(send(others[0], junk.data(), junk.size(), MSG_NOSIGNAL), 64);
  ASSERT_EQ(send(others[1], junk.data(), 6, MSG_NOSIGNAL), 6);
  std::vector<double> took_ms;
  for (int i = 0; i < 5; ++i) {
    const auto start = std::chrono::steady_clock::now();
    EXPECT_NO_THROW((void)Segment::attach(name)) << "attach " << i;
    took_ms.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
            .count());
  }
  std::sort(took_ms.begin(), took_ms.end());
  std::printf("attach beside 64 silent peers: %.2f / %.2f / %.2f ms (min / median / max of 5)\n",
              took_ms.front(), took_ms[2], took_ms.back());
  // The median: one attach the machine stalled does not judge the server (J5).
  EXPECT_LT(took_ms[2], 100.0) << "the silent peers held the attach up";
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // past the silent peers' 200 ms
  EXPECT_GE(core.refused_attaches(), 66U) << "the garbage, the partial and 64 silent peers";
  held.close_all();
  others.close_all();
  EXPECT_NO_THROW((void)Segment::attach(name)) << "and the server serves on";
}

TEST(SegmentHandoff, WhenEverySlotIsHeldTheAttacherAsksAgainWithinItsBudget) {
  // 256 silent peers of the group hold every slot: the server closes a new connection at once,
  // and the attacher asks again (every 50 ms, 10 times) until a slot frees (200 ms).
  const std::string name = unique_instance("full");
  Segment core = Segment::create({.instance = name});
  const SilentPeers held(name, 256);
  ASSERT_EQ(held.connected(), held.size());
  std::this_thread::sleep_for(std::chrono::milliseconds(20));  // all accepted
  EXPECT_NO_THROW((void)Segment::attach(name));
}

}  // namespace
}  // namespace hapticctrl::shm
