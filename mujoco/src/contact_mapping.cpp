// Implements contact_mapping.hpp: MuJoCo's solref/solimp as the spring and damper a hand feels.
#include "hapticctrl/mujoco/contact_mapping.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::mujoco {
namespace {

/// The protocol's bounds (protocol/values.hpp, checked again by the controller).
constexpr double kMaxFriction = 10.0;
constexpr double kMaxDamping = 1e6;    // N.s/m
constexpr double kMinStiffness = 1.0;  // N/m
/// Contacts whose normals are within 10 degrees belong to one surface.
const double kSameSurfaceCosine = std::cos(10.0 * 3.14159265358979323846 / 180.0);

/// The contact's direction as the surface pushes the coupled body.
std::array<double, 3> push_direction(const EngineContact& c) noexcept {
  const double sign = c.body_is_geom2 ? 1.0 : -1.0;  // MuJoCo's normal: from geom1 to geom2
  return {sign * c.normal[0], sign * c.normal[1], sign * c.normal[2]};
}

double dot(const std::array<double, 3>& a, const std::array<double, 3>& b) noexcept {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

}  // namespace

SurfaceGains contact_gains(const EngineContact& c, double timestep) noexcept {
  const double d = c.solimp[0];
  const double dmax = c.solimp[1];
  if (!(d > 0.0 && d < 1.0) || !(dmax > 0.0 && dmax < 1.0) || !(c.inverse_weight > 0.0) ||
      c.condim < 1) {
    return {};
  }
  double k = 0.0;
  double b = 0.0;
  if (c.solref[0] > 0.0) {
    const double timeconst = std::max(c.solref[0], 2.0 * std::max(timestep, 0.0));  // refsafe
    const double dampratio = c.solref[1];
    k = 1.0 / (dmax * dmax * timeconst * timeconst * dampratio * dampratio);
    b = 2.0 / (dmax * timeconst);
  } else {
    k = -c.solref[0] / (dmax * dmax);
    b = -c.solref[1] / dmax;
  }
  // Rows and their approximate inverse inertia: a pyramid has two edges per sliding (and
  // spinning, rolling) direction, each n +- mu t, weighted 1 + mu^2; otherwise one normal row.
  double per_weight = 0.0;  // sum over rows of 1 / A
  if (c.pyramidal && c.condim > 1) {
    for (int j = 0; j < c.condim - 1 && j < 5; ++j) {
      const double mu = c.friction[static_cast<std::size_t>(j)];
      per_weight += 2.0 / (c.inverse_weight * (1.0 + mu * mu));
    }
  } else {
    per_weight = 1.0 / c.inverse_weight;
  }
  SurfaceGains g{d * d / (1.0 - d) * k * per_weight, d / (1.0 - d) * b * per_weight};
  if (!std::isfinite(g.stiffness) || !std::isfinite(g.damping) || !(g.stiffness > 0.0)) {
    return {};
  }
  g.damping = std::clamp(g.damping, 0.0, kMaxDamping);
  return g;
}

std::size_t to_client_contacts(std::span<const EngineContact> in, double timestep,
                               double max_stiffness, std::span<client::Contact> out) noexcept {
  std::size_t count = 0;
  for (const EngineContact& c : in) {
    if (count >= out.size()) {
      break;
    }
    if (contact_gains(c, timestep).stiffness <= 0.0) {
      continue;
    }
    const std::array<double, 3> normal = push_direction(c);
    SurfaceGains surface;
    for (const EngineContact& other : in) {
      if (dot(push_direction(other), normal) >= kSameSurfaceCosine) {
        const SurfaceGains g = contact_gains(other, timestep);
        surface.stiffness += g.stiffness;
        surface.damping += g.damping;
      }
    }
    client::Contact& o = out[count++];
    for (std::size_t i = 0; i < 3; ++i) {
      o.normal[i] = normal[i];
      // The surfaces are `distance` apart along the normal, the midpoint between them: the
      // body's own is half of it further along.
      o.point[i] = c.midpoint[i] + 0.5 * c.distance * normal[i];
    }
    o.distance = c.distance;
    o.stiffness =
        std::max(kMinStiffness, max_stiffness > 0.0 ? std::min(surface.stiffness, max_stiffness)
                                                    : surface.stiffness);
    o.damping = std::min(surface.damping, kMaxDamping);
    o.friction_static = std::clamp(c.friction[0], 0.0, kMaxFriction);
    o.friction_dynamic = o.friction_static;
  }
  return count;
}

}  // namespace hapticctrl::mujoco
