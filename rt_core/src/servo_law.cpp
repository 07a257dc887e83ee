// The servo law's cycle (ServoLaw::compute) and the coupling it renders: the client's wrench,
// the fade of a silent link, engagement, saturation and the rate limit. Its gains, passivity,
// contacts and walls live in servo_law_gains.cpp, servo_law_passivity.cpp,
// servo_law_contact.cpp and servo_law_walls.cpp.
#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"

#include <algorithm>
#include <cmath>

#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

using law_math::clamp_norm;
using law_math::object_twist_in_base;
using law_math::rotation_vector;
using law_math::to_quaternion;
using law_math::to_vector;

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

ClientFrame client_frame_of(const ClientSample& c) noexcept {
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

ServoLaw::ObjectImage ServoLaw::object_image(const ServoInputs& in,
                                             const ClientFrame& frame) const noexcept {
  const ClientSample& c = in.client;
  // Client poses are in its environment frame; base_frame is our base in that frame. Positions
  // are de-scaled by the speed factor.
  const Matrix3d base_r = frame.rotation.toRotationMatrix();
  ObjectImage image;
  const Vector3d object_p_env(c.object_pose[0], c.object_pose[1], c.object_pose[2]);
  image.position = base_r.transpose() * (object_p_env - frame.origin) / frame.speed_factor;
  image.rotation =
      base_r.transpose() * to_quaternion(c.object_pose).normalized().toRotationMatrix();
  image.twist = object_twist_in_base(c, frame);
  // Best estimate of where the object is now: extrapolate over the sample's true age (bounded).
  const double horizon =
      static_cast<double>(std::clamp<TimeNs>(in.client_age, 0, config_.extrapolate_max)) * 1e-9;
  const Vector3d w = image.twist.tail<3>();
  image.ahead = image.twist.head<3>() * horizon;
  image.position += image.ahead + memory_.drift.head<3>();
  if (w.norm() * horizon > 1e-12) {
    image.rotation = Eigen::AngleAxisd(w.norm() * horizon, w.normalized()) * image.rotation;
  }
  const Vector3d turned = memory_.drift.tail<3>();  // the channel PC's share (guard_channel)
  if (turned.norm() > 1e-12) {
    image.rotation = Eigen::AngleAxisd(turned.norm(), turned.normalized()) * image.rotation;
  }
  return image;
}

ServoLaw::Coupling ServoLaw::client_wrench(const ServoInputs& in, const ClientFrame& frame,
                                           const ChainState& chain, const Vector6d& twist,
                                           ServoOutputs& out) noexcept {
  const ClientSample& c = in.client;
  Coupling coupling;
  if (!in.client_valid || c.session_id == 0) {
    out.fade = 0.0;
    return coupling;  // no session: released at release_rate
  }
  // Freshness is the time since a new sample arrived (a long but live link is fresh). Past the
  // fade window the link is lost and nothing is rendered; within it, fade_of() fades the force.
  if (in.client_silence >= config_.fade_after + config_.fade_duration) {
    out.fade = 0.0;
    return coupling;
  }
  const Matrix3d base_r = frame.rotation.toRotationMatrix();
  const double scale = frame.force_factor;

  if (c.command == ClientCommand::kImpedance) {
    const Vector6d env = to_vector(c.impedance_wrench);
    coupling.spring << base_r.transpose() * env.head<3>(), base_r.transpose() * env.tail<3>();
    // Protocol 1.3: a surface the client reports is rendered here, at the servo rate, in place
    // of the client's own push out of it and its friction (which come a loop late: a 2000 N/m
    // wall the client rendered moved at 31-689 mm/s from 1 ms one way and gave way from 5 ms,
    // J1 2026-12-03).
    const Surface surface = local_surface(in, frame, chain, twist, false, coupling, out);
    if (surface.share > 0.0) {
      // The client's push out of the surface and along it (its friction) is the surface's,
      // rendered here; a push into it stays the client's.
      const Vector3d& n = surface.normal;
      const double client_into = std::min(0.0, coupling.spring.head<3>().dot(n));
      coupling.spring.head<3>() =
          (1.0 - surface.share) * coupling.spring.head<3>() + surface.share * client_into * n;
      coupling.local.head<3>() = (surface.force * n + surface.friction) * scale;
      out.contact_normal = n * surface.share;
      out.normal_stiffness = surface.stiffness;
      out.normal_damping = surface.damping;
    }
    out.contacts = surface.fresh;
    coupling.spring *= scale;
    return coupling;
  }
  if (c.command != ClientCommand::kVirtmech || !c.object_attached ||
      to_quaternion(c.object_pose).norm() < 0.5) {
    return coupling;  // VIRTMECH couples an attached object only (and refuses a non-rotation)
  }
  ObjectImage image = object_image(in, frame);
  const CouplingGains g =
      slew_gains(derive_gains(c, static_cast<double>(memory_.design_delay) * 1e-9), in.dt);
  out.gains = g;
  // Along a contact the object is held by its surface: the coupling may be as stiff as the
  // device allows there (unilateral: only while it pushes the object into the surface), and the
  // object is not extrapolated along it: held, its velocity there is the jitter of its contact
  // (+-3 cm/s on a 5000 N/m wall), which 100 ms of extrapolation turned into 3 N of chatter.
  const Stiffening stiff =
      contact_stiffening(in, frame, image.position - image.ahead - memory_.drift.head<3>(), g);
  out.contacts = stiff.fresh;
  image.position -= stiff.share * image.ahead.dot(stiff.normal) * stiff.normal;
  Vector6d stretch;
  stretch << image.position - chain.handle_position,
      rotation_vector(image.rotation * chain.handle_rotation.transpose());
  const Vector6d used = stretch_in_use(stretch, twist, static_cast<double>(in.dt) * 1e-9);
  coupling.stretch = used;
  Vector6d relative = image.twist - twist;
  coupling.spring << g.k_linear * used.head<3>(), g.k_angular * used.tail<3>();
  coupling.damper << g.b_linear * relative.head<3>(), g.b_angular * relative.tail<3>();
  Vector3d object_pressed = Vector3d::Zero();  // what the object's side adds along its contact
  if (stiff.share > 0.0) {
    const Vector3d& n = stiff.normal;
    const double depth = used.head<3>().dot(n);  // > 0: the handle presses into the surface
    // The damper comes in over the first 0.5 mm, so that touching is not a step.
    const double engaged = std::clamp(depth / 5e-4, 0.0, 1.0);
    coupling.damper.head<3>() += engaged * stiff.damping * relative.head<3>().dot(n) * n;
    // The object's side: (k + object_stiffness) on the handle's depth in the surface, in the
    // contact's share, in place of k on the stretch and the handle's stiffening.
    const double held = depth + stiff.penetration;
    object_pressed = -stiff.stiffness * std::max(0.0, depth) * n;
    if (held > 0.0) {
      object_pressed +=
          (stiff.object_stiffness * held + stiff.share * g.k_linear * stiff.penetration) * n;
    }
    coupling.spring.head<3>() += stiff.stiffness * std::max(0.0, depth) * n;
    out.contact_normal = n * stiff.share;
    out.normal_stiffness = stiff.object_stiffness;
    out.normal_damping = stiff.damping;
  }
  // The object gets the coupling stiffened along its contact to the surface's stiffness, on the
  // handle's depth in the surface (the stretch plus the object's own penetration): at rest it is
  // pressed into its surface with the force the hand feels there (J2: with half the stiffness,
  // on the stretch alone, the demo's sphere pushed at 5 N onto the fixed one held 2.3 N). Its
  // 1.3 client closes this side itself along the contact (local_coupling.cpp) ...
  coupling.object_spring = coupling.spring;
  coupling.object_spring.head<3>() += object_pressed;
  coupling.object_spring *= scale;
  coupling.object_damper = coupling.damper * scale;
  coupling.spring *= scale;
  coupling.damper *= scale;
  // ... and the hand the surface the object touches, rendered here at the surface's stiffness
  // with no delay in its loop, in place of the coupling's force (along the normal and along the
  // surface, where the friction proxy acts) while the surface pushes. Through the coupling
  // stiffened to half the surface's stiffness, the demo's 2000 N/m wall and fixed sphere were
  // felt at 667 N/m at 10 and 20 ms one way; so, at 2000 N/m (J2 end-to-end test, 2026-12-04).
  // The object's own motion along the normal (held by its surface) does not come back to the
  // hand: with the coupling's pull into the surface kept, an object the wall had kicked away
  // during a 0.5 s blackout came back deeper than the handle and pulled it in (the felt 5 N fell
  // to 2 N, then rose to 7.4 N in steps of 1.3 N per cycle; 10 ms one way, 2026-12-05).
  const Surface surface = local_surface(in, frame, chain, twist, true, coupling, out);
  if (surface.share > 0.0) {
    const Vector3d& n = surface.normal;
    const double in_force = std::clamp(surface.force / (surface.stiffness * 5e-4), 0.0, 1.0);
    coupling.spring.head<3>() *= 1.0 - in_force;
    coupling.damper.head<3>() *= 1.0 - in_force;
    coupling.local.head<3>() = (surface.force * n + surface.friction) * scale;
  }
  out.coupled = true;
  return coupling;
}

ServoLaw::Surface ServoLaw::local_surface(const ServoInputs& in, const ClientFrame& frame,
                                          const ChainState& chain, const Vector6d& twist,
                                          bool on_object, Coupling& coupling,
                                          ServoOutputs& out) noexcept {
  Surface surface = reported_surface(in, frame, chain, on_object);
  render_surface(surface, chain, twist, static_cast<double>(in.dt) * 1e-9);
  const RenderMemory& m = memory_;
  out.surface_withheld = m.surface_withheld;
  out.contact_age = surface.age;
  if (m.on_surface) {
    out.surface_normal = surface.normal;
    out.surface_point = m.surface_point;
    out.surface_depth = (m.surface_point - chain.handle_position).dot(surface.normal);
    out.surface_force = surface.force * frame.force_factor;
    out.surface_hidden = m.surface_hidden;
  }
  if (surface.weight > 0.0) {
    coupling.contact_in_force = true;
    coupling.contact_whole = surface.weight >= 1.0;
    coupling.contact_local = true;
    coupling.contact = {surface.normal, surface.point - memory_.surface_hidden * surface.normal,
                        0.0, surface.stiffness * frame.force_factor};
  }
  return surface;
}

void ServoLaw::follow_session(const ServoInputs& in) noexcept {
  RenderMemory& m = memory_;
  const std::uint64_t session = in.client_valid ? in.client.session_id : 0;
  if (session != m.session_id) {
    m.session_id = session;
    m.engage = 0.0;      // a new session (or none) starts from zero ...
    m.channel_in = 0.0;  // ... and so does its channel's energy account
    m.channel_out = 0.0;
    m.travel = TravelHistory{};
    m.drift.setZero();
    m.gains = CouplingGains{};  // its gains start at their design
    m.held = RenderMemory::HeldContact{};
    m.surface_withheld = 0.0;
  }
}

double ServoLaw::peak_share(const Vector6d& wrench) const noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  return std::max(wrench.head<3>().norm() / lim.force_peak,
                  wrench.tail<3>().norm() / lim.torque_peak);
}

double ServoLaw::fade_of(TimeNs silence, double share) const noexcept {
  // The force is zero by the end of the window and never falls faster than the full-scale slope
  // (the device's peaks over fade_duration: 1 N/ms): a peak force starts fading at fade_after,
  // a smaller one as late as that slope allows but over shortest_fade at least (5 N: from 30
  // ms). Fading every force from 10 ms on turned a 31 ms stall of the link's processes on this
  // VM into a 60 % drop of the weight the handle carried: it sprang 2.5 mm off its joint wall
  // and came back at 30 mm/s (H1 end-to-end test at 1 ms one way, 2026-12-02). Without the
  // shortest fade, the 0.8 N a hand pressed through a blackout went in 1 ms (0.84 N/ms, the
  // coupling bench), a click where it had faded at 0.05 N/ms.
  const TimeNs end = config_.fade_after + config_.fade_duration;
  if (silence >= end) {
    return 0.0;
  }
  const double needed = std::max(share * static_cast<double>(config_.fade_duration),
                                 static_cast<double>(config_.shortest_fade));
  const auto left = static_cast<double>(end - silence);
  return needed <= left ? 1.0 : left / needed;
}

double ServoLaw::update_engagement(const ServoInputs& in, const Vector6d& twist, double fade,
                                   ServoOutputs& out) noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  const double speed = twist.head<3>().norm();
  RenderMemory& m = memory_;
  // The brake comes on above max_speed and lets go below brake_release_ratio of it.
  m.braking =
      speed > lim.max_speed || (m.braking && speed > config_.brake_release_ratio * lim.max_speed);
  m.overspeed = speed > lim.max_speed ? m.overspeed + in.dt : 0;
  out.velocity_fault = m.overspeed >= config_.overspeed_fault_after;
  out.braking = m.braking;
  const double step = static_cast<double>(in.dt) / static_cast<double>(config_.engage_duration);
  if (m.braking || fade < 1.0) {
    // Disengage (as fast as the release rate allows) and re-engage only through the ramp.
    m.engage = std::min(m.engage, m.braking ? 0.0 : fade);
  } else {
    m.engage = std::min(1.0, m.engage + step);
  }
  out.engage = m.engage;
  return m.engage;
}

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
  const double damper_share = std::min(1.0, engage * static_cast<double>(config_.engage_duration) /
                                                static_cast<double>(config_.hold_release));
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
  out.contact_age = -1;
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
