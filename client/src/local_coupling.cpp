// Implements local_coupling.hpp: the object's side of the coupling, closed in the client
// library on the application's own object state (protocol 1.3).
#include "local_coupling.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace hapticctrl::client {
namespace {

/// The object's damper along a contact comes in over its first 0.5 mm (as the controller's).
constexpr double kDamperBand = 5e-4;

Eigen::Vector3d head(const std::array<double, 7>& p) noexcept {
  return {p[0], p[1], p[2]};
}
Eigen::Quaterniond rotation(const std::array<double, 7>& p) noexcept {
  const Eigen::Quaterniond q(p[6], p[3], p[4], p[5]);
  return q.norm() > 0.5 ? q.normalized() : Eigen::Quaterniond::Identity();
}
Eigen::Vector3d part(const Vector6& v, int from) noexcept {
  const auto i = static_cast<std::size_t>(from);
  return {v[i], v[i + 1], v[i + 2]};
}
Eigen::Vector3d clamped(const Eigen::Vector3d& v, double limit) noexcept {
  const double n = v.norm();
  return limit > 0.0 && n > limit ? Eigen::Vector3d(v * (limit / n)) : v;
}

}  // namespace

CouplingTerms terms_of(const hcp_coupling_report& report,
                       const hcp_local_coupling& local) noexcept {
  CouplingTerms t;
  for (std::size_t i = 0; i < 4; ++i) {
    t.gains[i] = report.gains[i];
  }
  for (std::size_t i = 0; i < 3; ++i) {
    t.contact_normal[i] = local.contact_normal[i];
  }
  t.normal_gains = {local.normal_gains[0], local.normal_gains[1]};
  t.limits = {local.limits[0], local.limits[1]};
  return t;
}

Vector6 object_wrench(const CouplingTerms& t, const Pose7& handle_pose, const Vector6& handle_twist,
                      const Pose7& object_pose, const Vector6& object_twist, double penetration,
                      double speed_factor, double force_factor) noexcept {
  // The controller's gains act on its base-frame metres (client metres / speed factor) and the
  // object gets the coupling without the force factor (docs/control.md).
  const double sf = speed_factor > 0.0 ? speed_factor : 1.0;
  const double ff = force_factor > 0.0 ? force_factor : 1.0;
  const Eigen::Vector3d stretch = head(handle_pose) - head(object_pose);  // client metres
  const Eigen::Vector3d relative = part(handle_twist, 0) - part(object_twist, 0);
  const Eigen::AngleAxisd turn(rotation(handle_pose) * rotation(object_pose).conjugate());
  Eigen::Vector3d force = (t.gains[0] * stretch + t.gains[1] * relative) / sf;
  Eigen::Vector3d torque = t.gains[2] * turn.axis() * turn.angle() +
                           t.gains[3] * (part(handle_twist, 3) - part(object_twist, 3));
  const Eigen::Vector3d normal(t.contact_normal[0], t.contact_normal[1], t.contact_normal[2]);
  if (normal.squaredNorm() > 1e-12) {
    // The handle presses the object into the contact when the stretch points into the surface;
    // the stiffening acts on the handle's depth in the surface (the stretch plus the object's
    // own penetration), as the controller renders the surface on the handle: the object is
    // pressed with the force the hand feels (J2).
    const Eigen::Vector3d n = normal.normalized();
    const double share = std::min(1.0, normal.norm());
    const double depth = -stretch.dot(n) / sf;
    const double engaged = std::clamp(depth / kDamperBand, 0.0, 1.0);
    const double pen = std::max(0.0, penetration) / sf;
    if (depth + pen > 0.0) {  // (k + stiffening) on the handle's depth, in the contact's share
      force -= (t.normal_gains[0] * (depth + pen) + share * t.gains[0] * pen) * n;
    }
    force += engaged * t.normal_gains[1] * relative.dot(n) / sf * n;
  }
  force = clamped(force, t.limits[0] / ff);
  torque = clamped(torque, t.limits[1] / ff);
  return {force.x(), force.y(), force.z(), torque.x(), torque.y(), torque.z()};
}

Vector6 along_contact(const CouplingTerms& t, const Vector6& controller,
                      const Vector6& local) noexcept {
  // The normal's length is the share of the contact in force (fresh, touching): the local
  // wrench comes in in that share, so touching and leaving are no steps.
  const Eigen::Vector3d n(t.contact_normal[0], t.contact_normal[1], t.contact_normal[2]);
  const double share = std::min(1.0, n.norm());
  Vector6 w = controller;
  for (std::size_t i = 0; i < 6; ++i) {
    w[i] += share * (local[i] - controller[i]);
  }
  return w;
}

}  // namespace hapticctrl::client
