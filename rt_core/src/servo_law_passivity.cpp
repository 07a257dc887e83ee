// Passivity: the core's end of the channel's two-port (ServoLaw::guard_channel for a VIRTMECH
// object, guard_impedance for an IMPEDANCE client that reports its energy) and the one-port
// guard on the handle (guard_passivity); docs/control.md, H1 and J1.
#include <algorithm>
#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {

using law_math::object_twist_in_base;

namespace {

/// An excess below this is rounding, not energy the channel made (J).
constexpr double kNegligible = 1e-9;

/// Converts base-frame forces and twists into the client's units (force / force factor, speed *
/// speed factor), as it counts its energy.
HAPTICCTRL_RT Vector6d client_units(const ClientFrame& frame) noexcept {
  Vector6d weight;
  weight << Vector3d::Constant(frame.speed_factor / frame.force_factor),
      Vector3d::Constant(1.0 / frame.force_factor);
  return weight;
}

/// Removes from `force` the share that delivers power along `flow`, as much as dissipates
/// `energy` in one period (power = (force . weight) . flow): the force, then the torque, each at
/// most down to none along its own motion (never turned against it). Returns the energy taken.
HAPTICCTRL_RT double cut_output(Vector6d& force, const Vector6d& weight, const Vector6d& flow,
                                double energy, double dt) noexcept {
  double left = energy / dt;
  for (int from = 0; from < 6 && left > 0.0; from += 3) {
    const Vector3d f = force.segment<3>(from) * weight(from);
    const Vector3d v = flow.segment<3>(from);
    const double power = f.dot(v);
    if (power > 0.0 && v.squaredNorm() > 1e-18) {
      const double taken = std::min(power, left);
      force.segment<3>(from) -= v * (taken / (v.squaredNorm() * weight(from)));
      left -= taken;
    }
  }
  return std::max(0.0, energy - left * dt);
}

}  // namespace

void TravelHistory::advance(TimePoint now, const Vector6d& twist, double dt) noexcept {
  now_travel += twist * dt;
  const std::int64_t slot = now.time_since_epoch() / kSlot;
  if (newest >= 0 && slot < newest) {
    return;  // a clock that went back: keep what was kept
  }
  if (first < 0) {
    first = slot;
  }
  // Slots skipped since the last note keep the last known travel.
  const Vector6d last =
      newest >= 0 ? travel[static_cast<std::size_t>(newest) % kSlots] : now_travel;
  for (std::int64_t s = std::max(newest + 1, slot - static_cast<std::int64_t>(kSlots) + 1);
       s < slot; ++s) {
    travel[static_cast<std::size_t>(s) % kSlots] = last;
  }
  travel[static_cast<std::size_t>(slot) % kSlots] = now_travel;
  newest = slot;
}

Vector6d TravelHistory::since(TimePoint now, Duration ago) const noexcept {
  if (newest < 0) {
    return Vector6d::Zero();
  }
  const std::int64_t oldest = std::max(first, newest - static_cast<std::int64_t>(kSlots) + 1);
  // A slot holds the travel at its end: the travel since the end of the slot before the one
  // `ago` falls in covers `ago` at least (up to one slot more).
  const Duration at = (now - std::max(Duration{0}, ago)).time_since_epoch();
  const std::int64_t wanted =
      (at >= Duration{0} ? at / kSlot : (at - kSlot + Duration{1}) / kSlot) - 1;
  if (wanted < first) {
    return now_travel;  // all of it: the session's first slot is younger than that
  }
  const std::int64_t slot = std::clamp<std::int64_t>(wanted, oldest, newest);
  return now_travel - travel[static_cast<std::size_t>(slot) % kSlots];
}

bool ServoLaw::two_port_impedance(const ServoInputs& in) noexcept {
  return in.client_valid && in.client.command == ClientCommand::kImpedance &&
         in.client.local_coupling && in.client.energy_in >= 0.0;
}

double ServoLaw::book_channel_power(double power, double budget, double dt) noexcept {
  RenderMemory& m = memory_;
  (power >= 0.0 ? m.channel_in : m.channel_out) += std::abs(power) * dt;
  return m.channel_out - budget;
}

Vector6d ServoLaw::guard_channel(const ServoInputs& in, const ClientFrame& frame,
                                 const Vector6d& coupling, const Vector6d& to_object,
                                 const Vector6d& stretch, double dt) noexcept {
  // Two-port time-domain passivity (Ryu, Artigas, Preusche): the channel between the coupling
  // and the client's object must not give either end more energy than the other end put in.
  // Here the core's end: the coupling (the force it puts on the handle; the object image gets
  // its opposite) pushes the image while it moves with the client's twist; the energy that came out
  // of the channel may not exceed what the client reports having put in (ClientSample::energy_in,
  // which arrives a link delay late). When it would, a series passivity controller lets the image
  // give way along the force (it drifts towards the handle) and dissipates the whole excess: as far
  // as relaxing the spring in one period, and what that cannot take (the damper's share) is cut
  // from the force along the image's motion. Nothing bounds it but that: bounded (0.5 m/s, 5 cm
  // until 2026-12-03), it let the balance break in contact (the core's end gave 7.1-25.8 J for the
  // client's 3.9-7.6 J at 10-20 ms, J1 review). The drift is given back slowly while the budget
  // allows. Energies in the client's units, as the client counts them. The effort that crosses
  // the channel is the coupling the object gets (`to_object`, as engaged as the handle's): where
  // the handle renders a reported surface instead, the handle's differs along its normal, and
  // booked on the handle's the client's end gave 2-3 mJ more than the core's end booked (J2).
  RenderMemory& m = memory_;
  if (!(in.client.energy_in >= 0.0)) {
    return coupling;  // a 1.0 client reports no energy: the one-port guard at the handle
  }
  const Vector6d flow = object_twist_in_base(in.client, frame);
  const Vector6d weight = client_units(frame);
  const Vector6d on_image = -to_object;  // what the coupling does to the image
  const double excess =
      book_channel_power(on_image.cwiseProduct(weight).dot(flow), in.client.energy_in, dt);
  const double force_sq = on_image.cwiseProduct(weight).dot(on_image);
  Vector6d rate = Vector6d::Zero();
  Vector6d force = coupling;
  if (excess > kNegligible) {
    ++counters_.channel_pc_active;
    if (force_sq > 1e-12) {
      rate = on_image * (excess / (dt * force_sq));
      // No further than relaxing the spring in one period: beyond, the image would pull the
      // other way, and that is no longer giving way.
      const double lin = rate.head<3>().norm() * dt;
      const double ang = rate.tail<3>().norm() * dt;
      if (lin > stretch.head<3>().norm()) {
        rate.head<3>() *= stretch.head<3>().norm() / lin;
      }
      if (ang > stretch.tail<3>().norm()) {
        rate.tail<3>() *= stretch.tail<3>().norm() / ang;
      }
    }
    const double drifted = on_image.cwiseProduct(weight).dot(rate) * dt;
    const double cut = cut_output(force, weight, flow, excess - drifted, dt);
    if (cut > 0.0) {
      ++counters_.channel_force_cut;
    }
    m.channel_out -= cut;
  } else if (m.drift.squaredNorm() > 0.0) {
    // Give the drift back, slowly (2 cm/s, 0.2 rad/s), within the budget: it costs energy.
    rate.head<3>() = -law_math::clamp_norm(m.drift.head<3>() / dt, 0.02);
    rate.tail<3>() = -law_math::clamp_norm(m.drift.tail<3>() / dt, 0.2);
    // Only what the budget has left: at it or above (by less than kNegligible), nothing. Scaled
    // by -excess / cost there, the step was infinite for a force of zero on the image and
    // reversed and amplified otherwise (NaN energies and image, 2026-12-04).
    const double cost = -on_image.cwiseProduct(weight).dot(rate) * dt;
    const double left = -excess;
    if (cost > left) {
      rate *= left > 0.0 ? left / cost : 0.0;
    }
  }
  m.channel_out -= on_image.cwiseProduct(weight).dot(rate) * dt;  // dissipated (> 0) or given back
  m.drift += rate * dt;
  return force;
}

Vector6d ServoLaw::guard_impedance(const ServoInputs& in, const ClientFrame& frame,
                                   const Vector6d& handle_force, const Vector6d& twist,
                                   double dt) noexcept {
  // The IMPEDANCE client's two-port (protocol 1.3, J1): its wrench enters the channel at its
  // end against the handle's motion as the answers showed it, and comes out here against the
  // handle's motion now. The client reports the energy its wrench put in (CONTROL_WRENCH_TIMED);
  // what the rendered wrench gives the handle may not exceed it. When it would, a damper on the
  // handle (the device's stable damping at most) and then a cut of the wrench's share along
  // the motion dissipate the whole excess. A commanded force that does work is paid for by the
  // client's report, so in free space the command is rendered whole (the one-port guard took
  // 11 % of 6 N and 44 % of 1 N, J1 review), and a client wall that the delay makes active is
  // damped at this end.
  RenderMemory& m = memory_;
  const Vector6d weight = client_units(frame);
  // The channel gives the handle power handle_force . twist: that is its output here. The
  // client's report covers the handle's motion up to a loop ago (it saw it in an answer, then
  // its frame came back); for the last loop the budget adds what the client will bill for it at
  // its current wrench. Compared with the report alone, a commanded force lost the work of the
  // last loop (1 N on an unheld handle: a share of about loop / time since the push); compared
  // with the output of a loop ago, a wall's bounce got a loop of energy through at every
  // bounce (a 2000 N/m wall at 10 ms one way: a limit cycle with 35 N peaks, J1 2026-12-03).
  m.travel.advance(in.now, twist, dt);
  const Duration loop = m.loop_delay > Duration{0} ? m.loop_delay : config_.assumed_loop_delay;
  const double credit = handle_force.cwiseProduct(weight).dot(m.travel.since(in.now, loop));
  const double excess = book_channel_power(-handle_force.cwiseProduct(weight).dot(twist),
                                           in.client.energy_in + std::max(0.0, credit), dt);
  Vector6d force = handle_force;
  if (excess > kNegligible && twist.squaredNorm() > 1e-12) {
    ++counters_.channel_pc_active;
    const ArmLimits& lim = dynamics_->model().limits;
    const double lin_sq = twist.head<3>().squaredNorm() * weight(0);
    const double ang_sq = twist.tail<3>().squaredNorm() * weight(3);
    const double alpha = excess / (dt * (lin_sq + ang_sq));
    const double alpha_lin = std::min(alpha, lim.max_damping_linear);
    const double alpha_ang = std::min(alpha, lim.max_damping_angular);
    force.head<3>() -= alpha_lin * twist.head<3>();
    force.tail<3>() -= alpha_ang * twist.tail<3>();
    const double damped = (alpha_lin * lin_sq + alpha_ang * ang_sq) * dt;
    const double cut = cut_output(force, weight, twist, excess - damped, dt);
    if (cut > 0.0) {
      ++counters_.channel_force_cut;
    }
    m.channel_out -= damped + cut;
  }
  return force;
}

Vector6d ServoLaw::guard_passivity(const Vector6d& wrench, const Vector6d& twist,
                                   double dt) noexcept {
  // One-port passivity observer (Hannaford & Ryu) at the user's port, the handle: during the
  // last period the rendered wrench was `memory_.port_wrench` while the handle moved with `twist`,
  // so the user gave the port -w . v dt. The running total going negative means the port has
  // delivered more energy to the hand than it received (delay, loss, sampling, an unstable
  // client): the passivity controller then adds just enough damping on the handle's motion to
  // dissipate the deficit, bounded by the damping the device renders stably (model limits).
  // The rate limit comes after it (compute()).
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
  return w;
}

}  // namespace hapticctrl::rt_core
