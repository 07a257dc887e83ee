#pragma once
/// @file arm_model.hpp
/// The arm model: a 6-revolute-joint serial chain with link inertias, joint limits, friction,
/// motor limits and encoders, read from a documented text file (docs/arm_model.md).
/// Loading is setup code (allocates, throws ArmModelError naming the file, line and field).

#include <Eigen/Core>

#include <array>
#include <stdexcept>
#include <string>

namespace hapticctrl::arm_model {

using Vector3d = Eigen::Matrix<double, 3, 1>;
using Matrix3d = Eigen::Matrix<double, 3, 3>;

inline constexpr int kJoints = 6;

struct JointModel {
  Vector3d origin = Vector3d::Zero();   ///< joint position in the previous link frame (q = 0)
  Vector3d axis = Vector3d::UnitZ();    ///< unit rotation axis in this joint's frame
  double mass = 0.0;                    ///< of the link this joint moves, kg
  Vector3d com = Vector3d::Zero();      ///< centre of mass in this link's frame
  Matrix3d inertia = Matrix3d::Zero();  ///< about the centre of mass, link frame
  double q_min = 0.0;
  double q_max = 0.0;
  double viscous = 0.0;        ///< N·m·s/rad
  double coulomb = 0.0;        ///< N·m
  double rotor_inertia = 0.0;  ///< kg·m², reflected to the joint
  double torque_peak = 0.0;
  double torque_continuous = 0.0;
  int encoder_counts = 0;  ///< per revolution
};

struct ArmLimits {
  double coupled_j23_min = -10.0;  ///< J2 + J3 range
  double coupled_j23_max = 10.0;
  double force_peak = 0.0;
  double force_continuous = 0.0;
  double torque_peak = 0.0;
  double torque_continuous = 0.0;
  double max_stiffness_linear = 0.0;
  double max_stiffness_angular = 0.0;
  double max_damping_linear = 0.0;
  double max_damping_angular = 0.0;
  double max_speed = 0.0;                        ///< handle speed safety threshold, m/s
  double force_rate = 0.0;                       ///< N/s
  Vector3d workspace_center = Vector3d::Zero();  ///< handle workspace box, base frame
  Vector3d workspace_half_size = Vector3d::Zero();
  double workspace_stiffness = 0.0;  ///< N/m, soft wall outside the box
};

struct ArmModel {
  std::string name;
  Vector3d gravity{0.0, 0.0, -9.81};
  std::array<JointModel, kJoints> joints{};
  Vector3d handle = Vector3d::Zero();  ///< handle point in the joint-6 frame
  ArmLimits limits;
};

class ArmModelError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Parses a model from text; `source` names it in error messages.
ArmModel parse_arm_model(const std::string& text, const std::string& source);
/// Loads a model file. Throws ArmModelError (also when the file cannot be read).
ArmModel load_arm_model(const std::string& path);
/// The default model file shipped with the build (arm_model/models/virtuose6d_class.arm).
std::string default_arm_model_path();

}  // namespace hapticctrl::arm_model
