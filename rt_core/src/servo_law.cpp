// The servo law's cycle (ServoLaw::compute): saturation, the rate limit, the limits in force,
// the brake or hold and the motor torques. The coupling it renders (the client's wrench, the
// fade of a silent link, engagement) is in servo_law_coupling.cpp; its gains, passivity,
// contacts and walls in servo_law_gains.cpp, servo_law_passivity.cpp, servo_law_contact.cpp and
// servo_law_walls.cpp.
#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"

#include <algorithm>
#include <cmath>

#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

using law_math::clamp_norm;

/// A wrench counts as clipped (VirtuoseAPI's SATURATE alarm) when the limit took more than 1 uN
/// off it (a squared norm of 1e-12): far above the rounding of an unclipped sum.
constexpr double kClipped = 1e-12;

/// The largest share s in [0, 1] of `spring` that keeps |spring * s + damper| within `limit`,
/// with the damper clamped to `limit` first (its own share, returned in `damper_share`). The
/// damper keeps its whole share of a saturated force.
HAPTICCTRL_RT double spring_share_within(const Vector3d& spring, const Vector3d& damper,
                                         double limit, double& damper_share) noexcept {
  const double d_norm = damper.norm();
  if (d_norm >= limit) {
    damper_share = d_norm > 0.0 ? limit / d_norm : 0.0;
    return 0.0;
  }
  damper_share = 1.0;
  if ((spring + damper).norm() <= limit) {
    return 1.0;
  }
  // |s a + d| = limit: a.a s^2 + 2 a.d s + d.d - limit^2 = 0, the positive root (d inside).
  const double aa = spring.squaredNorm();
  const double ad = spring.dot(damper);
  const double disc = ad * ad - aa * (damper.squaredNorm() - limit * limit);
  return std::clamp((-ad + std::sqrt(std::max(0.0, disc))) / aa, 0.0, 1.0);
}

/// Spring and damper of a coupling, each scaled as the saturation leaves them.
struct SaturatedParts {
  Vector6d spring = Vector6d::Zero();
  Vector6d damper = Vector6d::Zero();
};

HAPTICCTRL_RT SaturatedParts saturate_parts(const Vector6d& spring, const Vector6d& damper,
                                            double force_limit, double torque_limit) noexcept {
  SaturatedParts p;
  double d = 1.0;
  double s = spring_share_within(spring.head<3>(), damper.head<3>(), force_limit, d);
  p.spring.head<3>() = spring.head<3>() * s;
  p.damper.head<3>() = damper.head<3>() * d;
  s = spring_share_within(spring.tail<3>(), damper.tail<3>(), torque_limit, d);
  p.spring.tail<3>() = spring.tail<3>() * s;
  p.damper.tail<3>() = damper.tail<3>() * d;
  return p;
}

}  // namespace

namespace {

JointLawConfig joint_config_of(const LawConfig& config) noexcept {
  JointLawConfig c = config.joint_space;
  c.wall_margin = config.wall_margin;  // set points stay out of the soft joint walls
  c.passivity_guard = config.passivity_guard;
  return c;
}

}  // namespace

ServoLaw::ServoLaw(const ArmDynamics& dynamics, const LawConfig& config) noexcept
    : dynamics_(&dynamics), config_(config), joints_(dynamics.model(), joint_config_of(config)) {}

void ServoLaw::set_limits(const ClientSample& client, ServoOutputs& out) const noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  out.force_limit = client.force_limits[0] > 0.0 ? std::min(client.force_limits[0], lim.force_peak)
                                                 : lim.force_peak;
  out.torque_limit = client.force_limits[1] > 0.0
                         ? std::min(client.force_limits[1], lim.torque_peak)
                         : lim.torque_peak;
}

Vector6d ServoLaw::rate_limit(const Vector6d& target, double rate, double dt) noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  // Never a step larger than rate * dt (torque scaled like the peaks).
  const double max_force_step = rate * dt;
  const double max_torque_step = rate * (lim.torque_peak / lim.force_peak) * dt;
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

void ServoLaw::express_for_client(const ClientFrame& frame, const Vector6d& twist,
                                  ServoOutputs& out) const noexcept {
  const Vector3d p = frame.origin + frame.rotation * (chain_.handle_position * frame.speed_factor);
  const Eigen::Quaterniond q = frame.rotation * Eigen::Quaterniond(chain_.handle_rotation);
  out.client_handle_pose = {p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w()};
  out.client_handle_twist << frame.rotation * (twist.head<3>() * frame.speed_factor),
      frame.rotation * twist.tail<3>();
}

void ServoLaw::compute(const ServoInputs& in, bool /*degraded*/, ServoOutputs& out) noexcept {
  const double dt = to_seconds(in.dt);
  const Vector6d& q = in.measures.position;
  const Vector6d& qd = in.measures.velocity;
  dynamics_->forward_kinematics(q, chain_);
  const Matrix6d jac = dynamics_->jacobian(chain_);
  const Vector6d twist = jac * qd;
  out.handle_pose = pose_of(chain_);
  out.handle_twist = twist;
  const ClientFrame frame = client_frame_of(in.client);
  express_for_client(frame, twist, out);
  follow_session(in);
  start_outputs(in, q, out);
  track_loop_delay(in);
  out.loop_delay = memory_.design_delay;
  if (!out.commands.enable || dt <= 0.0) {
    out.commands.torque.setZero();
    memory_.wrench.setZero();  // power-on starts from zero force, never with a step ...
    memory_.engage = 0.0;      // ... and re-engages the coupling through the ramp
    memory_.held = RenderMemory::HeldContact{};  // and holds no contact from before
    JointLaw::release(memory_.joints);
    return;
  }

  // A degraded cycle (the main SERVO missed) renders the same coupling from the same last
  // sample, extrapolated and faded as it ages: rendering nothing dipped a carried weight by
  // about 1 N at every VM stall (J1 review of f3c5aec).
  const Coupling coupling = client_wrench(in, frame, chain_, twist, out);
  const SaturatedParts parts =
      saturate_parts(coupling.spring, coupling.damper, out.force_limit, out.torque_limit);
  const Vector6d saturated = parts.spring + parts.damper;
  out.saturated = (saturated - (coupling.spring + coupling.damper)).squaredNorm() > kClipped;
  const bool joint_mode = in.client_valid && is_joint_command(in.client.command);
  if (out.fade > 0.0) {  // 0: no session, or its link lost
    // A joint-space command fades as fast as its largest share of a joint's peak torque allows.
    out.fade = fade_of(in.client_silence, joint_mode ? joints_.peak_share(memory_.joints.torque)
                                                     : peak_share(saturated));
  }
  // The engagement follows the fade down (and ramps back up after it): the handle gets the fade
  // once. Multiplying a faded force by it made the fade quadratic, twice as steep at its start
  // as the slope it was designed for.
  const double engage = update_engagement(in, twist, out.fade, out);
  hold_contact(in, coupling, engage);
  // The damper comes back (and the viscous hold lets go) over hold_release, the spring over the
  // whole ramp: the damping on the handle stays whole while the coupling returns (the hold let
  // go over the whole ramp before 2026-12-03; released within 50 ms with the spring, the handle
  // that came back onto a wall after a 2 s blackout shook at up to 25 N).
  const double damper_share = std::min(
      1.0,
      engage * (std::chrono::duration<double>(config_.engage_duration) / config_.hold_release));
  Vector6d target = parts.spring * engage + parts.damper * damper_share;
  const SaturatedParts object_parts = saturate_parts(coupling.object_spring, coupling.object_damper,
                                                     out.force_limit, out.torque_limit);
  // The object's side of the coupling: the same spring (re-anchored alike: on the true stretch,
  // the object got the spring the handle's motion through a 300 ms blackout had stored, 33 N at
  // once, an energy the channel made; the weighted sphere flew past the handle and pulled it up,
  // then fell back at 0.22 m/s, J1 2026-12-03), not faded (like a brake, the fade protects the
  // hand, and the object keeps its spring to the handle).
  const Vector6d object = object_parts.spring + object_parts.damper;
  if (out.coupled) {
    target = guard_channel(in, frame, target,
                           object_parts.spring * engage + object_parts.damper * damper_share,
                           coupling.stretch, dt);
  } else if (two_port_impedance(in)) {
    target = guard_impedance(in, frame, target, twist, dt);
  }
  // A surface rendered here is passive by itself (a static plane, damped): it stays out of the
  // two-port, whose guard would take back the energy it stores and returns; and out of the
  // link's fade: it fades with its own reports (contact_fresh + contact_fade). Faded with the
  // link, the wall let a 10 N push through at 0.5 m/s whenever 10 % loss at 100 ms one way
  // left 10 ms without a wrench (2026-12-03).
  target += coupling.local;
  target.head<3>() += held_contact_force(in, engage);
  out.channel_energy_in = memory_.channel_in;
  out.channel_energy_out = memory_.channel_out;
  brake_or_hold(in, out, twist, damper_share, target);
  const ArmLimits& lim = dynamics_->model().limits;
  // The one-port guard at the handle for what the two-port does not cover (a VIRTMECH object's
  // port to the hand, an IMPEDANCE client that reports no energy). Its damping goes through the
  // rate limit like every other term: after it, it stepped the force by up to 20 N.s/m x |v| in
  // one cycle (1.1 m/s after a blackout: 22 N, J1 review).
  if (out.coupled || (in.client.command == ClientCommand::kImpedance && !two_port_impedance(in))) {
    target = guard_passivity(target, twist, dt);
  }
  // The full rate only on fresh data with the coupling wholly engaged: while it comes back (the
  // ramp, the re-anchored stretch) the release rate, 1 N per ms (2 N steps after a blackout,
  // J1 2026-12-03).
  const bool fresh =
      out.fade >= 1.0 && !out.braking && out.coupled && engage >= 1.0 && !memory_.anchored;
  Vector6d wrench = rate_limit(
      target, fresh ? lim.force_rate : std::min(lim.force_rate, config_.release_rate), dt);
  wrench.head<3>() = clamp_norm(wrench.head<3>(), lim.force_peak);
  wrench.tail<3>() = clamp_norm(wrench.tail<3>(), lim.torque_peak);
  memory_.port_wrench = wrench;
  if (out.coupled) {
    // The object feels the opposite of its side of the coupling, in the client's frame,
    // unscaled: neither the brake nor the passivity guard's damping (they brake the handle;
    // mirrored onto the object they would push it along with the handle's motion), nor the fade
    // (faded, the weighted sphere lost its support for the catch-up steps the demo took after a
    // 60 ms stall of its process, fell, and bounced back at 0.16 m/s when the coupling
    // returned, bench/gravity_rest.sh, 2026-12-02). A protocol 1.3 client closes this side
    // itself while a contact is in force (docs/control.md).
    out.object_wrench << -(frame.rotation * object.head<3>()) / frame.force_factor,
        -(frame.rotation * object.tail<3>()) / frame.force_factor;
  }
  out.rendered_wrench = wrench;
  Vector6d joint_command = Vector6d::Zero();
  if (joint_mode) {  // the full rate on fresh data, wholly engaged, as the handle's coupling
    const bool fresh_joints = out.fade >= 1.0 && !out.braking && engage >= 1.0;
    const double rate =
        fresh_joints ? lim.force_rate : std::min(lim.force_rate, config_.release_rate);
    joint_command = joint_space(in, engage, rate / lim.force_peak, dt, out);
  } else {
    JointLaw::release(memory_.joints);
  }

  // In joint space the joints' ranges bound the arm, not the handle's workspace box: its wall
  // held a joint the client drove toward its limit away from it.
  const Vector6d box = joint_mode ? Vector6d::Zero() : workspace_wall(twist.head<3>());
  command_torques(in, jac.transpose() * (box + wrench), joint_command, out);
}

void ServoLaw::start_outputs(const ServoInputs& in, const Vector6d& q,
                             ServoOutputs& out) const noexcept {
  out.object_wrench.setZero();
  out.rendered_wrench.setZero();
  out.coupled = false;
  out.client_stale = in.client_valid && in.client.session_id != 0 &&
                     in.client_silence > config_.stale_after;  // link state, powered or not
  out.fade = 1.0;
  out.commands.enable = in.logical.powered && in.measures.supply_on;
  out.engage = 0.0;
  out.braking = false;
  out.velocity_fault = false;
  out.saturated = false;
  out.joint_bounds = joint_bounds(q);
  out.gains = CouplingGains{};
  out.contact_normal.setZero();
  out.normal_stiffness = 0.0;
  out.normal_damping = 0.0;
  out.contacts = 0;
  out.surface_point.setZero();
  out.surface_normal.setZero();
  out.surface_depth = 0.0;
  out.surface_force = 0.0;
  out.surface_hidden = 0.0;
  out.contact_age.reset();
  out.surface_withheld = memory_.surface_withheld;
  set_limits(in.client, out);
}

void ServoLaw::brake_or_hold(const ServoInputs& in, const ServoOutputs& out, const Vector6d& twist,
                             double damper_share, Vector6d& target) noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  if (out.braking) {
    // Speed safety: a damped brake on the handle while the coupling is disengaged; the object
    // still feels its spring to the (braked) handle, so it stays with it, and the handle gets
    // the coupling back through the engagement ramp.
    target.head<3>() -= lim.max_damping_linear * twist.head<3>();
    ++counters_.speed_limited;
  } else if (in.client_valid && in.client.session_id != 0) {
    // A session whose coupling is (partly) disengaged (link lost, ramping back) holds the handle
    // in a viscous field instead of letting it drift: released from the wall that carried a
    // weighted object, the handle coasted 3-5 cm during a 300 ms blackout and fell back at
    // 0.44 m/s when the coupling returned (H1).
    const double hold = 1.0 - damper_share;
    target.head<3>() -= hold * lim.max_damping_linear * twist.head<3>();
    target.tail<3>() -= hold * lim.max_damping_angular * twist.tail<3>();
    // As the hold lets go, the returning stretch keeps the whole damping along it.
    target += damper_share * restretch_damping(twist);
  }
}

void ServoLaw::command_torques(const ServoInputs& in, const Vector6d& handle_torque,
                               const Vector6d& joint_command, ServoOutputs& out) noexcept {
  const Vector6d& q = in.measures.position;
  Vector6d tau = dynamics_->gravity_torque(chain_) - config_.joint_damping * in.measures.velocity +
                 joint_walls(q) + handle_torque + joint_command;
  for (int i = 0; i < kJoints; ++i) {
    const double limit = dynamics_->model().joints[static_cast<std::size_t>(i)].torque_peak;
    tau(i) = std::clamp(tau(i), -limit, limit);
  }
  if (!tau.allFinite()) {
    ++counters_.non_finite_outputs;
    tau.setZero();
    out.commands.enable = false;
    memory_.wrench.setZero();
    memory_.engage = 0.0;
  }
  out.commands.torque = tau;
}

}  // namespace hapticctrl::rt_core
