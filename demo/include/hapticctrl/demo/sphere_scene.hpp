#pragma once
/// @file sphere_scene.hpp
/// The demo client's physics engine: two half-rigid spheres, one fixed, one mobile (mass,
/// isotropic inertia) coupled to the arm; or the mobile sphere and a wall (a plane). Contact is a
/// penalty force: stiffness and damping along the line of centres (never pulling), and Coulomb
/// friction modelled as a tangential spring-damper anchored where the spheres touched, which slips
/// beyond mu times the normal force; and rolling resistance of the flattened contact patch, an
/// angular spring-damper that gives way beyond rolling_resistance * normal force * radius. Without
/// them a sphere pushed onto a sphere by a force with no lateral stiffness (the operator's hand on
/// a gravity-compensated arm) slides or rolls off sideways: that equilibrium is unstable. Gravity
/// is optional; integration is semi-implicit Euler at the client's time step. Allocation-free; the
/// integrator reads no clock (it takes dt), so a scenario of any length is a fast deterministic
/// test.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::demo {

/// What the mobile sphere meets: the fixed sphere, or a wall (a plane through fixed_center,
/// facing -toward: the mobile sphere starts on that side of it).
enum class Obstacle : std::uint8_t { kSphere, kWall };

struct SceneConfig {
  Obstacle obstacle = Obstacle::kSphere;
  /// Where the obstacle is from the mobile sphere's start (unit, client frame).
  Eigen::Vector3d toward = Eigen::Vector3d::UnitX();
  Eigen::Vector3d fixed_center = Eigen::Vector3d::Zero();  ///< client frame [m]
  double fixed_radius = 0.03;                              ///< m
  double mobile_radius = 0.03;                             ///< m
  double mass = 0.5;                                       ///< kg
  double contact_stiffness = 2000.0;                       ///< N/m
  double contact_damping = 60.0;                           ///< N.s/m
  double friction = 0.6;                                   ///< Coulomb coefficient mu
  double rolling_resistance = 0.1;  ///< torque limit / (normal force * mobile radius)
  bool gravity = false;
  Eigen::Vector3d gravity_vector{0.0, 0.0, -9.81};  ///< m/s^2, client frame

  /// Solid-sphere principal inertia of the mobile sphere (kg.m^2): 2/5 m r^2.
  [[nodiscard]] double inertia() const noexcept {
    return 0.4 * mass * mobile_radius * mobile_radius;
  }
  /// Throws std::invalid_argument naming the first non-positive or non-finite value.
  void validate() const;
};

/// The mobile sphere's state.
struct SphereState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();  ///< client frame
};

class SphereScene {
 public:
  SphereScene(const SceneConfig& config, const SphereState& start) noexcept;

  /// Advances by `dt` seconds under the coupling wrench (from the controller) and an applied
  /// wrench (keyboard or script), both on the mobile sphere's centre, client frame.
  void step(const client::Vector6& coupling, const client::Vector6& applied, double dt) noexcept;

  [[nodiscard]] const SphereState& state() const noexcept { return state_; }
  [[nodiscard]] const SceneConfig& config() const noexcept { return config_; }
  /// Moves the obstacle (sphere or wall) by `by` (m, client frame) at once: a surface that
  /// jumps, for the model updates J2 keeps passive. A non-finite move is ignored.
  void move_obstacle(const Eigen::Vector3d& by) noexcept;
  /// Contact force the fixed sphere exerts on the mobile one at the current state (N): normal
  /// push plus friction.
  [[nodiscard]] Eigen::Vector3d contact_force() const noexcept;
  /// How deep the spheres overlap (m); 0 apart.
  [[nodiscard]] double penetration() const noexcept;
  /// The mobile sphere as the protocol wants it: pose {x y z qx qy qz qw} and twist.
  [[nodiscard]] client::Pose7 pose() const noexcept;
  [[nodiscard]] client::Vector6 twist() const noexcept;
  /// Kinetic energy (J), for tests and the log.
  [[nodiscard]] double kinetic_energy() const noexcept;
  /// The contact with the fixed sphere as the controller takes it (protocol 1.3), while the
  /// spheres touch or are within `near` metres: the fixed sphere's surface as a plane at the
  /// mobile sphere's nearest point, with the configured stiffness (at most `max_stiffness`),
  /// damping and friction. Nothing when farther apart.
  [[nodiscard]] std::optional<client::Contact> contact_report(double near,
                                                              double max_stiffness) const noexcept;
  /// The same, with the fixed sphere's surface as the plane tangent to it toward `probe` (the
  /// handle, which the controller renders the plane for: J2) instead of toward the mobile
  /// sphere, which a soft coupling lets lag the handle; `distance` is the mobile sphere's gap to
  /// that plane. A wall is the same plane either way.
  [[nodiscard]] std::optional<client::Contact> contact_report_toward(
      const Eigen::Vector3d& probe, double near, double max_stiffness) const noexcept;
  /// IMPEDANCE (protocol 1.3): the same surface as a plane for the mobile sphere's centre (the
  /// handle's point): `point` is where the centre touches it, the sphere's radius taken in.
  [[nodiscard]] std::optional<client::Contact> surface_for_center(
      double near, double max_stiffness) const noexcept;
  /// IMPEDANCE: the mobile sphere is the handle (no dynamics of its own): it takes the handle's
  /// pose and twist; contact_force() is then the wrench to render.
  void follow(const client::Pose7& pose, const client::Vector6& twist) noexcept;
  /// Normal contact stiffness and damping in force at the last step (N/m, N.s/m).
  [[nodiscard]] double contact_stiffness() const noexcept { return gains_.normal_k; }
  [[nodiscard]] double contact_damping() const noexcept { return gains_.normal_b; }

 private:
  /// Contact stiffness and damping as applied: the configured ones, bounded so that the
  /// explicit integration stays stable at the step in use (omega * dt <= 1, damping * dt <=
  /// half the mass it acts on).
  struct ContactGains {
    double normal_k = 0.0, normal_b = 0.0;
    double tangent_k = 0.0, tangent_b = 0.0;
    double rolling_k = 0.0, rolling_b = 0.0;
  };
  [[nodiscard]] ContactGains gains_for(double dt) const noexcept;

  struct Contact {
    Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  ///< from the fixed to the mobile sphere
    double depth = 0.0;                                 ///< m; <= 0 apart
    Eigen::Vector3d slip_velocity = Eigen::Vector3d::Zero();  ///< tangential, at the contact
  };
  [[nodiscard]] Contact contact() const noexcept;
  [[nodiscard]] double normal_push(const Contact& c) const noexcept;
  /// Normal push plus friction for contact `c` pushing with `push` (N).
  [[nodiscard]] Eigen::Vector3d force_of(const Contact& c, double push) const noexcept;
  /// Moves the friction anchor with the tangential slip; lets it slide beyond mu * normal.
  void update_stretch(const Contact& c, double push, double dt) noexcept;
  /// Resisting torque of the contact patch against rolling and spinning.
  [[nodiscard]] Eigen::Vector3d rolling_torque(double push) const noexcept;

  SceneConfig config_;
  SphereState state_;
  ContactGains gains_;
  Eigen::Vector3d stretch_ = Eigen::Vector3d::Zero();  ///< friction spring, tangent plane
  Eigen::Vector3d twist_ = Eigen::Vector3d::Zero();    ///< rolling spring (rotation vector)
};

}  // namespace hapticctrl::demo
