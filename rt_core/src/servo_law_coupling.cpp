// The coupling the servo law renders (ServoLaw's coupling half): the client's frame, the
// object's image in the base frame, the client's wrench (VIRTMECH spring-damper, IMPEDANCE
// wrench) with its contact stiffening, and the engagement and fade of a session. The cycle that
// uses them is servo_law.cpp; the local surface (J2) is servo_law_surface.cpp.
#include <algorithm>
#include <cmath>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {

using law_math::object_twist_in_base;
using law_math::rotation_vector;
using law_math::to_quaternion;
using law_math::to_vector;
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
      to_seconds(std::clamp(in.client_age, Duration{0}, config_.extrapolate_max));
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
    const Surfaces surfaces = local_surfaces(in, frame, chain, twist, false, coupling, out);
    if (surfaces.count > 0 && surfaces.list[surfaces.strongest].share > 0.0) {
      // The client's push out of the strongest surface and along it (its friction) is the
      // surface's, rendered here; a push into it stays the client's ...
      const Surface& top = surfaces.list[surfaces.strongest];
      const Vector3d& n = top.normal;
      const double client_into = std::min(0.0, coupling.spring.head<3>().dot(n));
      coupling.spring.head<3>() =
          (1.0 - top.share) * coupling.spring.head<3>() + top.share * client_into * n;
      // ... and so is its push out of every other surface in force.
      for (std::size_t i = 0; i < surfaces.count; ++i) {
        const Surface& s = surfaces.list[i];
        if (i != surfaces.strongest) {
          const double out_of = std::max(0.0, coupling.spring.head<3>().dot(s.normal));
          coupling.spring.head<3>() -= s.share * out_of * s.normal;
        }
      }
      out.contact_normal = n * top.share;
      out.normal_stiffness = top.stiffness;
      out.normal_damping = top.damping;
    }
    coupling.local.head<3>() = surfaces.push * scale;
    out.contacts = surfaces.fresh;
    coupling.spring *= scale;
    return coupling;
  }
  if (c.command != ClientCommand::kVirtmech || !c.object_attached ||
      to_quaternion(c.object_pose).norm() < 0.5) {
    return coupling;  // VIRTMECH couples an attached object only (and refuses a non-rotation)
  }
  ObjectImage image = object_image(in, frame);
  const CouplingGains g = slew_gains(derive_gains(c, to_seconds(memory_.design_delay)), in.dt);
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
  const Vector6d used = stretch_in_use(stretch, twist, to_seconds(in.dt));
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
  // ... and the hand the surfaces the object touches, rendered here at their stiffness with no
  // delay in their loop, in place of the coupling's force (along the normal and along the
  // surface, where the friction proxy acts) while a surface pushes. Through the coupling
  // stiffened to half the surface's stiffness, the demo's 2000 N/m wall and fixed sphere were
  // felt at 667 N/m at 10 and 20 ms one way; so, at 2000 N/m (J2 end-to-end test, 2026-12-04).
  // The object's own motion along the normal (held by its surface) does not come back to the
  // hand: with the coupling's pull into the surface kept, an object the wall had kicked away
  // during a 0.5 s blackout came back deeper than the handle and pulled it in (the felt 5 N fell
  // to 2 N, then rose to 7.4 N in steps of 1.3 N per cycle; 10 ms one way, 2026-12-05).
  const Surfaces surfaces = local_surfaces(in, frame, chain, twist, true, coupling, out);
  coupling.spring.head<3>() *= 1.0 - surfaces.in_force;
  coupling.damper.head<3>() *= 1.0 - surfaces.in_force;
  coupling.local.head<3>() = surfaces.push * scale;
  out.coupled = true;
  return coupling;
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

double ServoLaw::fade_of(Duration silence, double share) const noexcept {
  // The force is zero by the end of the window and never falls faster than the full-scale slope
  // (the device's peaks over fade_duration: 1 N/ms): a peak force starts fading at fade_after,
  // a smaller one as late as that slope allows but over shortest_fade at least (5 N: from 30
  // ms). Fading every force from 10 ms on turned a 31 ms stall of the link's processes on this
  // VM into a 60 % drop of the weight the handle carried: it sprang 2.5 mm off its joint wall
  // and came back at 30 mm/s (H1 end-to-end test at 1 ms one way, 2026-12-02). Without the
  // shortest fade, the 0.8 N a hand pressed through a blackout went in 1 ms (0.84 N/ms, the
  // coupling bench), a click where it had faded at 0.05 N/ms.
  const Duration end = config_.fade_after + config_.fade_duration;
  if (silence >= end) {
    return 0.0;
  }
  using Seconds = std::chrono::duration<double>;
  const Seconds needed =
      std::max(share * Seconds(config_.fade_duration), Seconds(config_.shortest_fade));
  const Seconds left = end - silence;
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
  m.overspeed = speed > lim.max_speed ? m.overspeed + in.dt : Duration{0};
  out.velocity_fault = m.overspeed >= config_.overspeed_fault_after;
  out.braking = m.braking;
  const double step = std::chrono::duration<double>(in.dt) / config_.engage_duration;
  if (m.braking || fade < 1.0) {
    // Disengage (as fast as the release rate allows) and re-engage only through the ramp.
    m.engage = std::min(m.engage, m.braking ? 0.0 : fade);
  } else {
    m.engage = std::min(1.0, m.engage + step);
  }
  out.engage = m.engage;
  return m.engage;
}

}  // namespace hapticctrl::rt_core
