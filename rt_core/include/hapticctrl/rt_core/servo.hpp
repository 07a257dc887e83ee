#pragma once
/// @file servo.hpp
/// The SERVO task's steps (DESIGN.md §4): read measures, build the logical state from ctrl,
/// exchange with the protocol regions, run the law, send commands, publish VP and position.
///
/// A cycle runs in two gate sections around the computation:
///   begin():  [gate] measures, ctrl -> logical state, supply, VPr           [/gate]
///             law.compute()                                   (no gate held)
///   finish(): [gate] send commands (inhibited unless powered), publish VP/position [/gate]
/// The main SERVO and the degraded SERVO are two ServoTask objects sharing one ServoShared; the
/// CycleGate serialises everything shared, so they can never write the arm or a region at once,
/// and a late main SERVO is refused at finish() once CLOCK granted a newer cycle.

#include <atomic>
#include <cstdint>

#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/cycle_gate.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"
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

/// State shared by the main and the degraded SERVO. Fields other than the atomics are only
/// touched inside the gate.
struct ServoShared {
  ServoShared(ArmIo& arm_io, shm::CtrlReader ctrl_reader, const ServoRegions& servo_regions,
              bool allow_fault_injection) noexcept
      : arm(&arm_io),
        ctrl(ctrl_reader),
        regions(servo_regions),
        interpreter(allow_fault_injection) {}

  CycleGate gate;
  ArmIo* arm;
  shm::CtrlReader ctrl;
  ServoRegions regions;
  CommandInterpreter interpreter;
  LogicalState logical;
  bool supply_on = false;

  // Client (VPr) tracking.
  shm::VprPayload last_client{};
  bool client_valid = false;
  std::uint64_t last_client_sequence = 0;
  TimeNs last_client_arrival = 0;
  TimeNs last_client_time = 0;  ///< when the client computed it, our clock (see VprPayload)

  /// The committed cycle's render memory; each task's law continues from it.
  RenderMemory rendered;

  ServoCounters counters;
  /// Set by the CLOCK at the start of the stop sequence: motor commands stay disabled.
  std::atomic<bool> inhibit{false};
  /// Extra state bits the CLOCK sets (kFailSafe/kStopping) for the next publishes.
  std::atomic<std::uint32_t> clock_state_bits{0};
  std::atomic<std::uint32_t> core_state{static_cast<std::uint32_t>(shm::CoreState::kRunning)};
  std::atomic<std::uint32_t> stop_reason{0};
  /// What the last commit published (VP state word, client session): the CLOCK turns changes
  /// into events.
  std::atomic<std::uint32_t> committed_state_word{0};
  std::atomic<std::uint64_t> committed_session{0};
  /// Mirror of logical.stop_requested for the CLOCK.
  std::atomic<bool> stop_requested{false};
  /// The handle stayed over the speed limit despite the brake (LawConfig::overspeed_fault_after).
  std::atomic<bool> velocity_fault{false};
  /// Command-line fault injection: at this cycle, request an overrun of inject_cycles.
  std::uint64_t inject_at_cycle = 0;
  std::uint32_t inject_cycles = 0;
  /// Fault injection taken by the main SERVO: stall for this many cycles' worth.
  std::atomic<std::uint32_t> overrun_request{0};
  /// Last cycle committed by anyone.
  std::atomic<std::uint64_t> commit_cycle{0};
};

/// Which SERVO a task is.
enum class ServoRole : std::uint8_t { kMain, kDegraded };

/// Outcome of one task step.
enum class StepResult : std::uint8_t {
  kDone,        ///< committed
  kNotGranted,  ///< the cycle was no longer (or never) this task's: nothing done
  kDiscarded,   ///< computed, but a newer cycle was granted before commit: outputs dropped
};

/// One SERVO (main or degraded), with its own law state.
class ServoTask {
 public:
  ServoTask(ServoShared& shared, ServoRole role, const ServoLaw& law) noexcept
      : shared_(&shared), role_(role), law_(law) {}

  /// Gate section 1 and the computation. Real-time contract: safe in the cycle.
  StepResult begin(std::uint64_t cycle, TimeNs now, TimeNs dt) noexcept;
  /// Gate section 2: commit. Real-time contract: safe in the cycle.
  StepResult finish(std::uint64_t cycle, TimeNs now) noexcept;
  /// begin() then finish() with no stall in between.
  StepResult run(std::uint64_t cycle, TimeNs now, TimeNs dt) noexcept;

  [[nodiscard]] ServoRole role() const noexcept { return role_; }

 private:
  void gather(std::uint64_t cycle, TimeNs now, TimeNs dt) noexcept;
  void exchange_client(TimeNs now) noexcept;
  void commit(std::uint64_t cycle, TimeNs now) noexcept;

  ServoShared* shared_;
  ServoRole role_;
  ServoLaw law_;
  ServoInputs inputs_;
  ServoOutputs outputs_;
};

}  // namespace hapticctrl::rt_core
