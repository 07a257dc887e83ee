// Tests of debounced_flag.hpp: a flag whose changes are reported only once they have held for a
// number of cycles; shorter flips are counted as lapses and handed over with the next reported
// change.
#include "hapticctrl/rt_core/debounced_flag.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(DebouncedFlag, AChangeIsReportedOnceItHeldAndShorterFlipsAreCountedWithIt) {
  DebouncedFlag flag(3);
  std::uint64_t cycle = 0;
  EXPECT_FALSE(flag.update(false, ++cycle));
  // Two lapses of one and two cycles: no report.
  EXPECT_FALSE(flag.update(true, ++cycle));
  EXPECT_FALSE(flag.update(false, ++cycle));
  EXPECT_FALSE(flag.update(true, ++cycle));
  EXPECT_FALSE(flag.update(true, ++cycle));
  EXPECT_FALSE(flag.update(false, ++cycle));
  // A change that holds 3 cycles: reported on its third, with the two lapses.
  EXPECT_FALSE(flag.update(true, ++cycle));
  EXPECT_FALSE(flag.update(true, ++cycle));
  EXPECT_TRUE(flag.update(true, ++cycle));
  EXPECT_TRUE(flag.reported());
  EXPECT_EQ(flag.lapses(), 2U);
  EXPECT_FALSE(flag.update(true, ++cycle)) << "no change, nothing to report";
  // Back, held: reported with no lapse.
  EXPECT_FALSE(flag.update(false, ++cycle));
  EXPECT_FALSE(flag.update(false, ++cycle));
  EXPECT_TRUE(flag.update(false, ++cycle));
  EXPECT_FALSE(flag.reported());
  EXPECT_EQ(flag.lapses(), 0U);
}

TEST(DebouncedFlag, AHoldOfOneOrZeroReportsEveryChangeAtOnce) {
  DebouncedFlag flag(0);
  EXPECT_TRUE(flag.update(true, 1));
  EXPECT_TRUE(flag.update(false, 2));
  EXPECT_EQ(flag.lapses(), 0U);
}

TEST(DebouncedFlag, ACycleGapCountsAsTimeHeld) {
  // Cycles skipped by a stall: the change held across them.
  DebouncedFlag flag(20);
  EXPECT_FALSE(flag.update(true, 100));
  EXPECT_TRUE(flag.update(true, 130));
}

}  // namespace
}  // namespace hapticctrl::rt_core
