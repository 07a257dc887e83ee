#include "hapticctrl/rt_core/decoupled_joint_sim.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::rt_core {

DecoupledJointSim::DecoupledJointSim(const DecoupledJointParams& params,
                                     const shm::SeqlockCell<shm::ForcePayload>* force) noexcept
    : params_(params), force_(force), position_(params.start) {}

bool DecoupledJointSim::get_measures(ArmMeasures& out) noexcept {
  out.position = position_;
  out.velocity = velocity_;
  out.torque = applied_torque_;
  out.supply_on = supply_on_;
  return out.position.allFinite() && out.velocity.allFinite();
}

void DecoupledJointSim::read_operator_wrench() noexcept {
  if (force_ == nullptr) {
    return;
  }
  shm::ForcePayload sample;
  if (!force_->read(sample).ok()) {
    return;  // never written or torn: keep the last valid wrench
  }
  bool valid = true;
  for (std::size_t i = 0; i < 6; ++i) {
    const double limit = i < 3 ? params_.max_operator_force : params_.max_operator_torque;
    valid = valid && std::isfinite(sample.wrench[i]) && std::abs(sample.wrench[i]) <= limit;
  }
  if (!valid) {
    ++rejected_;
    return;
  }
  for (Eigen::Index i = 0; i < 6; ++i) {
    operator_wrench_(i) = sample.wrench[static_cast<std::size_t>(i)];
  }
}

void DecoupledJointSim::send_commands(const ArmCommands& commands, TimeNs /*now*/,
                                      TimeNs dt) noexcept {
  read_operator_wrench();
  const double h = static_cast<double>(dt) * 1e-9;
  if (!supply_on_ || !commands.enable || !commands.torque.allFinite()) {
    applied_torque_.setZero();
    velocity_.setZero();  // brakes hold the arm
    return;
  }
  applied_torque_ = commands.torque.cwiseMax(-params_.torque_limit).cwiseMin(params_.torque_limit);
  const Vector6d total =
      applied_torque_ + operator_wrench_ - params_.viscous.cwiseProduct(velocity_);
  velocity_ += total.cwiseQuotient(params_.inertia) * h;  // semi-implicit Euler
  position_ += velocity_ * h;
  for (Eigen::Index i = 0; i < 6; ++i) {
    if (position_(i) < params_.position_min(i) || position_(i) > params_.position_max(i)) {
      position_(i) = std::clamp(position_(i), params_.position_min(i), params_.position_max(i));
      velocity_(i) = 0.0;  // hard stop (F3 models stiff damped stops)
    }
  }
}

}  // namespace hapticctrl::rt_core
