// Implements channel_passivity.hpp: the client library's end of the two-port time-domain
// passivity of the coupling channel (docs/control.md; Ryu, Artigas, Preusche).
#include "channel_passivity.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::client {
namespace {

/// A damper alpha on a mass m integrated at dt is stable for alpha dt / m < 1 (explicit); the PC
/// stays at half of that, with dt the time the application held the wrench (catch-up steps
/// included: a damper held over 20 steps as if over one drove the weighted sphere to 77 m/s at
/// 20 ms with 10 % loss, H1; bounded by the time between two sends alone, two sends 10 us apart
/// after a burst of answers let it reach 25 000 N.s/m on the demo's sphere, J1 2026-12-03).
constexpr double kDamperShare = 0.5;
/// Held by a contact, the damper may stop the object's step outright (alpha dt / m = 1: the
/// explicit integration's motion brought to rest, never reversed). With half of it, a hand
/// wandering on a 3000 N/m wall at 100 ms one way left the client's end 3.9 J over what the core
/// put in in 60 s; with all of it 0.40-0.77 J (bench/contact.sh, J1 2026-12-03: still open).
/// Along the object's motion only: a contact turns the object too (friction at its contact
/// point, a rolling patch), with terms the library does not see and that an application sets
/// near its own integration's bound. The demo's sphere on the fixed one at a 10 ms cycle (its
/// rolling spring at I / dt^2, damper at I / (2 dt)) rang at the step's Nyquist rate with the
/// whole damper on its rotation (+-0.23 N.m a step; the client's end put out 2.38-2.73 J for
/// the core's 0.22-0.31 J in, 3 runs of 3) and 0.31-0.40 J over with half of it (4 runs,
/// 2026-12-07).
constexpr double kContactDamperShare = 1.0;

double dot3(const Vector6& a, const Vector6& b, std::size_t from) noexcept {
  return a[from] * b[from] + a[from + 1] * b[from + 1] + a[from + 2] * b[from + 2];
}

}  // namespace

void ChannelPassivity::set_object(double mass, double inertia) noexcept {
  mass_ = mass > 0.0 ? mass : 0.5;
  inertia_ = inertia > 0.0 ? inertia : 0.4 * mass_ * 0.05 * 0.05;  // a 5 cm solid sphere
}

void ChannelPassivity::on_controller_energy(double joules) noexcept {
  if (std::isfinite(joules) && joules >= controller_in_) {
    controller_in_ = joules;  // cumulative: it never goes down within a session
  }
}

void ChannelPassivity::set_contact_share(double share) noexcept {
  contact_share_ = std::isfinite(share) ? std::clamp(share, 0.0, 1.0) : 0.0;
}

void ChannelPassivity::set_loop(double seconds) noexcept {
  loop_ = std::isfinite(seconds) && seconds > 0.0 ? from_seconds(seconds) : Duration::zero();
}

double ChannelPassivity::output_ago(TimePoint now) const noexcept {
  // The newest entry at or before now - loop; before the first entry there was no output (the
  // oldest kept once the ring is full and the loop longer than it).
  const TimePoint when = now - loop_;
  double found = 0.0;
  for (std::size_t k = 1; k <= std::min(past_count_, past_.size()); ++k) {
    const Past& p = past_[(past_next_ + past_.size() - k) % past_.size()];
    if (p.at <= when) {
      return p.out;
    }
    found = p.out;
  }
  return past_count_ >= past_.size() ? found : 0.0;
}

double ChannelPassivity::book_output(double power, double dt) noexcept {
  (power >= 0.0 ? energy_out_ : energy_in_) += std::abs(power) * dt;
  return energy_out_ - controller_in_;
}

Vector6 ChannelPassivity::render(const Vector6& wrench) noexcept {
  raw_ = wrench;
  Vector6 out = wrench;
  // Free, the damper removes at most the share of the wrench that does work on the object's
  // motion: it stops the channel's output without ever pushing against the motion itself (a
  // full damper held over the application's catch-up steps drove the weighted sphere to 77 m/s
  // at 20 ms with 10 % loss, H1; unbounded by that share, it shook the resting weighted sphere's
  // support between 1.4 and 7.4 N and the handle carried 6.4 N for its 4.9 N, J1 2026-12-03).
  // Held by a contact, it is whole, within the integration's bound alone (kContactDamperShare).
  // A cut of what it could not take, from the wrench along the last step's motion, turned the
  // object's next step by 90 degrees or more: a self-made dither of 2-20 mm/s against the wall
  // that the cut never caught, and the client's end gave 0.7-13 mJ more than the core put in on
  // 7 of 9 runs of the wandering hand at 10 ms one way; without it 4 of 4 balanced (J1
  // 2026-12-03; at 50-100 ms the cut did better, 0.22-0.26 J over, for 0.15-0.77 J without).
  for (std::size_t from = 0; from < 6; from += 3) {
    const double v_sq = dot3(twist_, twist_, from);
    const double working = v_sq > 1e-15 ? std::max(0.0, dot3(wrench, twist_, from) / v_sq) : 0.0;
    const double alpha = from == 0 ? alpha_linear_ : alpha_angular_;
    const double a = contact_share_ > 0.0 ? alpha : std::min(alpha, working);
    for (std::size_t i = from; i < from + 3; ++i) {
      out[i] -= a * twist_[i];
    }
  }
  rendered_ = out;
  return out;
}

void ChannelPassivity::on_step(const Vector6& twist, double dt, double held,
                               TimePoint now) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  held = std::isfinite(held) ? std::max(held, dt) : dt;
  // The channel's power into the object, with the channel's wrench (Ryu's observer); the PC's
  // damping is booked apart: what it took leaves the output account.
  double power = 0.0;
  double damped = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    power += raw_[i] * twist[i];
    damped += (raw_[i] - rendered_[i]) * twist[i];
  }
  if (!std::isfinite(power) || !std::isfinite(damped)) {
    return;
  }
  book_output(power, dt);
  energy_out_ -= damped * dt;
  dissipated_ += damped * dt;
  past_[past_next_] = {now, energy_out_ + dissipated_};
  past_next_ = (past_next_ + 1) % past_.size();
  ++past_count_;
  // The controller's report covers the object's motion up to a loop ago (the object's state went
  // out, the controller took it, its answer came back): compared with the output of now, every
  // push into a wall looked like a loop's worth of excess, and the PC chattered the object's
  // wrench between 0 and 12 N at 100 ms one way (J1, 2026-12-03).
  const double excess = output_ago(now) - dissipated_ - controller_in_;
  twist_ = twist;
  alpha_linear_ = 0.0;
  alpha_angular_ = 0.0;
  const double lin_sq = dot3(twist, twist, 0);
  const double ang_sq = dot3(twist, twist, 3);
  if (excess > 0.0 && lin_sq + ang_sq > 1e-15) {
    // The damper for the next step: enough to dissipate the excess at this motion, within what
    // the object's integration bears. (H1 also bounded it by the coupling's own damping; with
    // the spring re-anchored after a blackout, that let the weighted sphere's handle fall back at
    // 0.23-0.36 m/s, J1 2026-12-03.)
    const double alpha = excess / ((lin_sq + ang_sq) * dt);
    const double share = contact_share_ > 0.0 ? kContactDamperShare : kDamperShare;
    alpha_linear_ = std::min(alpha, share * mass_ / held);
    alpha_angular_ = std::min(alpha, kDamperShare * inertia_ / held);
    ++active_steps_;
  }
}

void ChannelPassivity::on_image_step(const Vector6& wrench, const Vector6& flow,
                                     double dt) noexcept {
  drift_rate_ = {};
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  // The channel gives this end power when the handle image moves against the application's
  // wrench (-wrench . flow > 0: it compresses the application's wall, say).
  const double power = -(dot3(wrench, flow, 0) + dot3(wrench, flow, 3));
  const double force_sq = dot3(wrench, wrench, 0) + dot3(wrench, wrench, 3);
  if (!std::isfinite(power) || !std::isfinite(force_sq)) {
    return;
  }
  const double excess = book_output(power, dt);
  Vector6 rate{};
  if (excess > 0.0 && force_sq > 1e-12) {
    // The image gives way along the wrench, as fast as dissipates the excess in one step.
    for (std::size_t i = 0; i < 6; ++i) {
      rate[i] = wrench[i] * excess / (dt * force_sq);
    }
    ++active_steps_;
  } else if (excess < 0.0) {
    // Give the drift back, slowly (2 cm/s, 0.2 rad/s), within the budget: it costs energy.
    for (std::size_t from = 0; from < 6; from += 3) {
      const double norm = std::sqrt(dot3(drift_, drift_, from));
      const double speed = from == 0 ? 0.02 : 0.2;
      const double share = norm > 0.0 ? std::min(norm / dt, speed) / norm : 0.0;
      for (std::size_t i = from; i < from + 3; ++i) {
        rate[i] = -drift_[i] * share;
      }
    }
    const double cost = -(dot3(wrench, rate, 0) + dot3(wrench, rate, 3)) * dt;
    if (cost > -excess) {
      for (double& r : rate) {
        r *= -excess / cost;
      }
    }
  }
  double dissipated = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    dissipated += wrench[i] * rate[i] * dt;
    drift_[i] += rate[i] * dt;
  }
  drift_rate_ = rate;
  energy_out_ -= dissipated;  // dissipated (> 0) or given back (< 0)
}

std::uint32_t ChannelPassivity::energy_in_uj() const noexcept {
  const double uj = std::fmod(std::floor(energy_in_ * 1e6), 4294967296.0);
  return static_cast<std::uint32_t>(uj);
}

}  // namespace hapticctrl::client
