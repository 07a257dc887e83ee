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
/// The share of the object's own step bound a contact's hold of its rotation takes (a quarter of
/// the free design's): the application's own contact terms share that step. The demo's sphere on
/// the fixed one at a 10 ms step (its rolling patch at half the bound, the library's passivity
/// damper at half) rang at the step's Nyquist rate with the hold at the free design's quarter
/// (+-0.2 N.m a step; the client's end put out 3.9-4.3 J for the core's 0.02 J, 2026-12-08).
constexpr double kHoldFraction = kStiffnessFraction * kStiffnessFraction;
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

/// The object's smallest principal moment (it bounds the angular coupling on every axis);
/// without a declared inertia, a solid 5 cm sphere of its mass.
HAPTICCTRL_RT double smallest_moment(const ClientSample& c, double mass) noexcept {
  double smallest = 0.0;
  for (const double moment : c.object_inertia) {
    smallest = moment > 0.0 && (smallest == 0.0 || moment < smallest) ? moment : smallest;
  }
  return smallest > 0.0 ? smallest : 0.4 * mass * 0.05 * 0.05;
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
  // moment, went unstable about its long axis in 0.27 s, 2026-12-05).
  const double inertia = smallest_moment(c, mass);
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

ContactHold ServoLaw::contact_hold(const ClientSample& c, const CouplingGains& free,
                                   double share, double period) const noexcept {
  // In contact, a rotation held by the loop's gains alone lets the contact turn the object: a
  // peg pushed 3 N down with its edge on a chamfer got 0.03-0.06 N.m from it against the
  // coupling's 0.009 N.m/rad and tipped over at 5 ms one way (J3, 2026-12-08). A client that
  // closes its object's side itself (protocol 1.3) tracks the handle's delayed rotation with
  // its own step in the loop, not the network's: there the object's step bounds the gain. On the
  // handle's side the spring pulls towards the object, which follows the handle a loop late; an
  // angular damper on the handle (the device's, B) keeps that loop's gain below 1 at every
  // frequency, whatever the delay, while k < B^2 / (2 (I_handle + I_object)) (the handle a rotor
  // inertia, the object a follower: |L(jw)| < 1 for all w > 0; docs/control.md). Only one side
  // raised (the object's, 2026-12-08, taken back), the object was pressed into its surfaces with
  // torques the hand never paid: the lifted weight felt 9.2 N for 7.85 N.
  ContactHold hold;
  hold.gains = free;
  if (!c.local_coupling || !(share > 0.0) || c.gain_override[2] > 0.0) {
    return hold;  // not closed by the client, not in contact, or the client's own gain
  }
  const ArmModel& model = dynamics_->model();
  const ArmLimits& lim = model.limits;
  const double mass = c.object_mass > 0.0 ? c.object_mass : config_.default_object_mass;
  const double step = c.time_step > 0.0 ? c.time_step : config_.default_time_step;
  const double object = smallest_moment(c, mass);
  double handle = 0.0;  // the wrist's rotors: the least the handle's rotation carries
  for (std::size_t j = 3; j < model.joints.size(); ++j) {
    const double rotor = model.joints[j].rotor_inertia;
    handle = handle == 0.0 ? rotor : std::min(handle, rotor);
  }
  if (!(handle > 0.0) || !(period > 0.0)) {
    return hold;
  }
  // A damper sampled at the period is stable well inside I / T.
  const double damper = std::min(lim.max_damping_angular, 0.5 * handle / period);
  const double k = std::min({kHoldFraction * object / (step * step),
                             damper * damper / (2.0 * (handle + object)),
                             lim.max_stiffness_angular});
  if (!(k > free.k_angular)) {
    return hold;
  }
  const double b = bounded(2.0 * kDampingRatio * std::sqrt(k * object),
                           std::min(lim.max_damping_angular, object / step));
  const double s = std::min(1.0, share);
  hold.gains.k_angular += s * (k - free.k_angular);
  hold.gains.b_angular += s * std::max(0.0, b - free.b_angular);
  hold.handle_damping = s * damper;
  hold.share = s;
  return hold;
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
