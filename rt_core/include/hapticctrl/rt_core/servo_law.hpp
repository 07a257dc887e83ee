#pragma once
/// @file servo_law.hpp
/// The control law: inputs of one cycle in, motor torques and coupling wrench out. Pure
/// computation on fixed-size Eigen types: no clock (`now`/`dt` arrive in the inputs), no I/O,
/// no allocation. docs/control.md explains the law, the gains and the safety layers.
///
/// Per cycle: forward kinematics, Jacobian and handle twist; gravity compensation (always when
/// powered); the client's command (NONE, IMPEDANCE wrench, or VIRTMECH spring-damper coupling to
/// the virtual object, with stale-data extrapolation and fade); passivity guard on the coupling
/// port; saturation and rate limit of the handle wrench; speed safety; soft joint-limit walls;
/// joint torque saturation. The degraded SERVO runs the same code with `degraded = true`:
/// coupling off, gravity compensation and joint damping only.

#include <cstdint>

#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::rt_core {

/// Everything the law may use for one cycle.
struct ServoInputs {
  std::uint64_t cycle = 0;
  TimeNs now = 0;
  TimeNs dt = 0;
  ArmMeasures measures;
  LogicalState logical;
  shm::VprPayload client;     ///< last valid client sample
  bool client_valid = false;  ///< a valid client sample exists
  TimeNs client_age = 0;      ///< now - arrival of that sample
};

struct ServoOutputs {
  ArmCommands commands;
  /// Wrench the coupling applies to the client's object (what VP reports), base frame.
  Vector6d coupling_wrench = Vector6d::Zero();
  /// Wrench the controller renders on the handle (before the Jacobian transpose), base frame.
  Vector6d handle_wrench = Vector6d::Zero();
  std::array<double, 7> handle_pose{0, 0, 0, 0, 0, 0, 1};  ///< base frame
  Vector6d handle_twist = Vector6d::Zero();                ///< base frame
  /// The same, in the client's environment frame (through its base frame and speed factor).
  std::array<double, 7> client_handle_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6d client_handle_twist = Vector6d::Zero();
  double fade = 1.0;  ///< 1: fresh client data, 0: faded out
  bool coupled = false;
  bool client_stale = false;
};

/// Coupling gains (base frame): linear N/m, N·s/m; angular N·m/rad, N·m·s/rad.
struct CouplingGains {
  double k_linear = 0.0;
  double b_linear = 0.0;
  double k_angular = 0.0;
  double b_angular = 0.0;
};

/// How the client's environment frame relates to ours, derived once per cycle from its sample:
/// `base_frame` is our base in its environment (a degenerate quaternion counts as identity), and
/// the speed/force factors scale displacements and rendered forces (non-positive means 1).
struct ClientFrame {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Vector3d origin = Vector3d::Zero();
  double speed_factor = 1.0;
  double force_factor = 1.0;
};

/// Real-time contract: safe in the cycle.
ClientFrame client_frame_of(const shm::VprPayload& client) noexcept;

struct LawConfig {
  TimeNs stale_after = 5 * kNsPerMs;       ///< older client data is extrapolated, flagged stale
  TimeNs extrapolate_max = 50 * kNsPerMs;  ///< extrapolation horizon
  TimeNs fade_after = 50 * kNsPerMs;       ///< then the coupling fades ...
  TimeNs fade_duration = 100 * kNsPerMs;   ///< ... to zero over this ramp ("link lost")
  double joint_damping = 0.02;             ///< N·m·s/rad, always when powered (degraded too)
  double wall_margin = 0.05;               ///< rad before a joint limit where the soft wall starts
  double wall_stiffness = 20.0;            ///< N·m/rad
  bool passivity_guard = true;
  double default_object_mass = 0.5;  ///< kg, when the client declares none
  double default_time_step = 1e-3;   ///< s, when the client declares none
};

/// What the law carries from one cycle to the next about the wrench it rendered. The main and
/// the degraded SERVO each run a law of their own; the task that commits a cycle hands this on
/// to both (ServoShared), so that the rate limit and the passivity observer continue from what
/// the handle actually got, whichever SERVO rendered it. (Each law keeping its own let the
/// wrench jump between the two laws' last values when degraded cycles interleaved: 17.8 N in one
/// 4 ms cycle against an 8 N limit, found by the fault-injection test, 2026-12-01.)
struct RenderMemory {
  Vector6d wrench = Vector6d::Zero();       ///< handle wrench rendered last cycle
  Vector6d port_wrench = Vector6d::Zero();  ///< what the passivity observer saw at the port
  double observed_energy = 0.0;             ///< J, see observed_energy()
};

/// Counters of the law (cycle-safe reads).
struct LawCounters {
  std::uint64_t non_finite_outputs = 0;
  std::uint64_t speed_limited = 0;
  std::uint64_t passivity_active = 0;
  std::uint64_t rate_limited = 0;
  std::uint64_t workspace_walls = 0;  ///< cycles with the handle outside the workspace box
};

class ServoLaw {
 public:
  ServoLaw(const ArmDynamics& dynamics, const LawConfig& config = {}) noexcept;

  /// Real-time contract: noexcept, no allocation; safe in the cycle.
  void compute(const ServoInputs& in, bool degraded, ServoOutputs& out) noexcept;

  /// Gains the controller derives from the object's mass/inertia, the client's time step and
  /// the link's one-way delay (s), bounded by the device (model limits), then overridden (within
  /// the same bounds) by the client's non-zero overrides. Real-time contract: safe in the cycle.
  [[nodiscard]] CouplingGains derive_gains(const shm::VprPayload& client,
                                           double link_delay = 0.0) const noexcept;
  /// Current estimate of the client link's one-way delay (s).
  [[nodiscard]] double link_delay() const noexcept { return link_delay_; }

  /// Net energy the user has given the rendering port at the handle (J): negative means the port
  /// delivered more energy to the hand than it received (the guard then adds damping).
  [[nodiscard]] double observed_energy() const noexcept { return memory_.observed_energy; }
  /// Continues from what was rendered last (the committed cycle's memory). Safe in the cycle.
  void continue_from(const RenderMemory& memory) noexcept { memory_ = memory; }
  /// What this law rendered in its last compute(). Safe in the cycle.
  [[nodiscard]] const RenderMemory& memory() const noexcept { return memory_; }
  [[nodiscard]] const LawCounters& counters() const noexcept { return counters_; }
  [[nodiscard]] const LawConfig& config() const noexcept { return config_; }

 private:
  Vector6d client_wrench(const ServoInputs& in, const ClientFrame& frame, const ChainState& chain,
                         const Vector6d& twist, ServoOutputs& out) noexcept;
  Vector6d limit_wrench(const Vector6d& wrench, const shm::VprPayload& client, double dt) noexcept;
  Vector6d guard_passivity(const Vector6d& wrench, const Vector6d& twist, double dt) noexcept;
  Vector6d joint_walls(const Vector6d& q) const noexcept;
  Vector6d workspace_wall() noexcept;
  void express_for_client(const ClientFrame& frame, const Vector6d& twist,
                          ServoOutputs& out) const noexcept;

  const ArmDynamics* dynamics_;
  LawConfig config_;
  ChainState chain_;
  RenderMemory memory_;
  double link_delay_ = 0.0;
  TimeNs previous_age_ = 0;
  LawCounters counters_;
};

}  // namespace hapticctrl::rt_core
