#pragma once
/// @file executive.hpp
/// The CLOCK task. Per slot it wakes at the absolute deadline, releases the tasks due through the
/// periodic-task manager (periodic_tasks.hpp: the SERVO is its task, released every tick, its
/// degraded function taking a tick the main SERVO is still busy with), sleeps to 3/4 of the
/// period, has the manager judge the deadlines, updates statistics, the heartbeat and the black
/// box, and sleeps to the next slot.
///
/// A wake-up more than half a period late for its slot skips that slot (and any slot passed
/// meanwhile) and resumes at the next future slot: cycles never run back to back to catch up.
/// Skipped slots count as misses.
///
/// The fail-safe (exactly 5 consecutive misses) and the orderly stop (ctrl stop, signal,
/// duration) run the same sequence, in this order: inhibit motor commands, power off the supply,
/// close the protocol (VP says FAILSAFE/STOPPING with the reason), stop the tasks. The caller then
/// writes the black box (fail-safe), releases the regions and exits with the reason.

#include <array>
#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/black_box.hpp"
#include "hapticctrl/rt_core/clock.hpp"
#include "hapticctrl/rt_core/deadline_monitor.hpp"
#include "hapticctrl/rt_core/debounced_flag.hpp"
#include "hapticctrl/rt_core/latency_histogram.hpp"
#include "hapticctrl/rt_core/periodic_tasks.hpp"
#include "hapticctrl/rt_core/servo.hpp"
#include "hapticctrl/shm/events.hpp"
#include "hapticctrl/shm/layout.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

/// The steps of the stop sequence, recorded in order with their times.
enum class StopStep : std::uint8_t {
  kInhibitCommands = 1,
  kPowerOffSupply = 2,
  kCloseProtocol = 3,
  kStopTasks = 4,
};

struct ExecutiveConfig {
  Duration period = std::chrono::milliseconds(1);
  Duration duration{0};                ///< stop after this long (0: run until stopped)
  std::uint32_t telemetry_every = 20;  ///< publish telemetry every N cycles
  ChronicMissConfig chronic;
  shm::RtMode rt_mode = shm::RtMode::kNone;
  /// Benchmark mode (simulated arm only): the miss rules (5 consecutive, chronic) are evaluated
  /// and each trip is counted as a would-be fail-safe, but the core runs on. The simulated arm
  /// does not move while the core is stalled (its time is the cycles it runs), so a stall only
  /// pauses it; hardware would be uncontrolled. Lets a run on a VM that stalls every few seconds
  /// last as long as a measurement needs, and say how often it would have failed safe.
  bool ride_through_misses = false;
};

/// Where the CLOCK publishes (any may be null in tests).
struct ExecutiveOutputs {
  shm::SegmentHeader* header = nullptr;
  shm::SeqlockCell<shm::TelemetryPayload>* telemetry = nullptr;
  const shm::SeqlockCell<shm::PositionPayload>* position = nullptr;  ///< for the black box
  shm::EventRing* events = nullptr;  ///< state transitions and faults, for monitors
};

struct ExecutiveResult {
  shm::StopReason reason = shm::StopReason::kNone;
  bool fail_safe = false;  ///< a fault (exit non-zero), not an orderly stop
  std::array<StopStep, 4> steps{};
  std::array<TimePoint, 4> step_times{};
  std::size_t step_count = 0;
  bool protocol_closed_in_vp = false;  ///< VP carried the final state (gate could be closed)
  /// A miss rule tripped in a run of misses that a stall began: the clock task, the core's
  /// highest-priority thread, woke this late after a slot. 0: no stall in that run, or no
  /// fail-safe on misses.
  Duration tripped_by_stall{0};
};

class Executive {
 public:
  /// `servo`: the runners of the main and the degraded SERVO (the law, arm commands and
  /// publishing of a cycle: ServoTask), added as the manager's task released every tick.
  /// Setup.
  Executive(const ExecutiveConfig& config, Clock& clock, TaskRunners& servo, ServoShared& shared,
            ArmIo& arm, const ExecutiveOutputs& outputs, BlackBox& black_box);

  /// Runs until fail-safe or stop. `external_stop` (signals) is polled once per cycle.
  /// Real-time contract: this *is* the cycle; noexcept, no allocation.
  ExecutiveResult run(const std::atomic<bool>* external_stop = nullptr) noexcept;

  /// Current figures (also what telemetry carries).
  [[nodiscard]] HAPTICCTRL_RT shm::TelemetryPayload telemetry() const noexcept;
  [[nodiscard]] const LatencyHistogram& wake_latency() const noexcept { return wake_latency_; }
  /// The SERVO's deadline record.
  [[nodiscard]] HAPTICCTRL_RT const DeadlineMonitor& monitor() const noexcept {
    return tasks_.monitor(servo_);
  }
  [[nodiscard]] std::uint64_t cycles() const noexcept { return cycle_; }

 private:
  /// Runs one slot; returns a stop reason when the cycle must end.
  HAPTICCTRL_RT shm::StopReason run_slot(TimePoint scheduled, TimePoint woke) noexcept;
  /// One black-box record: a cycle, or a stall (kRecordStall) that skipped `skipped` slots.
  HAPTICCTRL_RT void record(const CycleTimes& times, std::uint32_t flags,
                            std::uint32_t skipped) noexcept;
  HAPTICCTRL_RT void publish_telemetry(TimePoint now) noexcept;
  HAPTICCTRL_RT void emit(shm::EventKind kind, std::uint32_t code, std::uint64_t value,
                          TimePoint now) noexcept;
  /// Turns changes of the committed state word and client session into events.
  HAPTICCTRL_RT void report_state_changes(TimePoint now) noexcept;
  ExecutiveResult stop_sequence(shm::StopReason reason, bool fail_safe) noexcept;
  /// Whether a monitor verdict stops the core; in benchmark mode a trip is only counted.
  HAPTICCTRL_RT bool trips(MonitorVerdict verdict) noexcept;
  static bool is_fault(shm::StopReason reason) noexcept;

  ExecutiveConfig config_;
  Clock* clock_;
  PeriodicTasks tasks_;
  TaskId servo_;
  CycleGate* gate_;
  GateOwnedState* gate_owned_;  ///< only once the gate is closed (the stop sequence)
  ClockToServo* to_servo_;
  const ServoToClock* from_servo_;
  ArmIo* arm_;
  ExecutiveOutputs outputs_;
  BlackBox* black_box_;

  LatencyHistogram wake_latency_;
  LatencyHistogram servo_start_delay_;
  LatencyHistogram servo_execution_;
  LatencyHistogram measured_period_;
  std::uint64_t cycle_ = 0;
  std::uint64_t skipped_slots_ = 0;
  Duration stall_in_misses_{0};  ///< the latest stall in the current run of misses (its lateness)
  std::uint64_t would_fail_safe_ = 0;  ///< benchmark mode: miss-rule trips ridden through
  std::uint64_t first_would_fail_safe_cycle_ = 0;
  TimePoint last_woke_ = kNotYet;
  shm::StopReason stop_reason_ = shm::StopReason::kNone;
  shm::CoreState core_state_ = shm::CoreState::kRunning;
  std::uint32_t reported_state_word_ = 0;
  /// Client stale/fresh is an event once it has held 20 ms (DebouncedFlag).
  DebouncedFlag stale_;
  std::uint64_t reported_session_ = 0;
};

}  // namespace hapticctrl::rt_core
