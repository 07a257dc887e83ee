#pragma once
/// @file hand_motion.hpp
/// A simulated operator's hand for `hapticctrl-hmi play --hand`: a spring-damper grip
/// (shm::HandGrip) whose anchor starts where the handle is and, with a wander amplitude, moves
/// at random - the "random hand motion" of the coupling benchmark (H1); an optional wrist holds
/// the handle's rotation where the grip found it. Per axis the anchor's offset is a sum of
/// sines at log-spaced frequencies over 0.2-2 Hz (a hand's voluntary band) with seeded random
/// phases, so a run is reproducible; its peak stays within the amplitude and it fades in over
/// the first second. The grip's and the wrist's gains ramp in and out (no force step when the
/// hand takes or lets go). Not for the cycle: plain value code.
#include <array>
#include <cstdint>

#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::hmi {

struct HandOptions {
  double stiffness = 300.0;  ///< N/m (a relaxed grip)
  double damping = 5.0;      ///< N.s/m
  double wander = 0.0;       ///< m, peak offset of the anchor per axis (0: the hand holds still)
  std::uint64_t seed = 1;
  double angular_stiffness = 0.0;  ///< N.m/rad (0 and 0: no wrist, the handle turns freely)
  double angular_damping = 0.0;    ///< N.m.s/rad
};

class HandMotion {
 public:
  /// Sines per axis.
  static constexpr int kSines = 5;
  /// How long the grip takes to reach its stiffness and damping, and to let go (s).
  static constexpr double kGripRamp = 0.2;

  /// A hand gripping the handle at `grip_point` (base frame, m), its wrist holding
  /// `grip_rotation` (base frame, quaternion x y z w). Throws std::invalid_argument for a grip
  /// or wander out of range (shm::ForceLimits; wander within 0..0.1 m).
  HandMotion(const HandOptions& options, const std::array<double, 3>& grip_point,
             const std::array<double, 4>& grip_rotation = {0, 0, 0, 1});

  /// The grip `t` seconds after it started.
  [[nodiscard]] shm::HandGrip at(double t) const noexcept;

 private:
  struct Sine {
    double amplitude = 0.0;  ///< m
    double omega = 0.0;      ///< rad/s
    double phase = 0.0;      ///< rad
  };

  HandOptions options_;
  std::array<double, 3> grip_point_;
  std::array<double, 4> grip_rotation_;
  std::array<std::array<Sine, kSines>, 3> sines_{};
};

}  // namespace hapticctrl::hmi
