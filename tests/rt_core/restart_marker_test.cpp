// Tests of restart_marker.hpp: whether the core before this one stopped in order.
#include "hapticctrl/rt_core/restart_marker.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <string>

#include "support/temp_directory.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::TempDirectory;

TEST(RestartMarker, ACoreThatDidNotStopInOrderIsNoticedByTheNext) {
  TempDirectory temp("restart");
  const PrivateDirectory dir(temp.path());
  {
    RestartMarker first(dir, "lab");
    EXPECT_FALSE(first.left_by_earlier()) << "a fresh start";
    EXPECT_TRUE(dir.contains("hapticctrl-running.lab")) << "marked while it runs";
  }  // killed, crashed or failed safe: the marker stays
  struct stat st {};
  ASSERT_EQ(stat((temp / "hapticctrl-running.lab").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600U);
  RestartMarker second(dir, "lab");
  ASSERT_TRUE(second.left_by_earlier());
  EXPECT_NE(second.left_note().find("running since 20"), std::string::npos) << second.left_note();
  EXPECT_NE(second.left_note().find("(core pid " + std::to_string(getpid()) + ")"),
            std::string::npos);
  EXPECT_FALSE(RestartMarker(dir, "lab-2").left_by_earlier()) << "each instance its own";
  second.stopped_in_order();
  EXPECT_FALSE(dir.contains("hapticctrl-running.lab"));
  EXPECT_FALSE(RestartMarker(dir, "lab").left_by_earlier()) << "after an orderly stop";
}

TEST(RestartMarker, ALinkAtTheMarkersNameCountsAsLeftAndIsNeverFollowed) {
  TempDirectory temp("restart");
  const std::string target = temp / "target";
  ASSERT_EQ(symlink(target.c_str(), (temp / "hapticctrl-running.lab").c_str()), 0);
  const PrivateDirectory dir(temp.path());
  const RestartMarker marker(dir, "lab");
  EXPECT_TRUE(marker.left_by_earlier()) << "the safe side";
  struct stat st {};
  EXPECT_NE(stat(target.c_str(), &st), 0) << "the link's target was never written";
  ASSERT_EQ(lstat((temp / "hapticctrl-running.lab").c_str(), &st), 0);
  EXPECT_TRUE(S_ISREG(st.st_mode)) << "replaced by this core's own marker";
}

}  // namespace
}  // namespace hapticctrl::rt_core
