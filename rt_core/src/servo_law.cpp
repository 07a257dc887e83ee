#include "hapticctrl/rt_core/servo_law.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::rt_core {
namespace {

/// Fraction of the explicit-integration stability bound (k < 4 m / T²) used for the derived
/// stiffness, and the damping ratio of the derived damping.
constexpr double kStiffnessFraction = 0.25;
constexpr double kDampingRatio = 0.7;
/// Per-sample gain of the link-delay average (about 20 samples).
constexpr double kDelayFilterGain = 0.05;

Vector6d to_vector(const std::array<double, 6>& a) noexcept {
  Vector6d v;
  for (int i = 0; i < 6; ++i) {
    v(i) = a[static_cast<std::size_t>(i)];
  }
  return v;
}

Eigen::Quaterniond to_quaternion(const std::array<double, 7>& pose) noexcept {
  return {pose[6], pose[3], pose[4], pose[5]};  // w, x, y, z
}

/// Scales `v` down to norm `limit` if longer.
Vector3d clamp_norm(const Vector3d& v, double limit) noexcept {
  const double n = v.norm();
  return n > limit && n > 0.0 ? Vector3d(v * (limit / n)) : v;
}

double bounded(double value, double upper) noexcept {
  return std::clamp(value, 0.0, upper);
}

}  // namespace

ClientFrame client_frame_of(const shm::VprPayload& c) noexcept {
  ClientFrame frame;
  const Eigen::Quaterniond q = to_quaternion(c.base_frame);
  if (q.norm() > 0.5) {
    frame.rotation = q.normalized();
  }
  frame.origin = Vector3d(c.base_frame[0], c.base_frame[1], c.base_frame[2]);
  frame.speed_factor = c.speed_factor > 0.0 ? c.speed_factor : 1.0;
  frame.force_factor = c.force_factor > 0.0 ? c.force_factor : 1.0;
  return frame;
}

ServoLaw::ServoLaw(const ArmDynamics& dynamics, const LawConfig& config) noexcept
    : dynamics_(&dynamics), config_(config) {}

CouplingGains ServoLaw::derive_gains(const shm::VprPayload& c, double link_delay) const noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  const double mass = c.object_mass > 0.0 ? c.object_mass : config_.default_object_mass;
  // The object sees the coupling's answer to its own motion one client step plus a round trip
  // of the link later: that whole lag bounds the stiffness it can take.
  const double client_step =
      c.client_time_step > 0.0 ? c.client_time_step : config_.default_time_step;
  const double step = client_step + 2.0 * std::max(0.0, link_delay);
  const double largest_inertia =
      std::max({c.object_inertia[0], c.object_inertia[1], c.object_inertia[2]});
  // Without a declared inertia: a solid 5 cm sphere of the object's mass.
  const double inertia = largest_inertia > 0.0 ? largest_inertia : 0.4 * mass * 0.05 * 0.05;
  CouplingGains g;
  g.k_linear = bounded(kStiffnessFraction * mass / (step * step), lim.max_stiffness_linear);
  g.b_linear = bounded(2.0 * kDampingRatio * std::sqrt(g.k_linear * mass),
                       std::min(lim.max_damping_linear, mass / step));
  g.k_angular = bounded(kStiffnessFraction * inertia / (step * step), lim.max_stiffness_angular);
  g.b_angular = bounded(2.0 * kDampingRatio * std::sqrt(g.k_angular * inertia),
                        std::min(lim.max_damping_angular, inertia / step));
  const auto& o = c.gain_override;
  if (o[0] > 0.0) {
    g.k_linear = bounded(o[0], lim.max_stiffness_linear);
  }
  if (o[1] > 0.0) {
    g.b_linear = bounded(o[1], lim.max_damping_linear);
  }
  if (o[2] > 0.0) {
    g.k_angular = bounded(o[2], lim.max_stiffness_angular);
  }
  if (o[3] > 0.0) {
    g.b_angular = bounded(o[3], lim.max_damping_angular);
  }
  return g;
}

Vector6d ServoLaw::client_wrench(const ServoInputs& in, const ClientFrame& frame,
                                 const ChainState& chain, const Vector6d& twist,
                                 ServoOutputs& out) noexcept {
  const shm::VprPayload& c = in.client;
  if (!in.client_valid || c.session_id == 0) {
    return Vector6d::Zero();  // no session: the rate limiter ramps any previous wrench out
  }
  const double fade =
      in.client_age <= config_.fade_after
          ? 1.0
          : std::clamp(1.0 - static_cast<double>(in.client_age - config_.fade_after) /
                                 static_cast<double>(config_.fade_duration),
                       0.0, 1.0);
  out.fade = fade;
  if (fade <= 0.0) {
    return Vector6d::Zero();
  }
  // Client poses are in its environment frame; base_frame is our base in that frame.
  const Matrix3d base_r = frame.rotation.toRotationMatrix();
  const double speed_factor = frame.speed_factor;

  if (c.command_type == static_cast<std::uint32_t>(shm::CommandType::kImpedance)) {
    const Vector6d env = to_vector(c.impedance_wrench);
    Vector6d w;
    w << base_r.transpose() * env.head<3>(), base_r.transpose() * env.tail<3>();
    return w * (fade * frame.force_factor);
  }
  if (c.command_type != static_cast<std::uint32_t>(shm::CommandType::kVirtmech) ||
      (c.flags & shm::vpr_flags::kObjectAttached) == 0) {
    return Vector6d::Zero();  // VIRTMECH couples an attached object only
  }
  const Eigen::Quaterniond object_q_env = to_quaternion(c.object_pose);
  if (object_q_env.norm() < 0.5) {
    return Vector6d::Zero();  // not a rotation: refuse rather than guess
  }
  // Object state in the base frame (positions de-scaled by the speed factor).
  const Vector3d object_p_env(c.object_pose[0], c.object_pose[1], c.object_pose[2]);
  Vector3d object_p = base_r.transpose() * (object_p_env - frame.origin) / speed_factor;
  Matrix3d object_r = base_r.transpose() * object_q_env.normalized().toRotationMatrix();
  const Vector6d twist_env = to_vector(c.object_twist);
  const Vector3d object_v = base_r.transpose() * twist_env.head<3>() / speed_factor;
  const Vector3d object_w = base_r.transpose() * twist_env.tail<3>();
  // Best estimate of where the object is now: extrapolate over the sample's age (bounded).
  const double horizon =
      static_cast<double>(std::min(in.client_age, config_.extrapolate_max)) * 1e-9;
  object_p += object_v * horizon;
  if (object_w.norm() * horizon > 1e-12) {
    object_r = Eigen::AngleAxisd(object_w.norm() * horizon, object_w.normalized()) * object_r;
  }

  // Link delay estimate: average age of client samples at the moment they arrive (staleness
  // after that is the fade's business, not the gains').
  if (in.client_age < previous_age_) {
    link_delay_ += (static_cast<double>(in.client_age) * 1e-9 - link_delay_) * kDelayFilterGain;
  }
  previous_age_ = in.client_age;
  const CouplingGains g = derive_gains(c, link_delay_);
  const Vector3d e_p = object_p - chain.handle_position;
  const Eigen::AngleAxisd e_rot(object_r * chain.handle_rotation.transpose());
  const Vector3d e_r = e_rot.axis() * e_rot.angle();
  Vector6d e_rate;
  e_rate << object_v - twist.head<3>(), object_w - twist.tail<3>();
  Vector6d w;
  w << g.k_linear * e_p + g.b_linear * e_rate.head<3>(),
      g.k_angular * e_r + g.b_angular * e_rate.tail<3>();

  out.coupled = true;
  return w * (fade * frame.force_factor);
}

Vector6d ServoLaw::limit_wrench(const Vector6d& wrench, const shm::VprPayload& client,
                                double dt) noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  const double force_limit = client.force_limits[0] > 0.0
                                 ? std::min(client.force_limits[0], lim.force_peak)
                                 : lim.force_peak;
  const double torque_limit = client.force_limits[1] > 0.0
                                  ? std::min(client.force_limits[1], lim.torque_peak)
                                  : lim.torque_peak;
  Vector6d target;
  target << clamp_norm(wrench.head<3>(), force_limit), clamp_norm(wrench.tail<3>(), torque_limit);
  // Rate limit: never a step larger than force_rate * dt (torque scaled like the peaks).
  const double max_force_step = lim.force_rate * dt;
  const double max_torque_step = lim.force_rate * (lim.torque_peak / lim.force_peak) * dt;
  const Vector6d& last = memory_.wrench;
  const Vector3d df = target.head<3>() - last.head<3>();
  const Vector3d dtau = target.tail<3>() - last.tail<3>();
  if (df.norm() > max_force_step || dtau.norm() > max_torque_step) {
    ++counters_.rate_limited;
  }
  Vector6d limited;
  limited << last.head<3>() + clamp_norm(df, max_force_step),
      last.tail<3>() + clamp_norm(dtau, max_torque_step);
  memory_.wrench = limited;
  return limited;
}

Vector6d ServoLaw::workspace_wall() noexcept {
  // A soft wall outside the workspace box pushes the handle back in; it starts at zero force on
  // the box's faces, so it never steps.
  const ArmLimits& lim = dynamics_->model().limits;
  const Vector3d offset = chain_.handle_position - lim.workspace_center;
  const Vector3d outside = (offset.cwiseAbs() - lim.workspace_half_size).cwiseMax(0.0);
  Vector6d wall = Vector6d::Zero();
  if ((outside.array() > 0.0).any()) {
    wall.head<3>() = -lim.workspace_stiffness * outside.cwiseProduct(offset.cwiseSign());
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

Vector6d ServoLaw::guard_passivity(const Vector6d& wrench, const Vector6d& twist,
                                   double dt) noexcept {
  // One-port passivity observer (Hannaford & Ryu) at the user's port, the handle: during the
  // last period the rendered wrench was `memory_.port_wrench` while the handle moved with `twist`,
  // so the user gave the port -w . v dt. The running total going negative means the port has
  // delivered more energy to the hand than it received (delay, loss, sampling, an unstable
  // client): the passivity controller then adds just enough damping on the handle's motion to
  // dissipate the deficit, bounded by the damping the device renders stably (model limits).
  double& energy = memory_.observed_energy;
  energy -= memory_.port_wrench.dot(twist) * dt;
  Vector6d w = wrench;
  const double speed_sq = twist.squaredNorm();
  if (config_.passivity_guard && energy < 0.0 && speed_sq > 1e-12) {
    const ArmLimits& lim = dynamics_->model().limits;
    const double alpha = -energy / (dt * speed_sq);
    const double alpha_lin = std::min(alpha, lim.max_damping_linear);
    const double alpha_ang = std::min(alpha, lim.max_damping_angular);
    w.head<3>() -= alpha_lin * twist.head<3>();
    w.tail<3>() -= alpha_ang * twist.tail<3>();
    energy +=
        (alpha_lin * twist.head<3>().squaredNorm() + alpha_ang * twist.tail<3>().squaredNorm()) *
        dt;
    ++counters_.passivity_active;
  }
  const ArmLimits& lim = dynamics_->model().limits;
  w.head<3>() = clamp_norm(w.head<3>(), lim.force_peak);
  w.tail<3>() = clamp_norm(w.tail<3>(), lim.torque_peak);
  memory_.port_wrench = w;
  memory_.wrench = w;
  return w;
}

void ServoLaw::express_for_client(const ClientFrame& frame, const Vector6d& twist,
                                  ServoOutputs& out) const noexcept {
  const Vector3d p = frame.origin + frame.rotation * (chain_.handle_position * frame.speed_factor);
  const Eigen::Quaterniond q = frame.rotation * Eigen::Quaterniond(chain_.handle_rotation);
  out.client_handle_pose = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
  out.client_handle_twist << frame.rotation * (twist.head<3>() * frame.speed_factor),
      frame.rotation * twist.tail<3>();
}

void ServoLaw::compute(const ServoInputs& in, bool degraded, ServoOutputs& out) noexcept {
  const double dt = static_cast<double>(in.dt) * 1e-9;
  const Vector6d& q = in.measures.position;
  const Vector6d& qd = in.measures.velocity;
  dynamics_->forward_kinematics(q, chain_);
  const Matrix6d jac = dynamics_->jacobian(chain_);
  const Vector6d twist = jac * qd;
  out.handle_pose = pose_of(chain_);
  out.handle_twist = twist;
  const ClientFrame frame = client_frame_of(in.client);
  express_for_client(frame, twist, out);
  out.coupling_wrench.setZero();
  out.handle_wrench.setZero();
  out.coupled = false;
  out.client_stale = in.client_valid && in.client.session_id != 0 &&
                     in.client_age > config_.stale_after;  // link state, powered or not
  out.fade = 1.0;
  out.commands.enable = in.logical.powered && in.measures.supply_on;
  if (!out.commands.enable || dt <= 0.0) {
    out.commands.torque.setZero();
    memory_.wrench.setZero();  // power-on starts from zero force, never with a step
    return;
  }

  Vector6d target = degraded ? Vector6d::Zero() : client_wrench(in, frame, chain_, twist, out);
  const ArmLimits& lim = dynamics_->model().limits;
  if (twist.head<3>().norm() > lim.max_speed) {
    // Speed safety (FD-style): drop the rendered wrench and brake the handle instead.
    target << -lim.max_damping_linear * twist.head<3>(), Vector3d::Zero();
    out.coupled = false;  // the object must not feel the brake
    ++counters_.speed_limited;
  }
  const Vector6d coupling = limit_wrench(target, in.client, dt);
  Vector6d wrench = coupling;
  if (out.coupled ||
      in.client.command_type == static_cast<std::uint32_t>(shm::CommandType::kImpedance)) {
    wrench = guard_passivity(wrench, twist, dt);
  } else {
    memory_.port_wrench.setZero();
  }
  if (out.coupled) {
    // The object feels the opposite of the coupling, in the client's frame, unscaled. Not the
    // passivity guard's damping: that brakes the handle, and mirrored onto the object it would
    // push the object along with the handle's motion.
    out.coupling_wrench << -(frame.rotation * coupling.head<3>()) / frame.force_factor,
        -(frame.rotation * coupling.tail<3>()) / frame.force_factor;
  }
  out.handle_wrench = wrench;

  Vector6d tau = dynamics_->gravity_torque(chain_) - config_.joint_damping * qd + joint_walls(q) +
                 jac.transpose() * (workspace_wall() + wrench);
  for (int i = 0; i < kJoints; ++i) {
    const double limit = dynamics_->model().joints[static_cast<std::size_t>(i)].torque_peak;
    tau(i) = std::clamp(tau(i), -limit, limit);
  }
  if (!tau.allFinite()) {
    ++counters_.non_finite_outputs;
    tau.setZero();
    out.commands.enable = false;
    memory_.wrench.setZero();
  }
  out.commands.torque = tau;
}

}  // namespace hapticctrl::rt_core
