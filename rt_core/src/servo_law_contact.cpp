// The coupling where the client's object touches something, and after the coupling let go:
// the stiffening along a contact the client reports (ServoLaw::contact_stiffening) and the
// re-anchored spring after a full disengagement (ServoLaw::stretch_in_use); docs/control.md, J1.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

using law_math::clamp_norm;

/// A contact counts as touching from this gap down (its stiffening comes in over it): the
/// object image arrives at the surface at the speed of the hand, and a stiffening switched on in
/// one cycle would step the force by k x its first penetration.
constexpr double kTouchBand = 1e-3;  // m

/// A handle creeping out of a soft workspace wall as a force comes back moves at up to this; a
/// faster motion away along a hidden stretch or depth is the handle being carried (m/s).
constexpr double kCreepSpeed = 0.02;

/// The most dissipated energy a surface keeps to give a hidden depth back with (J): a fifth of
/// J2's 1 mJ bound on what a model update may put out. A hand that moves on the surface pays as
/// it goes (sliding 1 cm at 5 N with mu 0.6 dissipates 30 mJ).
constexpr double kSurfaceBudgetBound = 2e-4;

/// How fast a hidden stretch or depth comes back: `speed` less the handle's own speed away
/// along it (`leaving`, m/s) beyond the creep, never below zero.
HAPTICCTRL_RT double return_speed(double speed, double leaving) noexcept {
  return std::max(0.0, speed - std::max(0.0, leaving - kCreepSpeed));
}

/// Share of the contact a slot still has after `silence` without a refresh: 1 while fresh,
/// falling linearly to 0 over the fade (a contact that stops coming fades as the link does).
HAPTICCTRL_RT double contact_weight(TimeNs silence, const LawConfig& config) noexcept {
  if (silence <= config.contact_fresh) {
    return 1.0;
  }
  const auto left = static_cast<double>(config.contact_fresh + config.contact_fade - silence);
  return std::clamp(left / static_cast<double>(config.contact_fade), 0.0, 1.0);
}

}  // namespace

ServoLaw::Stiffening ServoLaw::contact_stiffening(const ServoInputs& in, const ClientFrame& frame,
                                                  const Vector3d& reported,
                                                  const CouplingGains& g) const noexcept {
  // Held by a surface of stiffness K, the object moves little whatever the coupling does, so the
  // loop through it (the object's surface, the spring, the delay, the handle) keeps a gain below
  // 1 at any delay as long as the coupling along the surface's normal stays well below K: there
  // the coupling may be as stiff as contact_share * K and the device allow, whatever the delay
  // (small gain; the free-mass bound of derive_gains() is about the directions the object is
  // free in). One normal, the stiffest contact's: a client that closes its object's side mirrors
  // it (protocol 1.3).
  const ArmLimits& lim = dynamics_->model().limits;
  const ClientSample& c = in.client;
  const Matrix3d to_base = frame.rotation.conjugate().toRotationMatrix();
  Stiffening best;
  for (std::size_t i = 0; i < std::min<std::size_t>(c.contact_count, c.contacts.size()); ++i) {
    const ClientContact& contact = c.contacts[i];
    if (!(contact.stiffness > 0.0)) {
      continue;
    }
    const double weight = contact_weight(in.now - contact.received_ns, config_);
    if (weight <= 0.0) {
      continue;
    }
    ++best.fresh;
    const Vector3d normal =
        (to_base * Vector3d(contact.normal[0], contact.normal[1], contact.normal[2])).normalized();
    // The gap now: as reported, less how far the object's reported position moved towards the
    // surface since (neither the extrapolation over the sample's age nor the channel PC's drift
    // is a motion of the object: with them the contact flickered in and out of its band).
    const Vector3d at_report =
        to_base *
        (Vector3d(contact.object_pose[0], contact.object_pose[1], contact.object_pose[2]) -
         frame.origin) /
        frame.speed_factor;
    const double gap = contact.distance / frame.speed_factor - (reported - at_report).dot(normal);
    const double touching = std::clamp((kTouchBand - gap) / kTouchBand, 0.0, 1.0);
    // The surface's stiffness in the coupling's units (the client's force per base metre).
    const double surface = contact.stiffness * frame.speed_factor;
    const double stiffness =
        weight * touching *
        std::max(0.0,
                 std::min(lim.max_stiffness_linear, config_.contact_share * surface) - g.k_linear);
    if (weight * touching > best.share ||
        (weight * touching == best.share && stiffness > best.stiffness)) {
      best.normal = normal;
      best.share = weight * touching;
      best.weight = weight;
      best.stiffness = stiffness;
      best.object_stiffness =
          weight * touching *
          std::max(0.0, std::min(lim.max_stiffness_linear, surface) - g.k_linear);
      best.penetration = std::max(0.0, -gap);
      best.damping = weight * touching * std::max(0.0, lim.max_damping_linear - g.b_linear);
    }
  }
  return best;
}

Vector6d ServoLaw::stretch_in_use(const Vector6d& stretch, const Vector6d& twist,
                                  double dt) noexcept {
  // After a full disengagement (the link lost, a brake, a new session, power-on) the handle may
  // be far from where the coupling would hold it: a hand that pushed 5 N into a 3000 N/m wall
  // through a 2 s blackout went 30 cm through it, and the returning spring snapped it back at
  // up to 1.1 m/s with 10 N steps (J1 review of f3c5aec). So the spring restarts where the
  // handle is: the stretch it had then is hidden (memory_.stretch) and comes back at
  // restretch_speed at most, while every new motion of the handle or the object stretches the
  // spring at once. The hidden part never exceeds the true stretch along its own direction: when
  // the object comes to the handle or the hand goes back, it shrinks with it (the spring never
  // pulls the other way). (Letting it grow back up to a decaying envelope when they part again
  // hid the object's motion along it entirely: the weighted sphere's handle fell back at up to
  // 0.48 m/s after a blackout, 2026-12-03.)
  RenderMemory& m = memory_;
  if (m.engage <= 0.0) {
    if (!m.anchored) {
      ++counters_.reanchored;
    }
    m.anchored = true;  // fully disengaged: the whole stretch is hidden, the spring relaxed
    m.stretch = stretch;
    // ... but for what a held contact renders (held_contact_force): the hand still presses on it
    // and the spring takes it over as it re-engages (hidden, the 8 N push on a held contact
    // fell to 3.1 N as the coupling came back, 2026-12-04).
    const RenderMemory::HeldContact& h = m.held;
    if (h.coupling_stiffness + h.contact_stiffness > 0.0) {
      const double along = stretch.head<3>().dot(h.normal);
      const double held = h.depth_at(chain_.handle_position);
      m.stretch.head<3>() -= std::clamp(held, 0.0, std::max(0.0, along)) * h.normal;
    }
    return Vector6d::Zero();
  }
  if (!m.anchored) {
    return stretch;
  }
  // The hidden stretch comes back at restretch_speed less the handle's own speed toward the
  // object along it: on a handle held still the spring regains its push at once, and it never
  // drives a moving handle out after the object faster than it comes back. (At a fixed 8 cm/s
  // a hand that had pushed 5 N through a faded 3000 N/m wall for 0.1-0.3 s was carried back out
  // at 0.11-0.12 m/s; at a fixed 5 cm/s at 0.07-0.09, but a hand resting 31 cm deep after 2 s
  // felt its push back only after 330 ms; J1, 2026-12-03.)
  const auto release = [&stretch, &twist, dt](Vector6d& hidden, int from, double speed) {
    Vector3d h = hidden.segment<3>(from);
    const double hidden_length = h.norm();
    const double following =
        hidden_length > 0.0 ? std::max(0.0, twist.segment<3>(from).dot(h / hidden_length)) : 0.0;
    h -= clamp_norm(h, return_speed(speed, following) * dt);
    const double length = h.norm();
    if (length > 0.0) {
      const double along = stretch.segment<3>(from).dot(h / length);
      h *= std::clamp(along, 0.0, length) / length;
    }
    hidden.segment<3>(from) = h;
  };
  release(m.stretch, 0, config_.restretch_speed);
  release(m.stretch, 3, config_.restretch_angular_speed);
  m.anchored = m.stretch.squaredNorm() > 0.0;
  return stretch - m.stretch;
}

Vector6d ServoLaw::restretch_damping(const Vector6d& twist) const noexcept {
  // A hand that pushed 5 N into a 3000 N/m wall through a blackout plunged at the viscous hold's
  // 0.16-0.21 m/s, met the returning wall and bounced off it at 0.13-0.16 m/s, the coupling's
  // delay-bounded damper giving back most of what the wall took (J1 asks 0.1 m/s; 2026-12-03).
  // While the hidden stretch comes back, the handle's motion along it is damped with the
  // device's stable damping: on the handle's own velocity, so it is passive at any delay, and
  // only along the returning stretch, so that the hand slides freely along the wall. It fades
  // over the hidden stretch's last millimetre (no step when the stretch is back).
  const RenderMemory& m = memory_;
  Vector6d damping = Vector6d::Zero();
  if (!m.anchored) {
    return damping;
  }
  const ArmLimits& lim = dynamics_->model().limits;
  const auto along = [&](int from, double fade, double max_damping) {
    const Vector3d h = m.stretch.segment<3>(from);
    const double length = h.norm();
    if (length > 0.0) {
      const Vector3d u = h / length;
      const double share = std::min(1.0, length / fade);
      damping.segment<3>(from) = -share * max_damping * twist.segment<3>(from).dot(u) * u;
    }
  };
  along(0, config_.restretch_damper_fade, lim.max_damping_linear);
  along(3, config_.restretch_damper_angular_fade, lim.max_damping_angular);
  return damping;
}

ServoLaw::Surface ServoLaw::reported_surface(const ServoInputs& in, const ClientFrame& frame,
                                             const ChainState& chain,
                                             bool on_object) const noexcept {
  // A contact the client reports (protocol 1.3) is a plane for the handle's point, rendered at
  // the servo rate from the handle's position now: a wall with no delay inside its loop, whose
  // stiffness is bounded by the device only (K_max ~ 2(b+B)/T with the device's stable damping
  // B; with the client's own 2 N.s/m a 2000 N/m wall shook at 2.3 m/s, 2026-12-03). This is the
  // intermediate representation of Adachi et al. 1995 and model-mediated teleoperation (Mitra &
  // Niemeyer 2008): through the coupling alone a delayed loop is soft (211 N/m felt at 10 ms one
  // way, 71 N/m at 20 ms, J2). An IMPEDANCE client's `point` is where its handle's point meets
  // the surface. A VIRTMECH client's is on its object: the surface passes through point -
  // distance * normal, and the handle, which the coupling holds at the object, meets it where
  // the object's centre did, `distance` beyond the object's reported position. One surface, the
  // deepest; unilateral (it never pulls).
  const ArmLimits& lim = dynamics_->model().limits;
  const ClientSample& c = in.client;
  const Matrix3d to_base = frame.rotation.conjugate().toRotationMatrix();
  const double period = static_cast<double>(in.dt) * 1e-9;
  const double bound = period > 0.0
                           ? std::min(lim.max_stiffness_linear, config_.surface_bound_share * 2.0 *
                                                                    lim.max_damping_linear / period)
                           : lim.max_stiffness_linear;
  Surface best;
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < std::min<std::size_t>(c.contact_count, c.contacts.size()); ++i) {
    const ClientContact& contact = c.contacts[i];
    const double weight = contact_weight(in.now - contact.received_ns, config_);
    if (!(contact.stiffness > 0.0) || weight <= 0.0) {
      continue;
    }
    ++best.fresh;
    const TimeNs age = in.now - contact.received_ns;
    best.age = best.age < 0 ? age : std::min(best.age, age);
    const Vector3d normal =
        (to_base * Vector3d(contact.normal[0], contact.normal[1], contact.normal[2])).normalized();
    const Vector3d point =
        on_object ? Vector3d(to_base *
                                 (Vector3d(contact.object_pose[0], contact.object_pose[1],
                                           contact.object_pose[2]) -
                                  frame.origin) /
                                 frame.speed_factor -
                             contact.distance / frame.speed_factor * normal)
                  : Vector3d(to_base *
                             (Vector3d(contact.point[0], contact.point[1], contact.point[2]) -
                              frame.origin) /
                             frame.speed_factor);
    const double depth = (point - chain.handle_position).dot(normal);
    if (depth <= deepest) {
      continue;
    }
    deepest = depth;
    best.normal = normal;
    best.depth = depth;
    best.point = point;
    best.weight = weight;
    best.share = weight * std::clamp((kTouchBand + depth) / kTouchBand, 0.0, 1.0);
    best.stiffness = std::min(bound, contact.stiffness * frame.speed_factor);
    best.damping = lim.max_damping_linear;
    best.friction_static = contact.friction[0];
    best.friction_dynamic = std::min(contact.friction[1], contact.friction[0]);
  }
  return best;
}

void ServoLaw::render_surface(Surface& surface, const ChainState& chain, const Vector6d& twist,
                              double dt) noexcept {
  RenderMemory& m = memory_;
  const Vector3d& handle = chain.handle_position;
  const double reported = surface.share > 0.0 ? surface.depth : 0.0;
  if (reported <= 0.0) {
    m.on_surface = false;
    m.surface_hidden = 0.0;
    m.surface_budget = 0.0;
    return;
  }
  const Vector3d& n = surface.normal;
  const Vector3d v = twist.head<3>();
  // Passive model updates (the hazard of model-mediated teleoperation: a plane that moves or
  // appears under the handle steps the force and puts out energy). The plane rendered last
  // cycle, at the handle's position now, bounds the depth rendered: a report may take the plane
  // away from the handle at once, never bring it toward it. A surface that appears with the
  // handle inside it (reported a loop late, or moved onto it) is rendered from where the handle
  // is: a 2000 N/m wall whose first report found the handle 7 cm deep kicked it out at 35 N (100
  // ms one way, 2026-12-03). What a held contact renders there is not hidden: after a blackout
  // the hand still presses on it (hidden, the 10 N a hand pressed on a held surface fell to
  // nothing as it came back).
  double before = 0.0;
  if (m.on_surface) {
    before = (m.surface_point - handle).dot(m.surface_normal);
  } else {
    const RenderMemory::HeldContact& h = m.held;
    before = h.contact_stiffness > 0.0 && h.normal.dot(n) > 0.99 ? h.depth_at(handle) : 0.0;
    m.on_surface = true;
    m.surface_budget = 0.0;
    m.friction_anchor = handle;
  }
  double rendered = std::clamp(before, 0.0, reported);
  if (const double grew = reported - rendered - m.surface_hidden; grew > 1e-9) {
    ++counters_.surface_updates_held;
    // The spring energy the update would have put in at once, had the plane come with it.
    m.surface_withheld += surface.weight * surface.stiffness * grew * (rendered + 0.5 * grew);
  }
  // What is hidden comes back (at restretch_speed at most) only as far as the energy the
  // surface dissipated pays for the spring energy it adds (TDPA's budget, Ryu & Hannaford
  // 2002): given back on time alone, a plane that jumped 5 mm into a handle held still pushed
  // it out with the energy of the jump (2000 N/m: 25 mJ).
  const double hidden = reported - rendered;
  if (hidden > 0.0) {
    const double step = std::min(hidden, config_.restretch_speed * dt);
    const double cost = surface.weight * surface.stiffness * (rendered + 0.5 * step);
    const double back = cost > 0.0 ? std::min(step, m.surface_budget / cost) : step;
    rendered += back;
    m.surface_budget = std::max(0.0, m.surface_budget - back * cost);
  }
  m.surface_hidden = reported - rendered;
  m.surface_point = handle + rendered * n;
  m.surface_normal = n;
  // The damper comes in over the first half millimetre, so that touching is not a step.
  const double engaged = std::clamp(rendered / 5e-4, 0.0, 1.0);
  const double spring = surface.stiffness * rendered;
  const double damper = engaged * surface.damping * v.dot(n);
  surface.force = surface.weight * std::max(0.0, spring - damper);
  if (surface.force <= 0.0) {
    m.friction_anchor = handle;
    return;
  }
  // The budget is what the surface dissipated lately, not in all its history: banked without
  // bound, the damping of the first touch and of the resting handle's encoder dither paid, when
  // the wall jumped 5 mm into a handle held still, for pushing it 0.5 mm back out (2.3 mJ out
  // of the port, 2000 N/m, 2026-12-05).
  const auto bank = [&m](double dissipated) {
    m.surface_budget = std::min(m.surface_budget + dissipated, kSurfaceBudgetBound);
  };
  if (spring - damper > 0.0) {
    bank(surface.weight * engaged * surface.damping * v.dot(n) * v.dot(n) * dt);
  }
  // Coulomb friction as a proxy (Zilles & Salisbury 1995; Ruspini et al. 1997): the handle
  // sticks to an anchor on the surface through a tangential spring (the surface's stiffness,
  // damped with the device's stable damping) while that spring needs no more than mu_s times
  // the normal force; beyond, the anchor slides after the handle, the spring holding mu_d
  // times it. Local and passive: the client's friction, computed from a handle a loop old,
  // drove it along a 2000 N/m wall at 0.5-1.3 m/s at 100 ms one way (2026-12-03).
  const auto tangential = [&n](const Vector3d& x) -> Vector3d { return x - x.dot(n) * n; };
  Vector3d slip = tangential(handle - m.friction_anchor);
  if (surface.stiffness * slip.norm() > surface.friction_static * surface.force) {
    const double kept = surface.friction_dynamic * surface.force / surface.stiffness;
    const Vector3d slide = slip - slip.normalized() * kept;
    m.friction_anchor += slide;  // slides after the handle, dissipating mu_d F per metre
    bank(surface.friction_dynamic * surface.force * slide.norm());
    slip = tangential(handle - m.friction_anchor);
  }
  surface.friction = -surface.stiffness * slip - engaged * surface.damping * tangential(v);
  // Never more than the cone allows (the damper included): friction resists, it never drives.
  const double cone = surface.friction_static * surface.force;
  if (surface.friction.norm() > cone) {
    surface.friction *= cone / surface.friction.norm();
  }
}

void ServoLaw::hold_contact(const ServoInputs& in, const Coupling& coupling,
                            double engage) noexcept {
  // What the hand feels of a contact on a fresh link, wholly engaged (a VIRTMECH coupling that
  // is not re-stretching, or an IMPEDANCE surface), is noted; once the link falls silent what
  // was noted stays, and held_contact_force renders it as the link's coupling fades.
  if (in.client_silence > config_.contact_fresh) {
    return;
  }
  if (!coupling.contact_local && (engage < 1.0 || memory_.anchored)) {
    return;
  }
  if (!coupling.contact_in_force) {
    memory_.held = RenderMemory::HeldContact{};
  } else if (coupling.contact_whole) {
    memory_.held = coupling.contact;
  }
}

Vector3d ServoLaw::held_contact_force(const ServoInputs& in, double engage) const noexcept {
  // A surface the client's object rests on does not go away when the link does: a hand that
  // pushed 5 N into a 3000 N/m wall through a 2 s blackout went 30 cm through the faded wall at
  // the viscous hold's 0.16-0.21 m/s, and was still that fast when the link returned (J1 asks
  // 0.1 m/s; 2026-12-03). The contact as the hand last felt it is a static, unilateral plane on
  // the handle's position now: passive at any delay (no sample is in its loop). It takes over
  // what fades of the coupling: its own share as the link's engagement falls, the contact's as
  // the link's silence ages it (contact_weight on the link's silence, so that a contact the
  // client withdraws on a live link fades as it did); a surface rendered here (no coupling
  // stiffness held) is not engaged.
  const RenderMemory::HeldContact& h = memory_.held;
  const double depth = h.depth_at(chain_.handle_position);
  if (depth <= 0.0) {
    return Vector3d::Zero();
  }
  const double coupled = h.coupling_stiffness > 0.0 ? engage : 1.0;
  const double link = contact_weight(in.client_silence, config_);
  const double stiffness =
      (1.0 - engage) * h.coupling_stiffness + (1.0 - coupled * link) * h.contact_stiffness;
  return stiffness * depth * h.normal;
}

}  // namespace hapticctrl::rt_core
