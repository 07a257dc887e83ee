// The surfaces the servo law renders on the handle (J2): a contact the client reports becomes a
// plane for the handle's point, rendered at the servo rate from where the handle is now
// (ServoLaw::local_surfaces, reported_surfaces, render_surfaces); docs/control.md.
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

/// Contacts whose normals agree this well are one plane (8 degrees): the deepest of them.
constexpr double kSameSurface = 0.99;
/// A surface continues last cycle's plane whose normal is nearest, within 25 degrees (a contact
/// that rolls over a curved object turns its normal by a fraction of that in a cycle).
constexpr double kFollowedSurface = 0.9;

}  // namespace

void ServoLaw::add_surface(Surfaces& found, const Surface& s) noexcept {
  for (std::size_t j = 0; j < found.count; ++j) {
    if (found.list[j].normal.dot(s.normal) > kSameSurface) {
      if (s.depth > found.list[j].depth) {
        found.list[j] = s;
      }
      return;
    }
  }
  if (found.count < found.list.size()) {
    found.list[found.count++] = s;
    return;
  }
  auto shallowest =
      std::min_element(found.list.begin(), found.list.end(),
                       [](const Surface& a, const Surface& b) { return a.depth < b.depth; });
  if (s.depth > shallowest->depth) {
    *shallowest = s;
  }
}

ServoLaw::Surfaces ServoLaw::local_surfaces(const ServoInputs& in, const ClientFrame& frame,
                                            const ChainState& chain, const Vector6d& twist,
                                            bool on_object, Coupling& coupling,
                                            ServoOutputs& out) noexcept {
  Surfaces found = reported_surfaces(in, frame, chain, on_object);
  render_surfaces(found, chain, twist, to_seconds(in.dt));
  out.surface_withheld = memory_.surface_withheld;
  out.contact_age = found.age;
  for (std::size_t i = 0; i < found.count; ++i) {
    const Surface& s = found.list[i];
    found.push += s.force * s.normal + s.friction;
    // The coupling gives way to a surface over its first 0.5 mm of force.
    if (s.stiffness > 0.0) {
      found.in_force = std::max(found.in_force, std::min(1.0, s.force / (s.stiffness * 5e-4)));
    }
    if (s.force > found.list[found.strongest].force) {
      found.strongest = i;
    }
  }
  if (found.count == 0) {
    return found;
  }
  const Surface& top = found.list[found.strongest];
  double hidden = 0.0;
  if (top.pressed()) {
    const RenderMemory::SurfaceMemory& m = memory_.surfaces[top.slot];
    hidden = m.hidden;
    out.surface_normal = top.normal;
    out.surface_point = m.point;
    out.surface_depth = (m.point - chain.handle_position).dot(top.normal);
    out.surface_force = top.force * frame.force_factor;
    out.surface_hidden = m.hidden;
  }
  if (top.weight > 0.0) {
    coupling.contact_in_force = true;
    coupling.contact_whole = top.weight >= 1.0;
    coupling.contact_local = true;
    coupling.contact = {top.normal, top.point - hidden * top.normal, 0.0,
                        top.stiffness * frame.force_factor};
  }
  return found;
}

ServoLaw::Surfaces ServoLaw::reported_surfaces(const ServoInputs& in, const ClientFrame& frame,
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
  // the object's centre did, `distance` beyond the object's reported position. Contacts along
  // one normal are one plane, the deepest of them (a box on a table: four contacts, one plane);
  // unilateral (it never pulls).
  const ArmLimits& lim = dynamics_->model().limits;
  const ClientSample& c = in.client;
  const Matrix3d to_base = frame.rotation.conjugate().toRotationMatrix();
  const double period = to_seconds(in.dt);
  const double bound = period > 0.0
                           ? std::min(lim.max_stiffness_linear, config_.surface_bound_share * 2.0 *
                                                                    lim.max_damping_linear / period)
                           : lim.max_stiffness_linear;
  Surfaces found;
  for (std::size_t i = 0; i < std::min<std::size_t>(c.contact_count, c.contacts.size()); ++i) {
    const ClientContact& contact = c.contacts[i];
    const double weight = contact_weight(in.now - contact.received, config_);
    if (!(contact.stiffness > 0.0) || weight <= 0.0) {
      continue;
    }
    ++found.fresh;
    const Duration age = in.now - contact.received;
    found.age = found.age ? std::min(*found.age, age) : age;
    Surface s;
    s.normal =
        (to_base * Vector3d(contact.normal[0], contact.normal[1], contact.normal[2])).normalized();
    s.point = on_object ? Vector3d(to_base *
                                       (Vector3d(contact.object_pose[0], contact.object_pose[1],
                                                 contact.object_pose[2]) -
                                        frame.origin) /
                                       frame.speed_factor -
                                   contact.distance / frame.speed_factor * s.normal)
                        : Vector3d(to_base *
                                   (Vector3d(contact.point[0], contact.point[1], contact.point[2]) -
                                    frame.origin) /
                                   frame.speed_factor);
    s.depth = (s.point - chain.handle_position).dot(s.normal);
    s.weight = weight;
    s.share = weight * std::clamp((kTouchBand + s.depth) / kTouchBand, 0.0, 1.0);
    s.stiffness = std::min(bound, contact.stiffness * frame.speed_factor);
    s.damping = lim.max_damping_linear;
    s.friction_static = contact.friction[0];
    s.friction_dynamic = std::min(contact.friction[1], contact.friction[0]);
    add_surface(found, s);
  }
  std::sort(found.list.begin(), found.list.begin() + static_cast<std::ptrdiff_t>(found.count),
            [](const Surface& a, const Surface& b) { return a.depth > b.depth; });
  return found;
}

void ServoLaw::render_surfaces(Surfaces& surfaces, const ChainState& chain, const Vector6d& twist,
                               double dt) noexcept {
  constexpr std::size_t kNone = RenderMemory::kSurfaces;
  std::array<bool, RenderMemory::kSurfaces> taken{};
  // Each surface keeps the slot whose plane it continues (the nearest normal) ...
  for (std::size_t i = 0; i < surfaces.count; ++i) {
    Surface& s = surfaces.list[i];
    double nearest = kFollowedSurface;
    for (std::size_t j = 0; j < kNone; ++j) {
      const RenderMemory::SurfaceMemory& m = memory_.surfaces[j];
      if (m.on && !taken[j] && m.normal.dot(s.normal) > nearest) {
        nearest = m.normal.dot(s.normal);
        s.slot = j;
      }
    }
    if (s.slot != kNone) {
      taken[s.slot] = true;
    }
  }
  // ... a new one takes a free slot, and the slots no surface continues are forgotten.
  for (std::size_t i = 0; i < surfaces.count; ++i) {
    Surface& s = surfaces.list[i];
    for (std::size_t j = 0; s.slot == kNone && j < kNone; ++j) {
      if (!taken[j]) {
        s.slot = j;
        taken[j] = true;
        memory_.surfaces[j] = RenderMemory::SurfaceMemory{};
      }
    }
  }
  for (std::size_t j = 0; j < kNone; ++j) {
    if (!taken[j]) {
      memory_.surfaces[j] = RenderMemory::SurfaceMemory{};
    }
  }
  // Together no stiffer than the sampled-data bound 2 B / T (each is at most half of it): two
  // surfaces at any angle pass whole, three at acute angles share it. Counted on their shares,
  // which come in over the touch band, so that a surface coming into force steps nothing.
  double together = 0.0;
  for (std::size_t i = 0; i < surfaces.count; ++i) {
    together += surfaces.list[i].share * surfaces.list[i].stiffness;
  }
  const double bound = dt > 0.0 ? 2.0 * dynamics_->model().limits.max_damping_linear / dt : 0.0;
  const double scale = together > bound && bound > 0.0 ? bound / together : 1.0;
  for (std::size_t i = 0; i < surfaces.count; ++i) {
    Surface& s = surfaces.list[i];
    s.stiffness *= scale;
    s.damping *= scale;
    RenderMemory::SurfaceMemory& m = memory_.surfaces[s.slot];
    if (s.pressed()) {
      render_surface(s, m, chain, twist, dt);
    } else {
      // Not in force: rendered last cycle where it is reported, so that a handle that moves
      // into it meets it there (and a report that then comes toward the handle is a model
      // update, held back as one).
      m = RenderMemory::SurfaceMemory{true, 0.0, s.point, s.normal, 0.0, chain.handle_position};
    }
  }
}

void ServoLaw::render_surface(Surface& surface, RenderMemory::SurfaceMemory& m,
                              const ChainState& chain, const Vector6d& twist, double dt) noexcept {
  const Vector3d& handle = chain.handle_position;
  const double reported = surface.depth;  // > 0: render_surfaces renders surfaces in force
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
  if (m.on) {
    before = (m.point - handle).dot(m.normal);
  } else {
    const RenderMemory::HeldContact& h = memory_.held;
    before = h.contact_stiffness > 0.0 && h.normal.dot(n) > 0.99 ? h.depth_at(handle) : 0.0;
    m.on = true;
    m.budget = 0.0;
    m.friction_anchor = handle;
  }
  double rendered = std::clamp(before, 0.0, reported);
  if (const double grew = reported - rendered - m.hidden; grew > 1e-9) {
    ++counters_.surface_updates_held;
    // The spring energy the update would have put in at once, had the plane come with it.
    memory_.surface_withheld += surface.weight * surface.stiffness * grew * (rendered + 0.5 * grew);
  }
  // What is hidden comes back (at restretch_speed at most) only as far as the energy the
  // surface dissipated pays for the spring energy it adds (TDPA's budget, Ryu & Hannaford
  // 2002): given back on time alone, a plane that jumped 5 mm into a handle held still pushed
  // it out with the energy of the jump (2000 N/m: 25 mJ).
  const double hidden = reported - rendered;
  if (hidden > 0.0) {
    const double step = std::min(hidden, config_.restretch_speed * dt);
    const double cost = surface.weight * surface.stiffness * (rendered + 0.5 * step);
    const double back = cost > 0.0 ? std::min(step, m.budget / cost) : step;
    rendered += back;
    m.budget = std::max(0.0, m.budget - back * cost);
  }
  m.hidden = reported - rendered;
  m.point = handle + rendered * n;
  m.normal = n;
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
    m.budget = std::min(m.budget + dissipated, kSurfaceBudgetBound);
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
