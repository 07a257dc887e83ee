// The surfaces the servo law renders on the handle (J2): a contact the client reports becomes a
// plane for the handle's point, rendered at the servo rate from where the handle is now
// (ServoLaw::local_surface, reported_surface, render_surface); docs/control.md.
#include <algorithm>
#include <cmath>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"
#include "law_contacts.hpp"
#include "law_math.hpp"

namespace hapticctrl::rt_core {
namespace {

using law_contacts::contact_weight;
using law_contacts::kTouchBand;

/// The most dissipated energy a surface keeps to give a hidden depth back with (J): a fifth of
/// J2's 1 mJ bound on what a model update may put out. A hand that moves on the surface pays as
/// it goes (sliding 1 cm at 5 N with mu 0.6 dissipates 30 mJ).
constexpr double kSurfaceBudgetBound = 2e-4;

}  // namespace

ServoLaw::Surface ServoLaw::local_surface(const ServoInputs& in, const ClientFrame& frame,
                                          const ChainState& chain, const Vector6d& twist,
                                          bool on_object, Coupling& coupling,
                                          ServoOutputs& out) noexcept {
  Surface surface = reported_surface(in, frame, chain, on_object);
  render_surface(surface, chain, twist, to_seconds(in.dt));
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
  const double period = to_seconds(in.dt);
  const double bound = period > 0.0
                           ? std::min(lim.max_stiffness_linear, config_.surface_bound_share * 2.0 *
                                                                    lim.max_damping_linear / period)
                           : lim.max_stiffness_linear;
  Surface best;
  double deepest = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < std::min<std::size_t>(c.contact_count, c.contacts.size()); ++i) {
    const ClientContact& contact = c.contacts[i];
    const double weight = contact_weight(in.now - contact.received, config_);
    if (!(contact.stiffness > 0.0) || weight <= 0.0) {
      continue;
    }
    ++best.fresh;
    const Duration age = in.now - contact.received;
    best.age = best.age ? std::min(*best.age, age) : age;
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

}  // namespace hapticctrl::rt_core
