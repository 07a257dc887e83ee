// Tests of core_report.hpp: human and machine-readable reports of the core's figures.
#include "hapticctrl/rt_core/core_report.hpp"

#include <gtest/gtest.h>

namespace hapticctrl::rt_core {
namespace {

TEST(CoreReport, JsonCarriesTheFigures) {
  shm::TelemetryPayload t;
  t.cycle = 42;
  t.misses_total = 3;
  t.would_fail_safe = 7;
  t.first_would_fail_safe_cycle = 1234;
  t.wake_latency.p99_ns = 81'000;
  t.rt_mode = static_cast<std::uint32_t>(shm::RtMode::kFifoLocked);
  const std::string json = telemetry_json(t);
  EXPECT_EQ(json.front(), '{');
  EXPECT_EQ(json.back(), '}');
  EXPECT_NE(json.find("\"cycles\":42"), std::string::npos);
  EXPECT_NE(json.find("\"misses_total\":3"), std::string::npos);
  EXPECT_NE(json.find("\"would_fail_safe\":7,\"first_would_fail_safe_cycle\":1234"),
            std::string::npos);
  EXPECT_NE(json.find("\"wake_latency\":{\"min_ns\":0"), std::string::npos);
  EXPECT_NE(json.find("\"p99_ns\":81000"), std::string::npos);
  EXPECT_NE(json.find("\"rt_mode\":\"SCHED_FIFO+mlockall\""), std::string::npos);
}

}  // namespace
}  // namespace hapticctrl::rt_core
