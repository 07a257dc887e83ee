// Implements executive.hpp: the CLOCK task (slots, late wake-ups, the periodic tasks released and
// judged, statistics, black box, events, telemetry) and the stop sequence.
#include "hapticctrl/rt_core/executive.hpp"

#include <algorithm>
#include <array>

namespace hapticctrl::rt_core {
namespace {

/// Bound on waiting for a task to leave the gate during the stop sequence.
constexpr int kGateCloseAttempts = 2000;
/// How long client data must stay stale (or fresh) before the change is an event.
constexpr Duration kStaleEventHold = std::chrono::milliseconds(20);

}  // namespace

Executive::Executive(const ExecutiveConfig& config, Clock& clock, TaskRunners& servo,
                     ServoShared& shared, ArmIo& arm, const ExecutiveOutputs& outputs,
                     BlackBox& black_box)
    : config_(config),
      clock_(&clock),
      tasks_(config.period),
      servo_(tasks_.add({.runners = &servo,
                         .has_degraded = true,
                         .period_multiple = 1,
                         .gate = &shared.gate,
                         .deadline = config.period * 3 / 4,
                         .chronic = config.chronic})),
      gate_(&shared.gate),
      gate_owned_(&shared.state),
      to_servo_(&shared.from_clock),
      from_servo_(&shared.to_clock),
      arm_(&arm),
      outputs_(outputs),
      black_box_(&black_box),
      stale_(static_cast<std::uint64_t>(kStaleEventHold / std::max(Duration{1}, config.period))) {
  tasks_.activate(servo_);
}

bool Executive::is_fault(shm::StopReason reason) noexcept {
  return reason != shm::StopReason::kStopRequested && reason != shm::StopReason::kSignal &&
         reason != shm::StopReason::kDurationElapsed;
}

ExecutiveResult Executive::run(const std::atomic<bool>* external_stop) noexcept {
  const Duration period = config_.period;
  const TimePoint start = clock_->now();
  // Aligned on the period, at least a period ahead.
  const TimePoint first_slot{(start.time_since_epoch() / period + 2) * period};
  if (outputs_.header != nullptr) {
    outputs_.header->core_state.store(static_cast<std::uint32_t>(shm::CoreState::kRunning),
                                      std::memory_order_release);
  }
  emit(shm::EventKind::kCoreState, static_cast<std::uint32_t>(shm::CoreState::kRunning), 0, start);
  std::uint64_t slot = 0;
  for (;;) {
    const TimePoint scheduled = first_slot + static_cast<std::int64_t>(slot) * period;
    clock_->sleep_until(scheduled);
    const TimePoint woke = clock_->now();
    const Duration late = woke - scheduled;
    wake_latency_.add(late);
    if (late > period / 2) {
      // Too late for this slot: skip it and every slot passed meanwhile, resume at the next
      // future slot. Never run back to back to catch up.
      const auto passed = static_cast<std::uint64_t>(late / period);
      const std::uint64_t skip = passed + 1 - ((late % period <= period / 2) ? 1U : 0U);
      skipped_slots_ += skip;
      const MonitorVerdict verdict = tasks_.skip(static_cast<std::uint32_t>(skip));
      // The stall itself goes into the black box (before a fail-safe writes it out).
      CycleTimes stall;
      stall.scheduled = scheduled;
      stall.woke = woke;
      record(stall, kRecordMiss | kRecordStall, static_cast<std::uint32_t>(skip));
      if (trips(verdict)) {
        return stop_sequence(verdict == MonitorVerdict::kFailSafe
                                 ? shm::StopReason::kConsecutiveMisses
                                 : shm::StopReason::kChronicMisses,
                             true);
      }
      slot += skip;
      if (skip == passed) {
        // The latest passed slot is recent enough (<= P/2 late): run it now.
        const TimePoint run_scheduled = first_slot + static_cast<std::int64_t>(slot) * period;
        const shm::StopReason reason = run_slot(run_scheduled, woke);
        if (reason != shm::StopReason::kNone) {
          return stop_sequence(reason, is_fault(reason));
        }
        ++slot;
      }
      continue;
    }
    shm::StopReason reason = run_slot(scheduled, woke);
    if (reason == shm::StopReason::kNone && external_stop != nullptr &&
        external_stop->load(std::memory_order_acquire)) {
      reason = shm::StopReason::kSignal;
    }
    if (reason == shm::StopReason::kNone && config_.duration > Duration{0} &&
        woke - start >= config_.duration) {
      reason = shm::StopReason::kDurationElapsed;
    }
    if (reason != shm::StopReason::kNone) {
      return stop_sequence(reason, is_fault(reason));
    }
    ++slot;
  }
}

shm::StopReason Executive::run_slot(TimePoint scheduled, TimePoint woke) noexcept {
  const Duration period = config_.period;
  ++cycle_;
  if (last_woke_ != kNotYet) {
    measured_period_.add(woke - last_woke_);
  }
  last_woke_ = woke;
  if (outputs_.header != nullptr) {
    outputs_.header->heartbeat_cycle.store(cycle_, std::memory_order_relaxed);
    outputs_.header->heartbeat_ns.store(to_ns(woke), std::memory_order_release);
  }

  CycleTimes times;
  times.scheduled = scheduled;
  times.woke = woke;
  times.released = clock_->now();  // before the wake syscall, so the start delay includes it
  tasks_.release_due(cycle_, scheduled, times.released);

  clock_->sleep_until(scheduled + period * 3 / 4);
  times.checked = clock_->now();
  const MonitorVerdict verdict = tasks_.check_deadlines(times.checked);
  const TaskRelease& servo = tasks_.last_release(servo_);
  times.degraded = servo.role == TaskRole::kDegraded;
  times.started = servo.started;
  times.finished = servo.finished;
  const bool miss = verdict != MonitorVerdict::kGood;
  if (times.started != kNotYet) {
    servo_start_delay_.add(times.started - times.released);
    if (times.finished != kNotYet) {
      servo_execution_.add(times.finished - times.started);
    }
  }
  record(times, (miss ? kRecordMiss : 0U) | (times.degraded ? kRecordDegraded : 0U), 0);
  report_state_changes(times.checked);
  if (cycle_ % config_.telemetry_every == 0) {
    publish_telemetry(times.checked);
  }

  switch (trips(verdict) ? verdict : MonitorVerdict::kMiss) {
    case MonitorVerdict::kFailSafe:
      return shm::StopReason::kConsecutiveMisses;
    case MonitorVerdict::kChronicMisses:
      return shm::StopReason::kChronicMisses;
    case MonitorVerdict::kGood:
    case MonitorVerdict::kMiss:
      break;
  }
  if (from_servo_->counters.arm_faults.load(std::memory_order_relaxed) > 0) {
    return shm::StopReason::kArmFault;
  }
  if (from_servo_->velocity_fault.load(std::memory_order_acquire)) {
    return shm::StopReason::kVelocityLimit;
  }
  if (from_servo_->stop_requested.load(std::memory_order_acquire)) {
    return shm::StopReason::kStopRequested;
  }
  return shm::StopReason::kNone;
}

void Executive::record(const CycleTimes& times, std::uint32_t flags,
                       std::uint32_t skipped) noexcept {
  CycleRecord r;
  r.cycle = cycle_;
  r.scheduled = to_ns(times.scheduled);
  r.wake_latency = to_ns(times.woke - times.scheduled);
  r.servo_start_delay = times.started != kNotYet ? to_ns(times.started - times.released) : -1;
  r.servo_execution = (times.finished != kNotYet && times.started != kNotYet)
                          ? to_ns(times.finished - times.started)
                          : -1;
  r.flags = flags;
  r.consecutive_misses = monitor().consecutive_misses();
  r.skipped = skipped;
  if (outputs_.position != nullptr) {
    shm::PositionPayload pos;
    if (outputs_.position->read(pos).ok()) {
      r.state_word = pos.state_word;
      r.joint_position = pos.joint_position;
      r.joint_torque = pos.joint_torque;
    }
  }
  black_box_->record(r);
  // The misses that trip a fail-safe are the machine's when a stall began their run: after a
  // stall the SERVO often misses a cycle or two more before it gets its CPU back (run.sh saw
  // a 3.3 ms stall, then two missed cycles, trip; 2026-12-03).
  if ((flags & kRecordStall) != 0) {
    stall_in_misses_ = std::max(stall_in_misses_, times.woke - times.scheduled);
  } else if (r.consecutive_misses == 0) {
    stall_in_misses_ = Duration{0};
  }
}

bool Executive::trips(MonitorVerdict verdict) noexcept {
  if (verdict != MonitorVerdict::kFailSafe && verdict != MonitorVerdict::kChronicMisses) {
    return false;
  }
  if (!config_.ride_through_misses) {
    return true;
  }
  if (would_fail_safe_++ == 0) {
    first_would_fail_safe_cycle_ = cycle_;
  }
  return false;
}

shm::TelemetryPayload Executive::telemetry() const noexcept {
  shm::TelemetryPayload t;
  t.cycle = cycle_;
  t.period_ns = to_ns(config_.period);
  t.rt_mode = static_cast<std::uint32_t>(config_.rt_mode);
  t.core_state = static_cast<std::uint32_t>(core_state_);
  t.stop_reason = static_cast<std::uint32_t>(stop_reason_);
  const DeadlineMonitor& servo = monitor();
  t.consecutive_misses = servo.consecutive_misses();
  t.misses_total = servo.total_misses();
  t.degraded_cycles = tasks_.degraded_releases(servo_);
  t.skipped_slots = skipped_slots_;
  t.would_fail_safe = would_fail_safe_;
  t.first_would_fail_safe_cycle = first_would_fail_safe_cycle_;
  t.late_servo_discarded = from_servo_->counters.late_discarded.load(std::memory_order_relaxed);
  t.window_miss_ppm = servo.window_miss_ppm();
  t.leaky_bucket_score = servo.leaky_bucket_score();
  t.wake_latency = wake_latency_.summary();
  t.servo_start_delay = servo_start_delay_.summary();
  t.servo_execution = servo_execution_.summary();
  t.measured_period = measured_period_.summary();
  t.vpr_torn = from_servo_->counters.vpr_torn.load(std::memory_order_relaxed);
  t.vpr_stale = from_servo_->counters.vpr_stale.load(std::memory_order_relaxed);
  t.vpr_rejected = from_servo_->counters.vpr_rejected.load(std::memory_order_relaxed);
  t.force_rejected = from_servo_->counters.force_rejected.load(std::memory_order_relaxed);
  t.ctrl_accepted = from_servo_->counters.ctrl_accepted.load(std::memory_order_relaxed);
  t.ctrl_rejected = from_servo_->counters.ctrl_rejected.load(std::memory_order_relaxed);
  wake_latency_.coarse(t.wake_histogram);
  return t;
}

void Executive::emit(shm::EventKind kind, std::uint32_t code, std::uint64_t value,
                     TimePoint now) noexcept {
  if (outputs_.events != nullptr) {
    shm::push_event(*outputs_.events, cycle_, to_ns(now), kind, code, value);
  }
}

void Executive::report_state_changes(TimePoint now) noexcept {
  struct BitEvent {
    std::uint32_t bit;
    shm::EventKind kind;
  };
  static constexpr std::array<BitEvent, 4> kBitEvents{{
      {shm::state_bits::kPowered, shm::EventKind::kPower},
      {shm::state_bits::kEmergencyStop, shm::EventKind::kEmergencyStop},
      {shm::state_bits::kDegraded, shm::EventKind::kDegraded},
      {shm::state_bits::kCoupled, shm::EventKind::kCoupling},
  }};
  const std::uint32_t word = from_servo_->committed_state_word.load(std::memory_order_relaxed);
  const std::uint32_t changed = word ^ reported_state_word_;
  for (const BitEvent& b : kBitEvents) {
    if ((changed & b.bit) != 0) {
      emit(b.kind, (word & b.bit) != 0 ? 1U : 0U, 0, now);
      reported_state_word_ ^= b.bit;
    }
  }
  if (stale_.update((word & shm::state_bits::kClientStale) != 0, cycle_)) {
    emit(shm::EventKind::kClientStale, stale_.reported() ? 1U : 0U, stale_.lapses(), now);
  }
  const std::uint64_t session = from_servo_->committed_session.load(std::memory_order_relaxed);
  if (session != reported_session_) {
    emit(shm::EventKind::kClientSession, 0, session, now);
    reported_session_ = session;
  }
}

void Executive::publish_telemetry(TimePoint now) noexcept {
  if (outputs_.telemetry != nullptr) {
    outputs_.telemetry->publish_quietly(telemetry(), to_ns(now));
  }
}

ExecutiveResult Executive::stop_sequence(shm::StopReason reason, bool fail_safe) noexcept {
  ExecutiveResult result;
  result.reason = reason;
  result.fail_safe = fail_safe;
  if (reason == shm::StopReason::kConsecutiveMisses || reason == shm::StopReason::kChronicMisses) {
    result.tripped_by_stall = stall_in_misses_;
  }
  stop_reason_ = reason;
  core_state_ = fail_safe ? shm::CoreState::kFailSafe : shm::CoreState::kStopping;
  auto step = [&](StopStep s) {
    result.steps[result.step_count] = s;
    result.step_times[result.step_count] = clock_->now();
    ++result.step_count;
  };
  if (outputs_.header != nullptr) {
    outputs_.header->stop_reason.store(static_cast<std::uint32_t>(reason),
                                       std::memory_order_relaxed);
    outputs_.header->core_state.store(static_cast<std::uint32_t>(core_state_),
                                      std::memory_order_release);
  }

  // 1. Inhibit motor commands: no commit may enable them from now on, and no task may enter.
  to_servo_->inhibit_commands();
  to_servo_->add_state_bits(fail_safe ? shm::state_bits::kFailSafe : shm::state_bits::kStopping);
  bool exclusive = false;
  for (int attempt = 0; attempt < kGateCloseAttempts && !exclusive; ++attempt) {
    exclusive = gate_->close() || gate_->closed();
    if (!exclusive) {
      clock_->sleep_until(clock_->now() + std::chrono::microseconds(10));
    }
  }
  if (exclusive) {
    ArmCommands inhibit;  // zero torque, motors disabled, brakes on
    arm_->send_commands(inhibit, clock_->now(), config_.period);
  }
  step(StopStep::kInhibitCommands);

  // 2. Power off the (simulated) supply, even when the gate stayed open: a SERVO hung in the
  // cycle must not keep the motors powered, and set_supply is the ArmIo call made safe beside a
  // running cycle (arm_io.hpp).
  arm_->set_supply(false);
  step(StopStep::kPowerOffSupply);

  // 3. Close the protocol: VP says FAILSAFE/STOPPING and why, so the bridge tells the client.
  // Only now (no task can commit any more) does the servo's view of the state change, so the
  // first VP that says FAILSAFE is this one, already unpowered.
  to_servo_->announce(core_state_, reason);
  publish_telemetry(clock_->now());  // before VP: whoever sees VP close finds telemetry agreeing
  // The gate closed, the CLOCK holds the gate-owned state: the last VP is published from here.
  if (exclusive && gate_owned_->regions.vp != nullptr) {
    shm::VpPayload vp;
    (void)gate_owned_->regions.vp->read(vp);
    vp.cycle = cycle_;
    vp.state_word =
        (gate_owned_->logical.state_word() & ~shm::state_bits::kPowered) | to_servo_->state_bits();
    vp.core_state = static_cast<std::uint32_t>(core_state_);
    vp.stop_reason = static_cast<std::uint32_t>(reason);
    vp.object_wrench = {};
    gate_owned_->regions.vp->publish(vp, to_ns(clock_->now()));
    result.protocol_closed_in_vp = true;
  }
  emit(shm::EventKind::kCoreState, static_cast<std::uint32_t>(core_state_),
       static_cast<std::uint64_t>(reason), clock_->now());
  step(StopStep::kCloseProtocol);

  // 4. Stop the tasks.
  tasks_.stop_runners();
  step(StopStep::kStopTasks);
  return result;
}

}  // namespace hapticctrl::rt_core
