// The retry rule of the multi-process tests (support/machine_retries.hpp): only an attempt the
// machine measurably disturbed is tried again; a failure on an undisturbed machine stands.
#include "support/machine_retries.hpp"

#include <gtest/gtest-spi.h>
#include <gtest/gtest.h>

namespace hapticctrl::test {
namespace {

/// The telemetry of a core that ran at `period_ms` and once woke `longest_ms` after the last.
shm::TelemetryPayload core_that_saw(double period_ms, double longest_ms) {
  shm::TelemetryPayload t;
  t.period_ns = static_cast<std::int64_t>(period_ms * 1e6);
  t.measured_period.max_ns = static_cast<std::int64_t>(longest_ms * 1e6);
  return t;
}

TEST(MachineDisturbance, AStallIsAWakeUpFivePeriodsLateARideThroughOrAFailSafeOnMisses) {
  MachineDisturbance d;
  d.add(core_that_saw(1.0, 4.9));
  EXPECT_FALSE(d.any());
  d.add(core_that_saw(1.0, 5.0));
  EXPECT_TRUE(d.any()) << d.text();

  MachineDisturbance late;
  shm::TelemetryPayload woke_late = core_that_saw(1.0, 1.0);
  woke_late.wake_latency.max_ns = 16'000'000;  // a skipped slot is no measured period
  late.add(woke_late);
  EXPECT_TRUE(late.any()) << late.text();

  MachineDisturbance ridden;
  shm::TelemetryPayload t = core_that_saw(1.0, 1.0);
  t.would_fail_safe = 1;
  ridden.add(t);
  EXPECT_TRUE(ridden.any());

  MachineDisturbance failed;
  t = core_that_saw(4.0, 4.0);
  t.stop_reason = static_cast<std::uint32_t>(shm::StopReason::kConsecutiveMisses);
  failed.add(t);
  EXPECT_TRUE(failed.any());
  EXPECT_NE(failed.text().find("failed safe"), std::string::npos);

  MachineDisturbance starved;
  shm::TelemetryPayload stale = core_that_saw(4.0, 4.0);
  stale.vpr_stale = 5;  // 20 ms at 4 ms
  starved.add(stale);
  EXPECT_TRUE(starved.any()) << "a starved client on a link nobody impairs";
  starved.link_impaired = true;
  EXPECT_FALSE(starved.any()) << "through hapticctrl-netem, stale samples are the test's";

  MachineDisturbance velocity;
  t.stop_reason = static_cast<std::uint32_t>(shm::StopReason::kVelocityLimit);
  velocity.add(t);
  EXPECT_FALSE(velocity.any()) << "a velocity fault is the software's, not the machine's";
}

TEST(RetryWhatTheMachineDisturbed, AFailureOnAnUndisturbedMachineStands) {
  int attempts = 0;
  EXPECT_NONFATAL_FAILURE(
      retry_what_the_machine_disturbed("undisturbed", 3,
                                       [&](int) {
                                         ++attempts;
                                         attempt_disturbance().add(core_that_saw(1.0, 1.2));
                                         ADD_FAILURE() << "the physics";
                                         return true;
                                       }),
      "the physics");
  EXPECT_EQ(attempts, 1);
}

TEST(RetryWhatTheMachineDisturbed, AFailureTheMachineDisturbedIsTriedAgain) {
  int attempts = 0;
  retry_what_the_machine_disturbed("disturbed once", 3, [&](int attempt) {
    ++attempts;
    if (attempt == 0) {
      attempt_disturbance().add(core_that_saw(1.0, 30.0));
      ADD_FAILURE() << "held back: the machine stalled this attempt";
    }
    return true;
  });
  EXPECT_EQ(attempts, 2);
}

TEST(RetryWhatTheMachineDisturbed, ALostAttemptIsTriedAgainAndAPassIsAPass) {
  int attempts = 0;
  retry_what_the_machine_disturbed("lost once", 3, [&](int attempt) {
    ++attempts;
    return attempt > 0;
  });
  EXPECT_EQ(attempts, 2);
}

}  // namespace
}  // namespace hapticctrl::test
