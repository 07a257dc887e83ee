// Tests of process_identity.hpp: a process identity that survives pid reuse: pid plus the process
// start time.
#include "hapticctrl/shm/process_identity.hpp"

#include <gtest/gtest.h>

#include "support/child_process.hpp"

namespace hapticctrl::shm {
namespace {

TEST(ProcessIdentity, SelfIsAlive) {
  const ProcessIdentity me = ProcessIdentity::self();
  EXPECT_EQ(me.pid, getpid());
  EXPECT_GT(me.start_ticks, 0U);
  EXPECT_TRUE(me.alive());
  EXPECT_TRUE(packed_identity_alive(pack_identity(me)));
}

TEST(ProcessIdentity, ExitedProcessIsNotAlive) {
  ProcessIdentity child_id;
  {
    test::ReadyPipe ready;
    test::Child child([&] {
      ready.signal();
      pause();
      return 0;
    });
    ASSERT_EQ(ready.wait(), 'r');
    child_id = ProcessIdentity{child.pid(), *ProcessIdentity::start_ticks_of(child.pid())};
    EXPECT_TRUE(child_id.alive());
    child.kill_now();
    child.wait();
  }
  EXPECT_FALSE(child_id.alive());
  EXPECT_FALSE(packed_identity_alive(pack_identity(child_id)));
}

TEST(ProcessIdentity, ReusedPidWithOtherStartTimeIsNotTheSameProcess) {
  ProcessIdentity impostor = ProcessIdentity::self();
  impostor.start_ticks += 1;
  EXPECT_FALSE(impostor.alive());
  EXPECT_FALSE(packed_identity_alive(pack_identity(impostor)));
}

TEST(ProcessIdentity, PackRoundTripsAndZeroMeansNobody) {
  const ProcessIdentity id{4'194'303, (std::uint64_t{1} << 41) + 12345};
  EXPECT_EQ(unpack_identity(pack_identity(id)), id);
  EXPECT_FALSE(packed_identity_alive(0));
}

}  // namespace
}  // namespace hapticctrl::shm
