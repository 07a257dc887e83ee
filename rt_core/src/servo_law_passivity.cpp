// Passivity: the channel's two-port controller (the core's end of the link) and the one-port
// guard on the handle (ServoLaw::guard_channel, guard_passivity; docs/control.md, H1).
#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {

using law_math::clamp_norm;
using law_math::object_twist_in_base;

void ServoLaw::guard_channel(const ServoInputs& in, const ClientFrame& frame,
                             const Vector6d& object_force, double dt, ServoOutputs& out) noexcept {
  // Two-port time-domain passivity (Ryu, Artigas, Preusche): the channel between the coupling
  // and the client's object must not give either end more energy than the other end put in.
  // Here the core's end: the coupling pushes the object image with `object_force` while the
  // image moves with the client's twist; the energy that came out of the
  // channel may not exceed what the client reports having put in (ClientSample::energy_in, which
  // arrives a link delay late). When it would, a series passivity controller lets the image
  // give way along the force (it "drifts" towards the handle), dissipating exactly the excess;
  // the drift is given back slowly while the budget allows. Energies in the client's units
  // (speed and force factors), as the client counts them.
  RenderMemory& m = memory_;
  if (!(in.client.energy_in >= 0.0) || !out.coupled) {
    return;  // a 1.0 client reports no energy: the one-port guard at the handle remains
  }
  // The channel's own flow (the client's twist, in the base frame) and the power in the
  // client's units (force / force factor, speed * speed factor). The PC's drift is not part of
  // the channel: what it takes or gives back is booked separately below (Ryu's observer).
  const Vector6d image_twist = object_twist_in_base(in.client, frame);
  Vector6d weight;
  weight << Vector3d::Constant(frame.speed_factor / frame.force_factor),
      Vector3d::Constant(1.0 / frame.force_factor);
  const Vector6d force = object_force.cwiseProduct(weight);
  const double power = force.dot(image_twist);
  (power >= 0.0 ? m.channel_in : m.channel_out) += std::abs(power) * dt;
  const double excess = m.channel_out - in.client.energy_in;
  const double force_sq = force.dot(object_force);
  Vector6d rate = Vector6d::Zero();
  if (excess > 0.0 && force_sq > 1e-12) {
    rate = object_force * (excess / (dt * force_sq));
    // Bounded like everything the device renders: the image gives way at 0.5 m/s, 5 rad/s.
    rate.head<3>() = clamp_norm(rate.head<3>(), 0.5);
    rate.tail<3>() = clamp_norm(rate.tail<3>(), 5.0);
    ++counters_.channel_pc_active;
  } else if (excess < 0.0 && m.drift.squaredNorm() > 0.0) {
    // Give the drift back, slowly (2 cm/s, 0.2 rad/s), within the budget: it costs energy.
    rate.head<3>() = -clamp_norm(m.drift.head<3>() / dt, 0.02);
    rate.tail<3>() = -clamp_norm(m.drift.tail<3>() / dt, 0.2);
    const double cost = -force.dot(rate) * dt;
    if (cost > -excess) {
      rate *= -excess / cost;
    }
  }
  // The drift never exceeds 5 cm / 0.5 rad: beyond, the PC is saturated and the one-port guard
  // at the handle is what remains.
  Vector6d drift = m.drift + rate * dt;
  drift.head<3>() = clamp_norm(drift.head<3>(), 0.05);
  drift.tail<3>() = clamp_norm(drift.tail<3>(), 0.5);
  rate = (drift - m.drift) / dt;
  m.channel_out -= force.dot(rate) * dt;  // dissipated by the PC (> 0), or given back (< 0)
  m.drift = drift;
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
  memory_.port_wrench = w;  // the rate limiter's memory keeps the wrench without this damping
  return w;
}

}  // namespace hapticctrl::rt_core
