// Implements grasp.hpp: the constant offset and turn between the scene's body and the handle.
#include "hapticctrl/mujoco/grasp.hpp"

#include <Eigen/Geometry>

namespace hapticctrl::mujoco {
namespace {

Eigen::Quaterniond rotation_of(const client::Pose7& p) {
  return Eigen::Quaterniond(p[6], p[3], p[4], p[5]).normalized();
}

}  // namespace

Grasp Grasp::between(const client::Pose7& body, const client::Pose7& handle) noexcept {
  Grasp g;
  for (std::size_t i = 0; i < 3; ++i) {
    g.offset_[i] = body[i] - handle[i];
  }
  const Eigen::Quaterniond turn =
      (rotation_of(body).conjugate() * rotation_of(handle)).normalized();
  g.turn_ = {turn.x(), turn.y(), turn.z(), turn.w()};
  return g;
}

client::Pose7 Grasp::to_client(const client::Pose7& body) const noexcept {
  const Eigen::Quaterniond turn(turn_[3], turn_[0], turn_[1], turn_[2]);
  const Eigen::Quaterniond q = (rotation_of(body) * turn).normalized();
  return {
      body[0] - offset_[0], body[1] - offset_[1], body[2] - offset_[2], q.x(), q.y(), q.z(), q.w()};
}

std::array<double, 3> Grasp::point_to_client(const std::array<double, 3>& p) const noexcept {
  return {p[0] - offset_[0], p[1] - offset_[1], p[2] - offset_[2]};
}

}  // namespace hapticctrl::mujoco
