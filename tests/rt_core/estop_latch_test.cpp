// Tests of estop_latch.hpp: the latched emergency stop as a file that outlives the core.
#include "hapticctrl/rt_core/estop_latch.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <fstream>
#include <string>

#include "support/temp_directory.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::TempDirectory;

TEST(EstopLatchFile, ALatchedStopOutlivesItsCoreUntilAReset) {
  TempDirectory temp("estop");
  const PrivateDirectory dir(temp.path());
  {
    EstopLatchFile first(dir, "lab");
    EXPECT_FALSE(first.left_latched()) << "nothing left: a fresh start";
    first.follow(false);
    EXPECT_FALSE(dir.contains("hapticctrl-estop.lab"));
    first.follow(true);  // the operator pressed the stop; then the core dies
  }
  struct stat st {};
  ASSERT_EQ(stat((temp / "hapticctrl-estop.lab").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 07777, 0600U);
  EstopLatchFile second(dir, "lab");
  ASSERT_TRUE(second.left_latched());
  EXPECT_NE(second.left_note().find("latched at 20"), std::string::npos) << second.left_note();
  EXPECT_NE(second.left_note().find("(core pid " + std::to_string(getpid()) + ")"),
            std::string::npos)
      << second.left_note();
  EXPECT_FALSE(EstopLatchFile(dir, "lab-2").left_latched()) << "each instance its own";
  second.follow(true);   // still latched: nothing to do
  second.follow(false);  // reset by an operator
  EXPECT_FALSE(dir.contains("hapticctrl-estop.lab"));
  EXPECT_FALSE(EstopLatchFile(dir, "lab").left_latched());
}

TEST(EstopLatchFile, AnythingAtTheLatchsNameCountsAsLatched) {
  // The safe side: an unreadable file, or a link, is a latch whose note cannot be read.
  TempDirectory temp("estop");
  ASSERT_EQ(symlink("/nonexistent", (temp / "hapticctrl-estop.lab").c_str()), 0);
  const PrivateDirectory dir(temp.path());
  EstopLatchFile latch(dir, "lab");
  EXPECT_TRUE(latch.left_latched());
  EXPECT_EQ(latch.left_note(), "");
  latch.follow(false);
  EXPECT_FALSE(dir.contains("hapticctrl-estop.lab")) << "a reset removes it (the link itself)";
}

}  // namespace
}  // namespace hapticctrl::rt_core
