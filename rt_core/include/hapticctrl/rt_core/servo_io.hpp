#pragma once
/// @file servo_io.hpp
/// What the servo law (servo_law.hpp) takes and gives in one cycle: its inputs, the gains it
/// derived, its outputs (motor torques, the wrenches it renders and reports), and the client's
/// frame it derives from a sample.
///
/// Real-time contract: plain fixed-size structs; client_frame_of is safe in the cycle.

#include <cstdint>
#include <optional>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_dynamics.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"
#include "hapticctrl/rt_core/client_sample.hpp"
#include "hapticctrl/rt_core/logical_state.hpp"

namespace hapticctrl::rt_core {

/// Everything the law may use for one cycle.
struct ServoInputs {
  std::uint64_t cycle = 0;
  TimePoint now;
  Duration dt{0};
  ArmMeasures measures;
  LogicalState logical;
  ClientSample client;        ///< last valid client sample
  bool client_valid = false;  ///< a valid client sample exists
  /// True age of that sample: now - when the client computed it (network + bridge + waiting,
  /// from the protocol's timing echo; since its arrival for a client without it).
  Duration client_age{0};
  Duration client_silence{0};  ///< now - arrival of the newest sample (link freshness)
  bool new_sample = false;     ///< the sample arrived this cycle
  /// Coupling loop delay measured with that sample: from the core's answer the client had to
  /// this cycle (0: unknown, the law then assumes LawConfig::assumed_loop_delay).
  Duration loop_delay{0};
};

/// Coupling gains (base frame): linear N/m, N·s/m; angular N·m/rad, N·m·s/rad.
struct CouplingGains {
  double k_linear = 0.0;
  double b_linear = 0.0;
  double k_angular = 0.0;
  double b_angular = 0.0;
};

struct ServoOutputs {
  ArmCommands commands;
  /// Wrench the coupling applies to the client's object (what VP reports), base frame.
  Vector6d object_wrench = Vector6d::Zero();
  /// Wrench the controller renders on the handle (before the Jacobian transpose), base frame.
  Vector6d rendered_wrench = Vector6d::Zero();
  std::array<double, 7> handle_pose{0, 0, 0, 0, 0, 0, 1};  ///< base frame
  Vector6d handle_twist = Vector6d::Zero();                ///< base frame
  /// The same, in the client's environment frame (through its base frame and speed factor).
  std::array<double, 7> client_handle_pose{0, 0, 0, 0, 0, 0, 1};
  Vector6d client_handle_twist = Vector6d::Zero();
  double fade = 1.0;    ///< share of the coupling left by a silent link (1: fresh, 0: faded)
  double engage = 1.0;  ///< share of the coupling the handle gets (re-engagement, brake)
  bool coupled = false;
  bool client_stale = false;
  bool braking = false;         ///< handle over the speed limit: the damped brake is on
  bool velocity_fault = false;  ///< over the speed limit for LawConfig::overspeed_fault_after
  bool saturated = false;       ///< the coupling was clipped to the force or torque limit
  /// shm::state_bits::joint_bound bits of the joints (and the J2 + J3 sum) in their walls.
  std::uint32_t joint_bounds = 0;
  CouplingGains gains;     ///< gains in force this cycle (zero when not coupled)
  Duration loop_delay{0};  ///< loop delay the gains are designed for
  /// The coupling is stiffer along `contact_normal` (base frame; its length is the share of the
  /// contact in force, 0..1: fresh and touching; zero: none) by `normal_stiffness` /
  /// `normal_damping` while it pushes the object into the contact (protocol 1.3: a client closes
  /// its object's side along it, in that share).
  Vector3d contact_normal = Vector3d::Zero();
  double normal_stiffness = 0.0;
  double normal_damping = 0.0;
  std::uint32_t contacts = 0;  ///< the client's contacts in force (fresh)
  /// The reported surface rendered on the handle (base frame; normal zero: none): a point on
  /// the plane as rendered, how deep the handle's point is in it, its force along the normal,
  /// the depth a model update hid, and the age of the newest contact in force (-1: none).
  Vector3d surface_point = Vector3d::Zero();
  Vector3d surface_normal = Vector3d::Zero();
  double surface_depth = 0.0;
  double surface_force = 0.0;
  double surface_hidden = 0.0;
  std::optional<Duration> contact_age;  ///< of the newest fresh contact; none: no contact
  double surface_withheld = 0.0;        ///< J this session: what hidden depth kept from the hand
  double force_limit = 0.0;             ///< the coupling's force and torque limits in force
  double torque_limit = 0.0;
  /// Two-port passivity, the core's end of the channel (J since the session began).
  double channel_energy_in = 0.0;
  double channel_energy_out = 0.0;
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
HAPTICCTRL_RT ClientFrame client_frame_of(const ClientSample& client) noexcept;

}  // namespace hapticctrl::rt_core
