// The handle's walls: the workspace box and the soft joint limits, and the joint-bound bits
// (ServoLaw::workspace_wall, joint_walls, joint_bounds; docs/control.md).
#include <algorithm>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "hapticctrl/shm/payloads.hpp"  // state_bits::joint_bound

namespace hapticctrl::rt_core {

Vector6d ServoLaw::workspace_wall(const Vector3d& velocity) noexcept {
  // A soft wall outside the workspace box pushes the handle back in; it starts at zero force on
  // the box's faces, so it never steps. It damps the motion across it (never pulling the handle
  // out): a handle resting on the undamped wall under a weighted object kept ringing (H1).
  const ArmLimits& lim = dynamics_->model().limits;
  const Vector3d offset = chain_.handle_position - lim.workspace_center;
  const Vector3d outside = (offset.cwiseAbs() - lim.workspace_half_size).cwiseMax(0.0);
  Vector6d wall = Vector6d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (outside(i) > 0.0) {
      const double outward = offset(i) > 0.0 ? 1.0 : -1.0;
      const double push =
          lim.workspace_stiffness * outside(i) + lim.max_damping_linear * velocity(i) * outward;
      wall(i) = -outward * std::max(0.0, push);
    }
  }
  if ((outside.array() > 0.0).any()) {
    ++counters_.workspace_walls;
  }
  return wall;
}

Vector6d ServoLaw::joint_walls(const Vector6d& q) const noexcept {
  const ArmModel& m = dynamics_->model();
  Vector6d tau = Vector6d::Zero();
  const double margin = config_.wall_margin;
  const double k = config_.wall_stiffness;
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = m.joints[static_cast<std::size_t>(i)];
    tau(i) +=
        k * std::max(0.0, j.q_min + margin - q(i)) - k * std::max(0.0, q(i) - (j.q_max - margin));
  }
  const double sum = q(1) + q(2);
  const double coupled = k * std::max(0.0, m.limits.coupled_j23_min + margin - sum) -
                         k * std::max(0.0, sum - (m.limits.coupled_j23_max - margin));
  tau(1) += coupled;
  tau(2) += coupled;
  return tau;
}

std::uint32_t ServoLaw::joint_bounds(const Vector6d& q) const noexcept {
  // In the wall: where joint_walls pushes back (within the margin of the limit, or beyond).
  const ArmModel& m = dynamics_->model();
  const double margin = config_.wall_margin;
  std::uint32_t bits = 0;
  const auto mark = [&](unsigned index, double value, double lo, double hi) {
    bits |= value < lo + margin ? shm::state_bits::joint_bound(index, false) : 0U;
    bits |= value > hi - margin ? shm::state_bits::joint_bound(index, true) : 0U;
  };
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = m.joints[static_cast<std::size_t>(i)];
    mark(static_cast<unsigned>(i), q(i), j.q_min, j.q_max);
  }
  mark(kJoints, q(1) + q(2), m.limits.coupled_j23_min, m.limits.coupled_j23_max);
  return bits;
}

}  // namespace hapticctrl::rt_core
