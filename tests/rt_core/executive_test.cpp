// Fake-clock scenarios of the CLOCK/SERVO cycle: each runs seconds of controller time in
// microseconds of real time, deterministically.
#include "hapticctrl/rt_core/executive.hpp"

#include <gtest/gtest.h>

#include <vector>

#include <memory>

#include "support/default_dynamics.hpp"
#include "support/in_memory_regions.hpp"
#include "support/mock_arm.hpp"
#include "support/scripted_servo_tasks.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::MockArm;
using test::ScriptedServoTasks;

constexpr Duration kPeriod = 1ms;
constexpr TimePoint kStart{1'000s + 123'456ns};  // deliberately not slot-aligned

/// Everything one scenario needs, with in-process regions.
struct Rig {
  explicit Rig(ScriptedServoTasks::CycleLength main_duration, ExecutiveConfig config = {})
      : tasks(clock, main_task, degraded_task, shared.overrun, kPeriod, std::move(main_duration)),
        executive(with_defaults(config), clock, tasks, shared, arm,
                  ExecutiveOutputs{nullptr, telemetry.get(), position.get(), events.get()}, box) {}

  static ExecutiveConfig with_defaults(ExecutiveConfig c) {
    c.period = kPeriod;
    if (c.duration == Duration{0}) {
      c.duration = 200ms;
    }
    return c;
  }
  /// The k-th slot's deadline (k from 0), as the executive computes it.
  static TimePoint slot(std::uint64_t k) {
    return TimePoint{(kStart.time_since_epoch() / kPeriod + 2) * kPeriod} + k * kPeriod;
  }
  shm::CtrlWriter ctrl_writer() { return regions.ctrl_writer(); }

  FakeClock clock{kStart};
  MockArm arm;
  test::InMemoryRegions regions;
  std::unique_ptr<shm::SeqlockCell<shm::VpPayload>>& vp = regions.vp;
  std::unique_ptr<shm::SeqlockCell<shm::PositionPayload>>& position = regions.position;
  std::unique_ptr<shm::SeqlockCell<shm::TelemetryPayload>>& telemetry = regions.telemetry;
  ServoShared shared{arm, regions.ctrl_reader(), regions.servo_regions(), true};
  ServoTask main_task{shared, TaskRole::kMain, ServoLaw(test::default_dynamics())};
  ServoTask degraded_task{shared, TaskRole::kDegraded, ServoLaw(test::default_dynamics())};
  std::unique_ptr<shm::EventRing> events = std::make_unique<shm::EventRing>();
  BlackBox box{4000};
  ScriptedServoTasks tasks;
  Executive executive;
};

/// Main SERVO takes `slow` for the given cycles, 50 µs otherwise.
ScriptedServoTasks::CycleLength slow_for(std::uint64_t first, std::uint64_t last, Duration slow) {
  return [=](std::uint64_t cycle) {
    return (cycle >= first && cycle <= last) ? slow : Duration{50us};
  };
}

TEST(Executive, NominalRunHasNoMissAndStopsWhenDurationElapses) {
  Rig rig(slow_for(0, 0, 0ns));
  const ExecutiveResult r = rig.executive.run();
  EXPECT_EQ(r.reason, shm::StopReason::kDurationElapsed);
  EXPECT_FALSE(r.fail_safe);
  EXPECT_EQ(rig.executive.monitor().total_misses(), 0U);
  // The first slot is aligned and ~2 periods after start: 200 slots fit in 200 ms.
  EXPECT_EQ(rig.executive.cycles(), 200U);
  const shm::TelemetryPayload t = rig.executive.telemetry();
  EXPECT_EQ(t.wake_latency.max_ns, 0);  // a fake clock wakes exactly on time
  EXPECT_EQ(t.servo_start_delay.p50_ns, to_ns(5us));
  EXPECT_EQ(t.measured_period.min_ns, to_ns(kPeriod));
  EXPECT_EQ(t.measured_period.max_ns, to_ns(kPeriod));
}

TEST(Executive, FourMissesThenAGoodCycleDoNotTrip) {
  Rig rig(slow_for(10, 13, kPeriod * 9 / 10));  // past the 3/4 check, done before next release
  const ExecutiveResult r = rig.executive.run();
  EXPECT_FALSE(r.fail_safe);
  EXPECT_EQ(rig.executive.monitor().total_misses(), 4U);
  EXPECT_EQ(rig.executive.telemetry().degraded_cycles, 0U);
}

TEST(Executive, ExactlyFiveConsecutiveMissesTripTheFailSafe) {
  Rig rig(slow_for(10, 14, kPeriod * 9 / 10));
  const ExecutiveResult r = rig.executive.run();
  EXPECT_TRUE(r.fail_safe);
  EXPECT_EQ(r.reason, shm::StopReason::kConsecutiveMisses);
  EXPECT_EQ(rig.executive.cycles(), 14U) << "trips on the 5th miss, not later";
  EXPECT_EQ(rig.executive.monitor().consecutive_misses(), 5U);
}

TEST(Executive, FailSafeRunsItsStepsInOrderAndLeavesTheArmSafe) {
  Rig rig(slow_for(10, 14, kPeriod * 9 / 10));
  rig.ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  const ExecutiveResult r = rig.executive.run();
  ASSERT_TRUE(r.fail_safe);
  ASSERT_EQ(r.step_count, 4U);
  EXPECT_EQ(r.steps[0], StopStep::kInhibitCommands);
  EXPECT_EQ(r.steps[1], StopStep::kPowerOffSupply);
  EXPECT_EQ(r.steps[2], StopStep::kCloseProtocol);
  EXPECT_EQ(r.steps[3], StopStep::kStopTasks);
  EXPECT_GT(rig.arm.enabled_sends, 0) << "the arm was powered before";
  EXPECT_FALSE(rig.arm.last.enable);
  EXPECT_TRUE(rig.arm.last.torque.isZero());
  EXPECT_FALSE(rig.arm.supply);
  EXPECT_TRUE(rig.tasks.stopped);
  EXPECT_TRUE(r.protocol_closed_in_vp);
  shm::VpPayload vp;
  ASSERT_TRUE(rig.vp->read(vp).ok());
  EXPECT_EQ(vp.core_state, static_cast<std::uint32_t>(shm::CoreState::kFailSafe));
  EXPECT_EQ(vp.stop_reason, static_cast<std::uint32_t>(shm::StopReason::kConsecutiveMisses));
  EXPECT_NE(vp.state_word & shm::state_bits::kFailSafe, 0U);
  EXPECT_EQ(vp.state_word & shm::state_bits::kPowered, 0U);
  shm::TelemetryPayload t;
  ASSERT_TRUE(rig.telemetry->read(t).ok());
  EXPECT_EQ(t.core_state, static_cast<std::uint32_t>(shm::CoreState::kFailSafe));
}

TEST(Executive, StateTransitionsAndTheFailSafeAreEvents) {
  Rig rig(slow_for(10, 14, kPeriod * 9 / 10));
  shm::EventReader reader(*rig.events);
  rig.ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  (void)rig.executive.run();
  std::vector<shm::Event> seen;
  reader.poll([&](const shm::Event& e) { seen.push_back(e); });
  EXPECT_EQ(reader.lost(), 0U);
  const auto first = [&](shm::EventKind kind, std::uint32_t code) -> const shm::Event* {
    for (const shm::Event& e : seen) {
      if (e.kind == kind && e.code == code) {
        return &e;
      }
    }
    return nullptr;
  };
  ASSERT_FALSE(seen.empty());
  EXPECT_EQ(seen.front().kind, shm::EventKind::kCoreState);
  EXPECT_EQ(seen.front().code, static_cast<std::uint32_t>(shm::CoreState::kRunning));
  const shm::Event* powered = first(shm::EventKind::kPower, 1);
  ASSERT_NE(powered, nullptr);
  EXPECT_LE(powered->cycle, 2U);
  const shm::Event& last = seen.back();
  EXPECT_EQ(last.kind, shm::EventKind::kCoreState);
  EXPECT_EQ(last.code, static_cast<std::uint32_t>(shm::CoreState::kFailSafe));
  EXPECT_EQ(last.value, static_cast<std::uint64_t>(shm::StopReason::kConsecutiveMisses));
  EXPECT_EQ(last.cycle, 14U);
  for (std::size_t i = 1; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].index, seen[i - 1].index + 1) << "in order, none skipped";
  }
}

TEST(Executive, TelemetryCarriesTheCoarseWakeHistogram) {
  Rig rig([](std::uint64_t) { return 50us; });
  (void)rig.executive.run();
  shm::TelemetryPayload t;
  ASSERT_TRUE(rig.telemetry->read(t).ok());
  std::uint64_t total = 0;
  for (const std::uint64_t c : t.wake_histogram) {
    total += c;
  }
  EXPECT_EQ(total, t.wake_latency.samples);
  EXPECT_GT(total, 0U);
}

TEST(Executive, ChronicOneInThreeIsReportedButDoesNotTripByDefault) {
  ExecutiveConfig config;
  config.duration = 3s;
  Rig rig([](std::uint64_t c) { return c % 3 == 0 ? kPeriod * 9 / 10 : 50us; }, config);
  const ExecutiveResult r = rig.executive.run();
  EXPECT_FALSE(r.fail_safe);
  const shm::TelemetryPayload t = rig.executive.telemetry();
  EXPECT_NEAR(t.window_miss_ppm, 333'333, 1'000);
  EXPECT_GT(t.leaky_bucket_score, 0U);
  EXPECT_LE(t.consecutive_misses, 1U);
}

TEST(Executive, ChronicMissesTripWhenAThresholdIsConfigured) {
  ExecutiveConfig config;
  config.duration = 3s;
  config.chronic.trip_window_ppm = 200'000;
  Rig rig([](std::uint64_t c) { return c % 3 == 0 ? kPeriod * 9 / 10 : 50us; }, config);
  const ExecutiveResult r = rig.executive.run();
  EXPECT_TRUE(r.fail_safe);
  EXPECT_EQ(r.reason, shm::StopReason::kChronicMisses);
  EXPECT_EQ(rig.executive.cycles(), 1002U) << "trips at the first miss once the window is full";
}

TEST(Executive, BenchmarkModeCountsWouldBeFailSafesAndRunsOn) {
  // A 12-period stall of the clock (a VM stall) and, later, five overruns of the SERVO: each
  // would fail the core safe; in benchmark mode both are counted and the run goes on.
  ExecutiveConfig config;
  config.ride_through_misses = true;
  Rig rig(slow_for(100, 104, kPeriod * 9 / 10), config);
  rig.clock.oversleep_at(Rig::slot(40), kPeriod * 12);
  const ExecutiveResult r = rig.executive.run();
  EXPECT_FALSE(r.fail_safe);
  EXPECT_EQ(r.reason, shm::StopReason::kDurationElapsed);
  const shm::TelemetryPayload t = rig.executive.telemetry();
  EXPECT_EQ(t.would_fail_safe, 2U);
  EXPECT_EQ(t.first_would_fail_safe_cycle, 40U);
  EXPECT_GT(rig.executive.cycles(), 180U);

  // The same stall without benchmark mode fails safe, and counts nothing as would-be.
  Rig strict(slow_for(0, 0, 0ns));
  strict.clock.oversleep_at(Rig::slot(40), kPeriod * 12);
  EXPECT_TRUE(strict.executive.run().fail_safe);
  EXPECT_EQ(strict.executive.telemetry().would_fail_safe, 0U);
}

TEST(Executive, ServoOverrunOf2Point7PeriodsMissesThreeSlotsRunsTwoDegraded) {
  Rig rig(slow_for(10, 10, kPeriod * 27 / 10));
  const ExecutiveResult r = rig.executive.run();
  EXPECT_FALSE(r.fail_safe);
  const shm::TelemetryPayload t = rig.executive.telemetry();
  EXPECT_EQ(t.misses_total, 3U);
  EXPECT_EQ(t.degraded_cycles, 2U);
  EXPECT_EQ(t.late_servo_discarded, 1U);
  std::vector<std::uint32_t> degraded_edges;  // entering, then leaving the degraded SERVO
  shm::EventReader(*rig.events, true).poll([&](const shm::Event& e) {
    if (e.kind == shm::EventKind::kDegraded) {
      degraded_edges.push_back(e.code);
    }
  });
  EXPECT_EQ(degraded_edges, (std::vector<std::uint32_t>{1, 0}));
}

TEST(Executive, ClockWakingLateBy2Point7PeriodsSkipsThreeSlots) {
  Rig rig(slow_for(0, 0, 0ns));
  rig.clock.oversleep_at(Rig::slot(10), kPeriod * 27 / 10);
  const ExecutiveResult r = rig.executive.run();
  EXPECT_FALSE(r.fail_safe);
  const shm::TelemetryPayload t = rig.executive.telemetry();
  EXPECT_EQ(t.skipped_slots, 3U);
  EXPECT_EQ(t.misses_total, 3U);
  EXPECT_EQ(rig.executive.cycles(), 200U - 3U) << "skipped slots are not run back to back";
  EXPECT_EQ(t.wake_latency.max_ns, to_ns(kPeriod * 27 / 10));
}

TEST(Executive, ClockWakingSlightlyPastHalfAPeriodSkipsOnlyThatSlot) {
  Rig rig(slow_for(0, 0, 0ns));
  rig.clock.oversleep_at(Rig::slot(20), kPeriod * 6 / 10);
  rig.executive.run();
  EXPECT_EQ(rig.executive.telemetry().skipped_slots, 1U);
}

TEST(Executive, WakeUpLessThanHalfAPeriodLateRunsTheCycleLate) {
  Rig rig(slow_for(0, 0, 0ns));
  rig.clock.oversleep_at(Rig::slot(20), kPeriod * 3 / 10);
  rig.executive.run();
  EXPECT_EQ(rig.executive.telemetry().skipped_slots, 0U);
  EXPECT_EQ(rig.executive.telemetry().wake_latency.max_ns, to_ns(kPeriod * 3 / 10));
}

TEST(Executive, StopRequestMidRunStopsInOrderWithoutFault) {
  Rig rig([&](std::uint64_t) { return 50us; });
  // The request is queued before the run and consumed by the first SERVO cycle.
  rig.ctrl_writer().send(shm::CtrlCode::kPowerOn, 0, 0);
  rig.ctrl_writer().send(shm::CtrlCode::kStop, 0, 0);
  const ExecutiveResult r = rig.executive.run();
  EXPECT_EQ(r.reason, shm::StopReason::kStopRequested);
  EXPECT_FALSE(r.fail_safe);
  EXPECT_EQ(rig.executive.cycles(), 1U);
  ASSERT_EQ(r.step_count, 4U);
  EXPECT_FALSE(rig.arm.supply);
  shm::VpPayload vp;
  ASSERT_TRUE(rig.vp->read(vp).ok());
  EXPECT_EQ(vp.core_state, static_cast<std::uint32_t>(shm::CoreState::kStopping));
  EXPECT_EQ(vp.stop_reason, static_cast<std::uint32_t>(shm::StopReason::kStopRequested));
}

TEST(Executive, ExternalStopFlagEndsTheRun) {
  Rig rig(slow_for(0, 0, 0ns));
  std::atomic<bool> stop{true};
  const ExecutiveResult r = rig.executive.run(&stop);
  EXPECT_EQ(r.reason, shm::StopReason::kSignal);
  EXPECT_FALSE(r.fail_safe);
}

TEST(Executive, DegradedCycleCommitsAndLateMainOutputIsDiscarded) {
  Rig rig(slow_for(10, 10, kPeriod * 3 / 2));
  rig.executive.run();
  EXPECT_EQ(rig.tasks.discarded, 1);
  EXPECT_EQ(rig.executive.telemetry().degraded_cycles, 1U);
  bool saw_degraded_commit = false;
  for (std::size_t i = 0; i < rig.box.size(); ++i) {
    const CycleRecord& rec = rig.box.at(i);
    if (rec.cycle == 11) {
      EXPECT_NE(rec.flags & kRecordDegraded, 0U);
      saw_degraded_commit = (rec.state_word & shm::state_bits::kDegraded) != 0;
    }
  }
  EXPECT_TRUE(saw_degraded_commit) << "the degraded SERVO published cycle 11";
  shm::VpPayload vp;
  ASSERT_TRUE(rig.vp->read(vp).ok());
  EXPECT_EQ(vp.cycle, rig.executive.cycles()) << "VP always carries the newest cycle";
}

TEST(Executive, FaultInjectionOfFiveCyclesTripsAndOfFourDoesNot) {
  for (const std::uint32_t k : {4U, 5U}) {
    Rig rig(slow_for(0, 0, 0ns));
    rig.ctrl_writer().send(shm::CtrlCode::kInjectOverrun, k, 0);
    const ExecutiveResult r = rig.executive.run();
    EXPECT_EQ(r.fail_safe, k == 5) << "K=" << k;
    EXPECT_EQ(rig.executive.monitor().total_misses(), k) << "K=" << k;
  }
}

TEST(Executive, TheBlackBoxOfAStallThatFailedSafeEndsWithTheStall) {
  // H5: the cause of a fail-safe is in its black box. A clock that wakes 12 periods late skips
  // 12 slots; the fail-safe follows, and the last record is that late wake-up, after the
  // ordinary cycle before it.
  Rig rig(slow_for(0, 0, 0ns));
  rig.clock.oversleep_at(Rig::slot(40), kPeriod * 12);
  EXPECT_TRUE(rig.executive.run().fail_safe);
  ASSERT_GE(rig.box.size(), 2U);
  const CycleRecord& stall = rig.box.at(rig.box.size() - 1);
  EXPECT_EQ(stall.flags, kRecordMiss | kRecordStall);
  EXPECT_EQ(stall.skipped, 12U);
  EXPECT_EQ(stall.wake_latency, to_ns(kPeriod * 12));
  EXPECT_EQ(stall.scheduled, to_ns(Rig::slot(40)));
  EXPECT_EQ(stall.servo_start_delay, -1);
  EXPECT_EQ(stall.cycle, 40U) << "the last cycle that ran";
  const CycleRecord& before = rig.box.at(rig.box.size() - 2);
  EXPECT_EQ(before.flags, 0U);
  EXPECT_EQ(before.cycle, 40U);
}

TEST(Executive, BlackBoxHoldsTheLastCycles) {
  Rig rig(slow_for(0, 0, 0ns));
  rig.executive.run();
  ASSERT_EQ(rig.box.size(), 200U);
  EXPECT_EQ(rig.box.at(0).cycle, 1U);
  EXPECT_EQ(rig.box.at(199).cycle, 200U);
}

}  // namespace
}  // namespace hapticctrl::rt_core
