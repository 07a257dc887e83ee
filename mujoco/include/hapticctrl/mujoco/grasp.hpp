#pragma once
/// @file grasp.hpp
/// Where the hand holds the coupled body: the scene and the arm's workspace are placed so that
/// at the session's start the body is where the handle is. Positions are shifted by a constant
/// offset (the scene's axes stay the arm's: up is up, gravity is along -z in both), and the
/// body's orientation is taken with a constant turn in its own frame (the handle's at the start),
/// so velocities, forces and torques are the same numbers on both sides.
#include <array>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::mujoco {

class Grasp {
 public:
  /// The identity: scene coordinates are the client's.
  Grasp() = default;
  /// The body at `body` (scene) held by a handle at `handle` (client frame).
  static Grasp between(const client::Pose7& body, const client::Pose7& handle) noexcept;

  /// The body's pose as the client sends it.
  [[nodiscard]] client::Pose7 to_client(const client::Pose7& body) const noexcept;
  /// A point of the scene (a contact's) in the client's frame.
  [[nodiscard]] std::array<double, 3> point_to_client(
      const std::array<double, 3>& p) const noexcept;

 private:
  std::array<double, 3> offset_{};          ///< scene minus client
  std::array<double, 4> turn_{0, 0, 0, 1};  ///< x y z w, body frame -> the handle's
};

}  // namespace hapticctrl::mujoco
