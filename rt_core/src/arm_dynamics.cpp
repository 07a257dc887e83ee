// Implements arm_dynamics.hpp: kinematics and rigid-body dynamics of the 6R chain with fixed-size
// Eigen types only.
#include "hapticctrl/rt_core/arm_dynamics.hpp"

#include <array>
#include <cmath>

namespace hapticctrl::rt_core {

Matrix3d axis_rotation(const Vector3d& axis, double angle) noexcept {
  return Eigen::AngleAxisd(angle, axis).toRotationMatrix();
}

std::array<double, 7> pose_of(const ChainState& s) noexcept {
  const Eigen::Quaterniond q(s.handle_rotation);
  return {s.handle_position.x(),
          s.handle_position.y(),
          s.handle_position.z(),
          q.x(),
          q.y(),
          q.z(),
          q.w()};
}

void ArmDynamics::forward_kinematics(const Vector6d& q, ChainState& out) const noexcept {
  Matrix3d rotation = Matrix3d::Identity();
  Vector3d position = Vector3d::Zero();
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = model_.joints[static_cast<std::size_t>(i)];
    position += rotation * j.origin;  // the joint sits on the previous link
    out.axis[static_cast<std::size_t>(i)] = rotation * j.axis;
    rotation = rotation * axis_rotation(j.axis, q(i));
    out.rotation[static_cast<std::size_t>(i)] = rotation;
    out.position[static_cast<std::size_t>(i)] = position;
  }
  out.handle_rotation = rotation;
  out.handle_position = position + rotation * model_.handle;
}

Matrix6d ArmDynamics::jacobian(const ChainState& s) const noexcept {
  Matrix6d jac;
  for (int i = 0; i < kJoints; ++i) {
    const auto k = static_cast<std::size_t>(i);
    jac.block<3, 1>(0, i) = s.axis[k].cross(s.handle_position - s.position[k]);
    jac.block<3, 1>(3, i) = s.axis[k];
  }
  return jac;
}

Vector6d ArmDynamics::inverse_dynamics(const ChainState& s, const Vector6d& qd, const Vector6d& qdd,
                                       const Vector3d& gravity) const noexcept {
  // Forward pass in base coordinates: angular velocity/acceleration of each link and linear
  // acceleration of each joint origin (the base accelerates upward against gravity).
  std::array<Vector3d, kJoints> omega{};
  std::array<Vector3d, kJoints> alpha{};
  std::array<Vector3d, kJoints> force{};
  std::array<Vector3d, kJoints> moment{};
  Vector3d w = Vector3d::Zero();
  Vector3d dw = Vector3d::Zero();
  Vector3d a = -gravity;
  Vector3d previous = Vector3d::Zero();
  for (int i = 0; i < kJoints; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const JointModel& j = model_.joints[k];
    const Vector3d r = s.position[k] - previous;
    a = a + dw.cross(r) + w.cross(w.cross(r));
    const Vector3d joint_rate = s.axis[k] * qd(i);
    dw = dw + s.axis[k] * qdd(i) + w.cross(joint_rate);
    w = w + joint_rate;
    omega[k] = w;
    alpha[k] = dw;
    const Vector3d c = s.rotation[k] * j.com;  // com relative to the joint origin
    const Vector3d a_com = a + dw.cross(c) + w.cross(w.cross(c));
    const Matrix3d inertia = s.rotation[k] * j.inertia * s.rotation[k].transpose();
    force[k] = j.mass * a_com;
    moment[k] = inertia * dw + w.cross(inertia * w) + c.cross(force[k]);
    previous = s.position[k];
  }
  // Backward pass: wrench each joint transmits, about its origin.
  Vector6d tau;
  Vector3d f = Vector3d::Zero();
  Vector3d n = Vector3d::Zero();
  for (int i = kJoints - 1; i >= 0; --i) {
    const auto k = static_cast<std::size_t>(i);
    if (i < kJoints - 1) {
      n = n + (s.position[k + 1] - s.position[k]).cross(f);
    }
    f = f + force[k];
    n = n + moment[k];
    tau(i) = s.axis[k].dot(n) + model_.joints[k].rotor_inertia * qdd(i);
  }
  return tau;
}

Matrix6d ArmDynamics::mass_matrix(const ChainState& s) const noexcept {
  // Composite rigid bodies (links j..n lumped), built from the hand back: one pass instead of one
  // Newton-Euler run per column. 3.1 -> 0.43 us (BM_MassMatrix) and 1 ms of simulation 42 -> 13 us
  // (BM_SimulatorStep1ms), 2026-12-01. Under ASan+UBSan the old way made the simulator's substeps
  // alone fill ~75 % of every period, and coupled cycles missed their deadline.
  double mass = 0.0;
  Vector3d first_moment = Vector3d::Zero();       // sum of m * com, about the base origin
  Matrix3d inertia_at_origin = Matrix3d::Zero();  // rotational inertia about the base origin
  Matrix6d inertia_matrix;
  for (int j = kJoints - 1; j >= 0; --j) {
    const auto k = static_cast<std::size_t>(j);
    const JointModel& link = model_.joints[k];
    const Vector3d com = s.position[k] + s.rotation[k] * link.com;
    mass += link.mass;
    first_moment += link.mass * com;
    inertia_at_origin +=
        s.rotation[k] * link.inertia * s.rotation[k].transpose() +
        link.mass * (com.squaredNorm() * Matrix3d::Identity() - com * com.transpose());
    // Momentum of links j..n when joint j turns at unit rate: velocity of the base origin point
    // v0 = o_j x z_j, linear momentum L = m v0 + z_j x h, angular momentum A = h x v0 + I0 z_j.
    const Vector3d& z = s.axis[k];
    const Vector3d v0 = s.position[k].cross(z);
    const Vector3d linear = mass * v0 + z.cross(first_moment);
    const Vector3d angular = first_moment.cross(v0) + inertia_at_origin * z;
    // Joints i <= j carry that momentum's rate: H(i, j) = z_i . (A - o_i x L).
    for (int i = 0; i <= j; ++i) {
      const auto r = static_cast<std::size_t>(i);
      const double h = s.axis[r].dot(angular - s.position[r].cross(linear));
      inertia_matrix(i, j) = h;
      inertia_matrix(j, i) = h;
    }
    inertia_matrix(j, j) += link.rotor_inertia;
  }
  return inertia_matrix;
}

Vector6d ArmDynamics::gravity_torque(const ChainState& s) const noexcept {
  return inverse_dynamics(s, Vector6d::Zero(), Vector6d::Zero(), model_.gravity);
}

Vector6d ArmDynamics::bias_torque(const ChainState& s, const Vector6d& qd) const noexcept {
  return inverse_dynamics(s, qd, Vector6d::Zero(), model_.gravity);
}

double ArmDynamics::potential_energy(const ChainState& s) const noexcept {
  double energy = 0.0;
  for (int i = 0; i < kJoints; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const Vector3d com = s.position[k] + s.rotation[k] * model_.joints[k].com;
    energy -= model_.joints[k].mass * model_.gravity.dot(com);
  }
  return energy;
}

GravityDemand gravity_demand(const ArmDynamics& dynamics) noexcept {
  constexpr int kSteps = 5;
  const ArmModel& m = dynamics.model();
  GravityDemand worst;
  ChainState chain;
  std::array<int, kJoints> index{};
  for (;;) {
    Vector6d q;
    for (int j = 0; j < kJoints; ++j) {
      const JointModel& joint = m.joints[static_cast<std::size_t>(j)];
      q(j) = joint.q_min +
             (joint.q_max - joint.q_min) * index[static_cast<std::size_t>(j)] / (kSteps - 1);
    }
    const double j23 = q(1) + q(2);
    if (j23 >= m.limits.coupled_j23_min && j23 <= m.limits.coupled_j23_max) {
      dynamics.forward_kinematics(q, chain);
      const Vector6d g = dynamics.gravity_torque(chain);
      for (int j = 0; j < kJoints; ++j) {
        const double share = std::abs(g(j)) / m.joints[static_cast<std::size_t>(j)].torque_peak;
        if (share > worst.share) {
          worst = {share, j};
        }
      }
    }
    int j = 0;  // the next pose of the grid, like an odometer
    while (j < kJoints && ++index[static_cast<std::size_t>(j)] == kSteps) {
      index[static_cast<std::size_t>(j)] = 0;
      ++j;
    }
    if (j == kJoints) {
      return worst;
    }
  }
}

}  // namespace hapticctrl::rt_core
