// Implements hand_motion.hpp: a simulated operator's hand for `hapticctrl-hmi play --hand`: a
// spring-damper grip (shm::HandGrip) with an optional wrist, its anchor wandering at random.
#include "hapticctrl/hmi/hand_motion.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include "hapticctrl/shm/force_slew.hpp"

namespace hapticctrl::hmi {
namespace {

constexpr double kLowestHz = 0.2;
constexpr double kHighestHz = 2.0;
constexpr double kMaxWander = 0.1;     ///< m: a hand's wander, well inside the workspace
constexpr double kWanderFadeIn = 1.0;  ///< s

/// Smooth 0 -> 1 over [0, 1] (and its derivative): the wander starts at rest.
double smoothstep(double x) noexcept {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}
double smoothstep_rate(double x) noexcept {
  return x <= 0.0 || x >= 1.0 ? 0.0 : 6.0 * x * (1.0 - x);
}

}  // namespace

HandMotion::HandMotion(const HandOptions& options, const std::array<double, 3>& grip_point,
                       const std::array<double, 4>& grip_rotation)
    : options_(options), grip_point_(grip_point), grip_rotation_(grip_rotation) {
  shm::HandGrip full;
  full.anchor = grip_point;
  full.stiffness = options.stiffness;
  full.damping = options.damping;
  full.anchor_rotation = grip_rotation;
  full.angular_stiffness = options.angular_stiffness;
  full.angular_damping = options.angular_damping;
  if (!shm::hand_acceptable(full)) {
    throw std::invalid_argument(
        "the hand's stiffness must be within 0..3000 N/m, its damping within 0..100 N.s/m, its "
        "wrist's within 0..30 N.m/rad and 0..1 N.m.s/rad, and the handle within 2 m of the base");
  }
  if (!(options.wander >= 0.0 && options.wander <= kMaxWander)) {
    throw std::invalid_argument("the hand's wander must be within 0..0.1 m");
  }
  std::mt19937_64 random(options.seed);
  std::uniform_real_distribution<double> phase(0.0, 2.0 * std::numbers::pi);
  for (auto& axis : sines_) {
    for (int k = 0; k < kSines; ++k) {
      const double hz =
          kLowestHz * std::pow(kHighestHz / kLowestHz, static_cast<double>(k) / (kSines - 1));
      axis[static_cast<std::size_t>(k)] = {options.wander / kSines, 2.0 * std::numbers::pi * hz,
                                           phase(random)};
    }
  }
}

shm::HandGrip HandMotion::at(double t) const noexcept {
  t = std::max(t, 0.0);
  shm::HandGrip g;
  const double grip = smoothstep(t / kGripRamp);
  g.stiffness = grip * options_.stiffness;
  g.damping = grip * options_.damping;
  g.anchor_rotation = grip_rotation_;
  g.angular_stiffness = grip * options_.angular_stiffness;
  g.angular_damping = grip * options_.angular_damping;
  const double fade = smoothstep(t / kWanderFadeIn);
  const double fade_rate = smoothstep_rate(t / kWanderFadeIn) / kWanderFadeIn;
  for (std::size_t axis = 0; axis < 3; ++axis) {
    double offset = 0.0;
    double rate = 0.0;
    for (const Sine& s : sines_[axis]) {
      offset += s.amplitude * std::sin(s.omega * t + s.phase);
      rate += s.amplitude * s.omega * std::cos(s.omega * t + s.phase);
    }
    g.anchor[axis] = grip_point_[axis] + fade * offset;
    g.anchor_velocity[axis] = fade * rate + fade_rate * offset;
  }
  return g;
}

}  // namespace hapticctrl::hmi
