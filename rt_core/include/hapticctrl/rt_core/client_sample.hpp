#pragma once
/// @file client_sample.hpp
/// The client's state as the control law sees it. The SERVO converts each valid VPr sample (the
/// shared-memory ABI, shm::VprPayload) into this at the edge (servo.cpp), so the law depends on
/// its own types only and a change of the region's layout stops at the conversion.

#include <array>
#include <cstdint>

namespace hapticctrl::rt_core {

/// What the client asks the controller to render.
enum class ClientCommand : std::uint8_t {
  kNone,                ///< nothing: the coupling is released
  kImpedance,           ///< render impedance_wrench at the handle
  kVirtmech,            ///< couple the handle to the client's object (spring-damper)
  kArticular,           ///< hold the joints at set points that follow joint_target (J6)
  kArticularImpedance,  ///< render joint_torque at the joints (J6)
};

/// Contact slots a client may use (protocol 1.3).
inline constexpr std::size_t kMaxClientContacts = 8;

/// A contact of the client's object: a plane through point - distance * normal, perpendicular to
/// normal, that the object touches (distance <= 0) or is near (client's environment frame).
struct ClientContact {
  std::array<double, 3> point{};     ///< on the object [m]
  std::array<double, 3> normal{};    ///< unit: the direction in which the surface pushes the object
  double distance = 0.0;             ///< signed gap along normal [m]
  double stiffness = 0.0;            ///< [N/m]; 0: no contact in this slot
  double damping = 0.0;              ///< [N·s/m]
  std::array<double, 2> friction{};  ///< static, dynamic
  std::array<double, 7> object_pose{0, 0, 0, 0, 0, 0, 1};  ///< the object when it came
  TimePoint received;  ///< when it arrived (our clock): it fades 30 ms after
};

/// One client sample (units SI; poses x, y, z, qx, qy, qz, qw; twists and wrenches linear first).
struct ClientSample {
  std::uint64_t session_id = 0;  ///< 0: no client session
  ClientCommand command = ClientCommand::kNone;
  bool object_attached = false;  ///< VIRTMECH: the client has attached an object
  std::array<double, 7> object_pose{0, 0, 0, 0, 0, 0, 1};  ///< client's environment frame
  std::array<double, 6> object_twist{};
  std::array<double, 6> impedance_wrench{};  ///< IMPEDANCE, environment frame [N, N·m]
  std::array<double, 6> joint_target{};      ///< ARTICULAR: joint positions [rad]
  std::array<double, 6> joint_speed{};       ///< ARTICULAR: joint speeds [rad/s]
  std::array<double, 6> joint_torque{};      ///< ARTICULAR_IMPEDANCE: joint torques [N·m]
  /// The joint command of the command type in force has come (until then: nothing rendered).
  bool joint_command = false;
  double object_mass = 0.0;                ///< kg, 0: not declared
  std::array<double, 3> object_inertia{};  ///< principal inertia, kg·m², 0: not declared
  double time_step = 0.0;                  ///< the client's simulation step, s (0: unknown)
  double force_factor = 1.0;
  double speed_factor = 1.0;
  std::array<double, 7> base_frame{0, 0, 0, 0, 0, 0, 1};  ///< our base in its environment
  std::array<double, 4> gain_override{};  ///< k_lin, b_lin, k_ang, b_ang; 0 = derived
  std::array<double, 2> force_limits{};   ///< max force [N], max torque [N·m]; 0 = model's
  /// Energy the client's object has put into the coupling channel since the session began (J;
  /// negative: not reported, no two-port passivity).
  double energy_in = -1.0;
  /// Protocol 1.3: the client closes its object's side of the coupling itself (the core then
  /// stiffens the coupling along a contact, and an IMPEDANCE wrench is inside the two-port).
  bool local_coupling = false;
  std::uint32_t contact_count = 0;  ///< slots in use (the valid ones have stiffness > 0)
  std::array<ClientContact, kMaxClientContacts> contacts{};
};

}  // namespace hapticctrl::rt_core
