// The coupling's gains: derived from the object and the measured coupling loop, and how they
// follow that loop (ServoLaw::derive_gains, track_loop_delay, slew_gains; docs/control.md).
#include <algorithm>
#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"

#include "hapticctrl/base/realtime.hpp"

namespace hapticctrl::rt_core {
namespace {

/// Fraction of the explicit-integration stability bound (k < 4 m / T²) used for the derived
/// stiffness, and the damping ratio of the derived damping.
constexpr double kStiffnessFraction = 0.25;
constexpr double kDampingRatio = 0.7;
/// The loop-delay envelope follows the median of the recent samples up at once and down by this
/// share per new sample (about 200 samples, 0.2 s at 1 kHz): the gains drop as soon as the link
/// slows and rise back slowly. The median ignores single long loops (a lost answer makes the
/// client echo an older one): following each of them changed the stiffness under load, and
/// k * stretch stepped with it (the weighted sphere jiggled at 25 mm/s with 10 % loss, H1).
constexpr double kLoopDelayRelease = 0.005;
/// The loop delay is believed up to this; longer is a stale echo, not a loop.
constexpr Duration kMaxLoopDelay = std::chrono::seconds(2);
/// The gains are designed for a loop delay that follows the envelope only when the envelope
/// leaves a band around it (10 %, at least 0.5 ms), and they rise to a new design over a time
/// constant, not in one cycle: a spring that carries a weight is stretched (72 mm for the demo's
/// 0.5 kg sphere at 20 ms one way), so every change of k is a force step of k * stretch. With
/// +-2 ms jitter the envelope wandered by 1-2 ms around 42 ms and each move stepped the force by
/// 0.1-0.3 N: the sphere jiggled at 20-40 mm/s and the handle, resting on its joint wall, at up
/// to 8 mm/s (2026-12-02). A 10 % longer loop leaves the stiffness at most 21 % over its design,
/// inside the margin kStiffnessFraction keeps.
constexpr double kDesignDelayBand = 0.1;
constexpr Duration kDesignDelayBandMin = std::chrono::microseconds(500);
constexpr Duration kGainSlewTime = std::chrono::milliseconds(50);

HAPTICCTRL_RT double bounded(double value, double upper) noexcept {
  return std::clamp(value, 0.0, upper);
}

}  // namespace

CouplingGains ServoLaw::derive_gains(const ClientSample& c, double loop_delay) const noexcept {
  const ArmLimits& lim = dynamics_->model().limits;
  const double mass = c.object_mass > 0.0 ? c.object_mass : config_.default_object_mass;
  // The object sees the coupling's answer to its own motion a whole loop later (the answer's
  // way out, the client's hold, the sample's way back and its wait for the cycle: measured),
  // and its integration adds one client step: that lag bounds the stiffness it can take.
  const double client_step = c.time_step > 0.0 ? c.time_step : config_.default_time_step;
  const double step = client_step + std::max(0.0, loop_delay);
  // The angular coupling acts on every axis of the object: its smallest principal moment bounds
  // it (J3: a 19 mm x 60 mm MuJoCo peg, 3.3e-5 and 6e-6 kg.m^2, held with gains for its largest
  // moment, went unstable about its long axis in 0.27 s, 2026-12-05). Without a declared
  // inertia: a solid 5 cm sphere of the object's mass.
  double smallest_inertia = 0.0;
  for (const double moment : c.object_inertia) {
    smallest_inertia = moment > 0.0 && (smallest_inertia == 0.0 || moment < smallest_inertia)
                           ? moment
                           : smallest_inertia;
  }
  const double inertia = smallest_inertia > 0.0 ? smallest_inertia : 0.4 * mass * 0.05 * 0.05;
  CouplingGains g;
  g.k_linear = bounded(kStiffnessFraction * mass / (step * step), lim.max_stiffness_linear);
  g.b_linear = bounded(2.0 * kDampingRatio * std::sqrt(g.k_linear * mass),
                       std::min(lim.max_damping_linear, mass / step));
  g.k_angular = bounded(kStiffnessFraction * inertia / (step * step), lim.max_stiffness_angular);
  g.b_angular = bounded(2.0 * kDampingRatio * std::sqrt(g.k_angular * inertia),
                        std::min(lim.max_damping_angular, inertia / step));
  const auto& o = c.gain_override;
  if (o[0] > 0.0) {
    g.k_linear = bounded(o[0], lim.max_stiffness_linear);
  }
  if (o[1] > 0.0) {
    g.b_linear = bounded(o[1], lim.max_damping_linear);
  }
  if (o[2] > 0.0) {
    g.k_angular = bounded(o[2], lim.max_stiffness_angular);
  }
  if (o[3] > 0.0) {
    g.b_angular = bounded(o[3], lim.max_damping_angular);
  }
  return g;
}

void ServoLaw::track_loop_delay(const ServoInputs& in) noexcept {
  if (!in.new_sample) {
    return;
  }
  RenderMemory& m = memory_;
  m.loop_samples[m.loop_next % m.loop_samples.size()] =
      in.loop_delay > Duration{0} && in.loop_delay <= kMaxLoopDelay ? in.loop_delay
                                                                    : config_.assumed_loop_delay;
  ++m.loop_next;
  const std::size_t n = std::min<std::size_t>(m.loop_next, m.loop_samples.size());
  std::array<Duration, RenderMemory::kLoopSamples> sorted{};
  std::copy_n(m.loop_samples.begin(), n, sorted.begin());
  std::nth_element(sorted.begin(), sorted.begin() + static_cast<std::ptrdiff_t>(n / 2),
                   sorted.begin() + static_cast<std::ptrdiff_t>(n));
  const Duration measured = sorted[n / 2];
  Duration& envelope = m.loop_delay;
  if (measured >= envelope) {
    envelope = measured;
  } else {
    envelope -= std::chrono::duration_cast<Duration>((envelope - measured) * kLoopDelayRelease);
  }
  const Duration band = std::max(
      kDesignDelayBandMin, std::chrono::duration_cast<Duration>(m.design_delay * kDesignDelayBand));
  if (m.design_delay == Duration{0} || envelope > m.design_delay + band ||
      envelope < m.design_delay - band) {
    m.design_delay = envelope;
  }
}

CouplingGains ServoLaw::slew_gains(const CouplingGains& target, Duration dt) noexcept {
  // Softer at once (a slower loop is a stability matter), stiffer over kGainSlewTime.
  const double share = std::clamp(std::chrono::duration<double>(dt) / kGainSlewTime, 0.0, 1.0);
  const auto towards = [share](double& gain, double design) {
    gain = gain <= 0.0 || design <= gain ? design : gain + (design - gain) * share;
  };
  CouplingGains& g = memory_.gains;
  towards(g.k_linear, target.k_linear);
  towards(g.b_linear, target.b_linear);
  towards(g.k_angular, target.k_angular);
  towards(g.b_angular, target.b_angular);
  return g;
}

}  // namespace hapticctrl::rt_core
