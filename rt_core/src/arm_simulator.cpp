// Implements arm_simulator.hpp: rigid-body simulation of the arm: M(q) qdd + C(q, qd) qd + G(q) =
// tau_motor + J^T w_operator + tau_friction + tau_stops, integrated with semi-implicit Euler in
// sub-steps.
#include "hapticctrl/rt_core/arm_simulator.hpp"

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/shm/force_slew.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

/// Velocity filter time constant of the measured velocity (s): a 1st-order low-pass on the
/// encoder finite difference, as ARM_REFERENCE proposes.
constexpr double kVelocityFilterTau = 0.002;

HAPTICCTRL_RT Vector3d to_vector(const std::array<double, 3>& a) noexcept {
  return {a[0], a[1], a[2]};
}

}  // namespace

Vector3d HandModel::force(const Vector3d& position, const Vector3d& velocity,
                          double elapsed) const noexcept {
  const Vector3d target = anchor + anchor_velocity * elapsed;
  return stiffness * (target - position) + damping * (anchor_velocity - velocity);
}

Vector3d HandModel::torque(const Matrix3d& rotation,
                           const Vector3d& angular_velocity) const noexcept {
  return angular_stiffness * law_math::rotation_vector(anchor_rotation * rotation.transpose()) -
         angular_damping * angular_velocity;
}

ArmSimulator::ArmSimulator(const ArmDynamics& dynamics, const SimulatorOptions& options,
                           const Vector6d& start) noexcept
    : dynamics_(&dynamics), options_(options), q_(start) {
  dynamics_->forward_kinematics(q_, chain_);
}

void ArmSimulator::set_state(const Vector6d& q, const Vector6d& qd) noexcept {
  q_ = q;
  qd_ = qd;
  dynamics_->forward_kinematics(q_, chain_);
}

Vector6d ArmSimulator::passive_torques() const noexcept {
  const ArmModel& m = dynamics_->model();
  Vector6d tau = Vector6d::Zero();
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = m.joints[static_cast<std::size_t>(i)];
    if (options_.friction) {
      tau(i) -= j.viscous * qd_(i) + j.coulomb * std::tanh(qd_(i) / options_.coulomb_velocity);
    }
    const double below = q_(i) - j.q_min;
    const double above = q_(i) - j.q_max;
    if (below < 0.0) {
      tau(i) -= options_.stop_stiffness * below + options_.stop_damping * std::min(qd_(i), 0.0);
    } else if (above > 0.0) {
      tau(i) -= options_.stop_stiffness * above + options_.stop_damping * std::max(qd_(i), 0.0);
    }
  }
  // Coupled J2 + J3 stop (the Virtuose AXE_2_3 limit) acts on both joints.
  const double sum = q_(1) + q_(2);
  const double sum_rate = qd_(1) + qd_(2);
  double coupled = 0.0;
  if (sum < m.limits.coupled_j23_min) {
    coupled = -options_.stop_stiffness * (sum - m.limits.coupled_j23_min) -
              options_.stop_damping * std::min(sum_rate, 0.0);
  } else if (sum > m.limits.coupled_j23_max) {
    coupled = -options_.stop_stiffness * (sum - m.limits.coupled_j23_max) -
              options_.stop_damping * std::max(sum_rate, 0.0);
  }
  tau(1) += coupled;
  tau(2) += coupled;
  return tau;
}

void ArmSimulator::step(const Vector6d& motor_torque, const Vector6d& operator_wrench, double dt,
                        bool brakes, const HandModel& hand) noexcept {
  if (brakes) {
    qd_.setZero();
    limit_operator(operator_wrench, dt);  // a held handle: the hand is not evaluated
    return;
  }
  const int substeps = std::max(1, static_cast<int>(std::ceil(dt / options_.max_substep - 1e-9)));
  const double h = dt / substeps;
  for (int n = 0; n < substeps; ++n) {
    const Matrix6d inertia_matrix = dynamics_->mass_matrix(chain_);
    const Vector6d bias = dynamics_->bias_torque(chain_, qd_);
    const Matrix6d jacobian = dynamics_->jacobian(chain_);
    Vector6d target = operator_wrench;
    if (hand.gripping()) {
      const Vector3d handle_velocity = jacobian.topRows<3>() * qd_;
      target.head<3>() += hand.force(chain_.handle_position, handle_velocity, n * h);
      if (hand.holds_rotation()) {  // no rotation vector per sub-step for a hand without a wrist
        target.tail<3>() += hand.torque(chain_.handle_rotation, jacobian.bottomRows<3>() * qd_);
      }
    }
    limit_operator(target, h);
    const Vector6d external = jacobian.transpose() * operator_applied_;
    const Vector6d qdd =
        inertia_matrix.ldlt().solve(motor_torque + external + passive_torques() - bias);
    qd_ += qdd * h;  // semi-implicit Euler: new velocity, then position
    q_ += qd_ * h;
    dynamics_->forward_kinematics(q_, chain_);
  }
}

void ArmSimulator::limit_operator(const Vector6d& target, double h) noexcept {
  const shm::ForceLimits& l = options_.operator_limits;
  for (int i = 0; i < 6; ++i) {
    const double peak = i < 3 ? l.max_force : l.max_torque;
    const double step = (i < 3 ? l.force_rate : l.torque_rate) * h;
    const double wanted = std::clamp(target(i), -peak, peak);
    operator_applied_(i) += std::clamp(wanted - operator_applied_(i), -step, step);
  }
}

double ArmSimulator::energy() const noexcept {
  const Matrix6d inertia_matrix = dynamics_->mass_matrix(chain_);
  // Elastic energy stored in compressed joint stops belongs to the total as well.
  const ArmModel& m = dynamics_->model();
  auto compression = [](double x, double lo, double hi) {
    return x < lo ? x - lo : (x > hi ? x - hi : 0.0);
  };
  double stops = 0.0;
  for (int i = 0; i < kJoints; ++i) {
    const JointModel& j = m.joints[static_cast<std::size_t>(i)];
    const double c = compression(q_(i), j.q_min, j.q_max);
    stops += 0.5 * options_.stop_stiffness * c * c;
  }
  const double c23 = compression(q_(1) + q_(2), m.limits.coupled_j23_min, m.limits.coupled_j23_max);
  stops += 0.5 * options_.stop_stiffness * c23 * c23;
  return 0.5 * qd_.dot(inertia_matrix * qd_) + dynamics_->potential_energy(chain_) + stops;
}

SimulatedArm::SimulatedArm(const ArmDynamics& dynamics, const SimulatorOptions& options,
                           const Vector6d& start,
                           const shm::SeqlockCell<shm::ForcePayload>* force) noexcept
    : dynamics_(&dynamics),
      sim_(dynamics, options, start),
      force_(force),
      measured_position_(quantised(start)) {}

Vector6d SimulatedArm::quantised(const Vector6d& q) const noexcept {
  Vector6d out;
  for (int i = 0; i < kJoints; ++i) {
    const double step = 2.0 * std::numbers::pi /
                        dynamics_->model().joints[static_cast<std::size_t>(i)].encoder_counts;
    out(i) = std::round(q(i) / step) * step;
  }
  return out;
}

bool SimulatedArm::get_measures(ArmMeasures& out) noexcept {
  out.position = measured_position_;
  out.velocity = measured_velocity_;
  out.torque = applied_torque_;
  out.supply_on = supply_on_.load(std::memory_order_acquire);
  out.operator_wrench = operator_wrench();
  out.operator_wrench_rejected = rejected_;
  return out.position.allFinite() && out.velocity.allFinite();
}

void SimulatedArm::read_operator_wrench() noexcept {
  if (force_ == nullptr) {
    return;
  }
  shm::ForcePayload sample;
  const shm::ReadResult r = force_->read(sample);
  if (!r.ok() || r.sequence == force_sequence_) {
    return;  // never written, torn, or already seen: keep the last valid wrench
  }
  force_sequence_ = r.sequence;                  // each refused sample is counted once
  if (!shm::wrench_acceptable(sample.wrench)) {  // non-finite, or beyond 100 N / 10 N·m
    ++rejected_;
    return;
  }
  if (!shm::hand_acceptable(sample.hand)) {  // a refused sample changes neither wrench nor hand
    ++rejected_;
    return;
  }
  for (int i = 0; i < 6; ++i) {
    operator_wrench_(i) = sample.wrench[static_cast<std::size_t>(i)];
  }
  hand_.anchor = to_vector(sample.hand.anchor);
  hand_.anchor_velocity = to_vector(sample.hand.anchor_velocity);
  hand_.stiffness = sample.hand.stiffness;
  hand_.damping = sample.hand.damping;
  const auto& q = sample.hand.anchor_rotation;
  hand_.anchor_rotation =
      q[3] * q[3] + q[0] * q[0] + q[1] * q[1] + q[2] * q[2] > 0.5
          ? Eigen::Quaterniond(q[3], q[0], q[1], q[2]).normalized().toRotationMatrix()
          : Matrix3d::Identity();
  hand_.angular_stiffness = sample.hand.angular_stiffness;
  hand_.angular_damping = sample.hand.angular_damping;
}

void SimulatedArm::send_commands(const ArmCommands& commands, TimePoint /*now*/,
                                 Duration dt) noexcept {
  read_operator_wrench();
  const bool enabled =
      supply_on_.load(std::memory_order_acquire) && commands.enable && commands.torque.allFinite();
  applied_torque_.setZero();
  if (enabled) {
    for (int i = 0; i < kJoints; ++i) {
      const double limit = dynamics_->model().joints[static_cast<std::size_t>(i)].torque_peak;
      applied_torque_(i) = std::clamp(commands.torque(i), -limit, limit);
    }
  }
  const double h = to_seconds(dt);
  sim_.step(applied_torque_, operator_wrench_, h, /*brakes=*/!enabled, hand_);
  const Vector6d previous = measured_position_;
  measured_position_ = quantised(sim_.position());
  const Vector6d raw_velocity = (measured_position_ - previous) / h;
  const double blend = h / (kVelocityFilterTau + h);
  measured_velocity_ += blend * (raw_velocity - measured_velocity_);
}

}  // namespace hapticctrl::rt_core
