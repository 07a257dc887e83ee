#pragma once
/// @file arm_dynamics.hpp
/// Kinematics and rigid-body dynamics of the 6R chain with fixed-size Eigen types only.
/// Frames: base frame at the J1 axis foot, z up; the handle point is `ArmModel::handle` in the
/// joint-6 frame. Twists and wrenches are {linear, angular} in the base frame, taken at the
/// handle point. Every method is noexcept and allocation-free: safe in the cycle.

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <array>

#include "hapticctrl/arm_model/arm_model.hpp"
#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/arm_io.hpp"

namespace hapticctrl::rt_core {

// The core works in the arm model's types (arm_model/, a contract of its own).
using arm_model::ArmLimits;
using arm_model::ArmModel;
using arm_model::ArmModelError;
using arm_model::default_arm_model_path;
using arm_model::JointModel;
using arm_model::kJoints;
using arm_model::load_arm_model;
using arm_model::Matrix3d;
using arm_model::parse_arm_model;
using arm_model::Vector3d;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// Joint frames and handle pose for one configuration.
struct ChainState {
  std::array<Matrix3d, kJoints> rotation{};  ///< link i frame in base
  std::array<Vector3d, kJoints> position{};  ///< joint i origin in base
  std::array<Vector3d, kJoints> axis{};      ///< joint i axis in base
  Vector3d handle_position = Vector3d::Zero();
  Matrix3d handle_rotation = Matrix3d::Identity();
};

class ArmDynamics {
 public:
  explicit ArmDynamics(const ArmModel& model) noexcept : model_(model) {}

  [[nodiscard]] HAPTICCTRL_RT const ArmModel& model() const noexcept { return model_; }

  /// Forward kinematics of every joint and the handle.
  HAPTICCTRL_RT void forward_kinematics(const Vector6d& q, ChainState& out) const noexcept;
  /// Geometric Jacobian at the handle point: twist = J * qd.
  [[nodiscard]] HAPTICCTRL_RT Matrix6d jacobian(const ChainState& s) const noexcept;
  /// Joint torques for (qd, qdd) under `gravity`, plus an external wrench applied *by* the handle
  /// on the environment (Newton-Euler). Rotor inertia is included.
  [[nodiscard]] HAPTICCTRL_RT Vector6d inverse_dynamics(const ChainState& s, const Vector6d& qd,
                                                        const Vector6d& qdd,
                                                        const Vector3d& gravity) const noexcept;
  /// Joint-space inertia (with rotor inertias).
  [[nodiscard]] HAPTICCTRL_RT Matrix6d mass_matrix(const ChainState& s) const noexcept;
  /// Torque that holds the arm against gravity: G(q).
  [[nodiscard]] HAPTICCTRL_RT Vector6d gravity_torque(const ChainState& s) const noexcept;
  /// Coriolis, centrifugal and gravity torques: C(q, qd) qd + G(q).
  [[nodiscard]] HAPTICCTRL_RT Vector6d bias_torque(const ChainState& s,
                                                   const Vector6d& qd) const noexcept;
  /// Potential energy of the links in the model's gravity field (J).
  [[nodiscard]] double potential_energy(const ChainState& s) const noexcept;

 private:
  ArmModel model_;
};

/// The largest share of a joint's peak torque that holding the arm against gravity needs, over
/// a grid of poses within the joint limits (5 per joint, the coupled J2 + J3 limit respected),
/// and which joint (0-based) needs it. Above 1 the arm cannot be gravity-compensated and the
/// core refuses the model. Not for the cycle (15 625 poses, about 10 ms).
struct GravityDemand {
  double share = 0.0;
  int joint = 0;
};
[[nodiscard]] GravityDemand gravity_demand(const ArmDynamics& dynamics) noexcept;

/// Rotation about a unit `axis` by `angle`. Safe in the cycle.
HAPTICCTRL_RT Matrix3d axis_rotation(const Vector3d& axis, double angle) noexcept;
/// Handle pose as {x, y, z, qx, qy, qz, qw}.
HAPTICCTRL_RT std::array<double, 7> pose_of(const ChainState& s) noexcept;

}  // namespace hapticctrl::rt_core
