#pragma once
/// @file servo.hpp
/// The SERVO task's steps (docs/rt_core.md, *The cycle*): read measures, build the logical state
/// from ctrl, exchange with the protocol regions, run the law, send commands, publish VP and
/// position.
///
/// A cycle runs in two gate sections around the computation:
///   begin():  [gate] measures, ctrl -> logical state, supply, VPr           [/gate]
///             law.compute()                                   (no gate held)
///   finish(): [gate] send commands (inhibited unless powered), publish VP/position [/gate]
/// The main SERVO and the degraded SERVO are two ServoTask objects sharing one ServoShared; the
/// CycleGate serialises the state it owns, so they can never write the arm or a region at once,
/// and a late main SERVO is refused at finish() once CLOCK granted a newer cycle. What crosses
/// between the CLOCK and the SERVOs goes through two one-writer mailboxes (ClockToServo,
/// ServoToClock).

#include <atomic>
#include <cstdint>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/cycle_gate.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"
#include "hapticctrl/rt_core/periodic_tasks.hpp"  // TaskRole
#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"
#include "hapticctrl/shm/seqlock.hpp"

namespace hapticctrl::rt_core {

/// Region endpoints of the servo (all in the instance segment).
struct ServoRegions {
  const shm::SeqlockCell<shm::VprPayload>* vpr = nullptr;
  shm::SeqlockCell<shm::VpPayload>* vp = nullptr;
  shm::SeqlockCell<shm::PositionPayload>* position = nullptr;
};

/// Counters the CLOCK reads for telemetry (written inside the gate, read relaxed elsewhere).
struct ServoCounters {
  std::atomic<std::uint64_t> vpr_torn{0};
  std::atomic<std::uint64_t> vpr_rejected{0};
  std::atomic<std::uint64_t> force_rejected{
      0};  ///< the arm's ArmMeasures::operator_wrench_rejected
  std::atomic<std::uint64_t> vpr_stale{0};
  std::atomic<std::uint64_t> ctrl_accepted{0};
  std::atomic<std::uint64_t> ctrl_rejected{0};
  std::atomic<std::uint64_t> late_discarded{0};
  std::atomic<std::uint64_t> arm_faults{0};
};

/// CLOCK -> SERVO: what the CLOCK tells the task that commits. The Executive holds it mutable and
/// the SERVOs const, so the CLOCK is its one writer by construction. Every method is wait-free
/// (one atomic operation) and safe in the cycle.
class ClockToServo {
 public:
  /// CLOCK: no commit may enable the motors from now on (stop sequence, step 1).
  void inhibit_commands() noexcept { inhibit_.store(true, std::memory_order_release); }
  /// CLOCK: state bits (kFailSafe/kStopping) every later publish carries.
  void add_state_bits(std::uint32_t bits) noexcept {
    state_bits_.fetch_or(bits, std::memory_order_acq_rel);
  }
  /// CLOCK: the core state and stop reason VP carries from now on.
  void announce(shm::CoreState state, shm::StopReason reason) noexcept {
    stop_reason_.store(static_cast<std::uint32_t>(reason), std::memory_order_relaxed);
    core_state_.store(static_cast<std::uint32_t>(state), std::memory_order_relaxed);
  }

  [[nodiscard]] HAPTICCTRL_RT bool commands_inhibited() const noexcept {
    return inhibit_.load(std::memory_order_acquire);
  }
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t state_bits() const noexcept {
    return state_bits_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t core_state() const noexcept {
    return core_state_.load(std::memory_order_relaxed);
  }
  [[nodiscard]] HAPTICCTRL_RT std::uint32_t stop_reason() const noexcept {
    return stop_reason_.load(std::memory_order_relaxed);
  }

 private:
  std::atomic<bool> inhibit_{false};
  std::atomic<std::uint32_t> state_bits_{0};
  std::atomic<std::uint32_t> core_state_{static_cast<std::uint32_t>(shm::CoreState::kRunning)};
  std::atomic<std::uint32_t> stop_reason_{0};
};

/// SERVO -> CLOCK: what the committing SERVO reports. Written only by a task inside the gate
/// (the gate makes the two SERVOs one writer at a time); the Executive holds it const.
struct ServoToClock {
  ServoCounters counters;
  /// What the last commit published (VP state word, client session): the CLOCK turns changes
  /// into events.
  std::atomic<std::uint32_t> committed_state_word{0};
  std::atomic<std::uint64_t> committed_session{0};
  /// A ctrl stop command was applied.
  std::atomic<bool> stop_requested{false};
  /// The handle stayed over the speed limit despite the brake (LawConfig::overspeed_fault_after).
  std::atomic<bool> velocity_fault{false};
  /// Last cycle committed by either SERVO.
  std::atomic<std::uint64_t> commit_cycle{0};
};

/// Fault injection of an overrun (--inject-overrun CYCLE:K, or the ctrl command): the SERVO inside
/// the gate asks for a stall of K cycles, the main SERVO's runner takes the request and stalls.
/// One producer, one consumer; wait-free, safe in the cycle.
class OverrunInjection {
 public:
  /// SERVO (inside the gate): stall the main SERVO for `cycles` cycles.
  HAPTICCTRL_RT void request(std::uint32_t cycles) noexcept {
    cycles_.store(cycles, std::memory_order_release);
  }
  /// The main SERVO's runner: the pending request (0: none), cleared.
  std::uint32_t take() noexcept { return cycles_.exchange(0, std::memory_order_acq_rel); }

 private:
  std::atomic<std::uint32_t> cycles_{0};
};

/// The command-line overrun: at cycle `at_cycle` (0: never), an overrun of `cycles`.
struct ScheduledOverrun {
  std::uint64_t at_cycle = 0;
  std::uint32_t cycles = 0;
};

/// Gate-owned state: touched only by whoever holds the CycleGate (a SERVO between enter() and
/// leave(), the CLOCK once it has closed the gate), so it needs no atomics.
struct GateOwnedState {
  ArmIo* arm;
  shm::CtrlReader ctrl;
  ServoRegions regions;
  CommandInterpreter interpreter;
  LogicalState logical;
  bool supply_on = false;
  ScheduledOverrun scheduled_overrun;

  // Client (VPr) tracking.
  shm::VprPayload last_client{};  ///< as received: its echo and link fields go back in VP
  ClientSample client;            ///< the same, converted for the law
  bool client_valid = false;
  std::uint64_t last_client_sequence = 0;
  TimePoint last_client_arrival;
  TimePoint last_client_time;           ///< when the client computed it, our clock (see VprPayload)
  std::uint32_t contacts_rejected = 0;  ///< contact frames with a contact refused, this session

  /// The committed cycle's render memory; each task's law continues from it.
  RenderMemory rendered;
};

/// Everything the CLOCK and the two SERVOs share, as one-writer parts: the gate, the state it
/// guards, and a mailbox each way. Each party keeps pointers to the parts it may use, typed
/// const where it only reads (Executive, ServoTask).
struct ServoShared {
  ServoShared(ArmIo& arm_io, shm::CtrlReader ctrl_reader, const ServoRegions& servo_regions,
              bool allow_fault_injection, ScheduledOverrun scheduled = {}) noexcept
      : state{.arm = &arm_io,
              .ctrl = ctrl_reader,
              .regions = servo_regions,
              .interpreter = CommandInterpreter(allow_fault_injection),
              .scheduled_overrun = scheduled} {}

  CycleGate gate;
  GateOwnedState state;
  ClockToServo from_clock;
  ServoToClock to_clock;
  OverrunInjection overrun;
};

/// Outcome of one task step.
enum class StepResult : std::uint8_t {
  kDone,        ///< committed
  kNotGranted,  ///< the cycle was no longer (or never) this task's: nothing done
  kDiscarded,   ///< computed, but a newer cycle was granted before commit: outputs dropped
};

/// One SERVO (main or degraded), with its own law state.
class ServoTask {
 public:
  ServoTask(ServoShared& shared, TaskRole role, const ServoLaw& law) noexcept
      : gate_(&shared.gate),
        state_(&shared.state),
        from_clock_(&shared.from_clock),
        to_clock_(&shared.to_clock),
        overrun_(&shared.overrun),
        role_(role),
        law_(law) {}

  /// Gate section 1 and the computation. Real-time contract: safe in the cycle.
  HAPTICCTRL_RT StepResult begin(std::uint64_t cycle, TimePoint now, Duration dt) noexcept;
  /// Gate section 2: commit. Real-time contract: safe in the cycle.
  HAPTICCTRL_RT StepResult finish(std::uint64_t cycle, TimePoint now) noexcept;
  /// begin() then finish() with no stall in between.
  HAPTICCTRL_RT StepResult run(std::uint64_t cycle, TimePoint now, Duration dt) noexcept;

  [[nodiscard]] TaskRole role() const noexcept { return role_; }

 private:
  HAPTICCTRL_RT void gather(std::uint64_t cycle, TimePoint now, Duration dt) noexcept;
  HAPTICCTRL_RT void exchange_client(TimePoint now) noexcept;
  /// The stiffest contact the device renders, in the client's units (N per client metre).
  [[nodiscard]] HAPTICCTRL_RT double max_contact_stiffness(double speed_factor) const noexcept;
  HAPTICCTRL_RT void commit(std::uint64_t cycle, TimePoint now) noexcept;
  /// The surface rendered on the handle, into VP in the client's frame and units.
  HAPTICCTRL_RT void publish_surface(const ClientFrame& frame, shm::VpPayload& vp) const noexcept;

  CycleGate* gate_;
  GateOwnedState* state_;
  const ClockToServo* from_clock_;
  ServoToClock* to_clock_;
  OverrunInjection* overrun_;
  TaskRole role_;
  ServoLaw law_;
  ServoInputs inputs_;
  ServoOutputs outputs_;
};

}  // namespace hapticctrl::rt_core
