#pragma once
// Small conversions and bounds the parts of the servo law share (servo_law*.cpp). Internal.
#include <array>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"

namespace hapticctrl::rt_core::law_math {

HAPTICCTRL_RT inline Vector6d to_vector(const std::array<double, 6>& a) noexcept {
  Vector6d v;
  for (int i = 0; i < 6; ++i) {
    v(i) = a[static_cast<std::size_t>(i)];
  }
  return v;
}

HAPTICCTRL_RT inline Eigen::Quaterniond to_quaternion(const std::array<double, 7>& pose) noexcept {
  return {pose[6], pose[3], pose[4], pose[5]};  // w, x, y, z
}

/// Scales `v` down to norm `limit` if longer.
HAPTICCTRL_RT inline Vector3d clamp_norm(const Vector3d& v, double limit) noexcept {
  const double n = v.norm();
  return n > limit && n > 0.0 ? Vector3d(v * (limit / n)) : v;
}

/// The rotation vector (axis * angle) of a rotation matrix.
HAPTICCTRL_RT inline Vector3d rotation_vector(const Matrix3d& r) noexcept {
  const Eigen::AngleAxisd a(r);
  return a.axis() * a.angle();
}

/// The client object's twist in our base frame (linear de-scaled by the speed factor).
HAPTICCTRL_RT inline Vector6d object_twist_in_base(const ClientSample& c,
                                                   const ClientFrame& frame) noexcept {
  const Vector6d env = to_vector(c.object_twist);
  Vector6d base;
  base << frame.rotation.conjugate() * env.head<3>() / frame.speed_factor,
      frame.rotation.conjugate() * env.tail<3>();
  return base;
}

}  // namespace hapticctrl::rt_core::law_math
