// Tests of layout.hpp: layout of one controller instance's shared-memory segment.
#include "hapticctrl/shm/layout.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::shm {
namespace {

TEST(Layout, EveryPartStartsOnItsOwnPageSoItCanBeMappedWithItsOwnProtection) {
  EXPECT_EQ(kClaimsOffset % kPageSize, 0U);
  for (std::size_t i = 0; i < kRegionCount; ++i) {
    const auto id = static_cast<RegionId>(i);
    EXPECT_EQ(region_offset(id) % kPageSize, 0U) << region_name(id);
    EXPECT_GE(region_offset(static_cast<RegionId>(i + 1)), region_offset(id) + kRegionSizes[i]);
  }
  EXPECT_EQ(kSegmentSize % kPageSize, 0U);
}

TEST(Layout, RegionsHaveTheirContractNames) {
  EXPECT_EQ(region_name(RegionId::kVpr), "VPr");
  EXPECT_EQ(region_name(RegionId::kVp), "VP");
  EXPECT_EQ(region_name(RegionId::kForce), "force");
  EXPECT_EQ(region_name(RegionId::kPosition), "position");
  EXPECT_EQ(region_name(RegionId::kCtrl), "ctrl");
  EXPECT_EQ(region_name(RegionId::kCtrlAck), "ctrl_ack");
  EXPECT_EQ(region_name(RegionId::kTelemetry), "telemetry");
}

}  // namespace
}  // namespace hapticctrl::shm
