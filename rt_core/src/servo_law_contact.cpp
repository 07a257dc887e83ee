// The coupling where the client's object touches something, and after the coupling let go:
// the stiffening along a contact the client reports (ServoLaw::contact_stiffening), the
// re-anchored spring after a full disengagement (ServoLaw::stretch_in_use) and the contact held
// through a blackout (ServoLaw::hold_contact); docs/control.md, J1. The surfaces rendered on the
// handle (J2) are in servo_law_surface.cpp.
#include <algorithm>
#include <cmath>
#include <limits>

#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"
#include "law_contacts.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

using law_contacts::contact_weight;
using law_contacts::kTouchBand;
using law_math::clamp_norm;

/// A handle creeping out of a soft workspace wall as a force comes back moves at up to this; a
/// faster motion away along a hidden stretch or depth is the handle being carried (m/s).
constexpr double kCreepSpeed = 0.02;

/// How fast a hidden stretch or depth comes back: `speed` less the handle's own speed away
/// along it (`leaving`, m/s) beyond the creep, never below zero.
HAPTICCTRL_RT double return_speed(double speed, double leaving) noexcept {
  return std::max(0.0, speed - std::max(0.0, leaving - kCreepSpeed));
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
    const double weight = contact_weight(in.now - contact.received, config_);
    if (weight <= 0.0) {
      continue;
    }
    ++best.fresh;
    const Vector3d normal =
        (to_base * Vector3d(contact.normal[0], contact.normal[1], contact.normal[2])).normalized();
    // The gap now: as reported, less how far the object's reported position moved towards the
    // surface since, that is against the normal, along which the surface pushes it (neither the
    // extrapolation over the sample's age nor the channel PC's drift is a motion of the object:
    // with them the contact flickered in and out of its band).
    const Vector3d at_report =
        to_base *
        (Vector3d(contact.object_pose[0], contact.object_pose[1], contact.object_pose[2]) -
         frame.origin) /
        frame.speed_factor;
    const double gap = contact.distance / frame.speed_factor + (reported - at_report).dot(normal);
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
