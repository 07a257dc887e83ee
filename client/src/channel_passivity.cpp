// Implements channel_passivity.hpp: the client library's end of the two-port time-domain passivity
// of the coupling channel (docs/control.md; Ryu, Artigas, Preusche).
#include "channel_passivity.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::client {
namespace {

/// A damper alpha on a mass m integrated at dt is stable for alpha dt / m < 1 (explicit); the PC
/// stays at half of that.
constexpr double kDamperShare = 0.5;

/// The damper the PC may add: what it wants, within the integration's bound and, when the
/// controller reports one, the coupling's own damping. Taking the whole working share at once
/// (up to m / 2 dt = 250 N·s/m for the demo's sphere) removed the 5.9 N that held the weighted
/// sphere whenever it rose by a few mm/s; the PC kept the force chattering between 0 and 6 N, the
/// sphere at 20-40 mm/s and the handle on its joint wall at up to 8 mm/s (20 ms one way, +-2 ms
/// jitter, 10 % loss, 2026-12-02). Within the coupling's damping it settles to 1 mm/s in 1.5 s
/// and dissipates the excess over a few steps instead of one.
double bounded(double wanted, double integration, double coupling) noexcept {
  const double bound = coupling > 0.0 ? std::min(integration, coupling) : integration;
  return std::min(wanted, bound);
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

void ChannelPassivity::on_coupling_damping(double linear, double angular) noexcept {
  coupling_linear_ = std::isfinite(linear) && linear > 0.0 ? linear : 0.0;
  coupling_angular_ = std::isfinite(angular) && angular > 0.0 ? angular : 0.0;
}

void ChannelPassivity::set_force_factor(double factor) noexcept {
  force_factor_ = std::isfinite(factor) && factor > 0.0 ? factor : 1.0;  // as the core reads it
}

void ChannelPassivity::set_speed_factor(double factor) noexcept {
  speed_factor_ = std::isfinite(factor) && factor > 0.0 ? factor : 1.0;
}

double ChannelPassivity::book(double power, double dt) noexcept {
  (power >= 0.0 ? energy_in_ : energy_out_) += std::abs(power) * dt;
  return energy_out_ - controller_in_;
}

double ChannelPassivity::on_image_step(const Vector6& force, const Vector6& flow,
                                       const Vector6& stretch, double dt) noexcept {
  drift_rate_ = {};
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return 0.0;
  }
  double power = 0.0;
  double force_sq = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    power += force[i] * flow[i];
    force_sq += force[i] * force[i];
  }
  if (!std::isfinite(power) || !std::isfinite(force_sq)) {
    return 0.0;
  }
  const double excess = book(power, dt);
  Vector6 rate{};
  if (excess > 0.0) {
    ++active_steps_;
    if (force_sq > 1e-12) {
      // The image gives way along the client's force, as fast as dissipates the excess in one
      // step, no further than relaxing the object's spring (a stretch of zero: no bound).
      for (std::size_t i = 0; i < 6; ++i) {
        rate[i] = force[i] * excess / (dt * force_sq);
      }
      for (std::size_t from = 0; from < 6; from += 3) {
        double moved = 0.0;
        double room = 0.0;
        for (std::size_t i = from; i < from + 3; ++i) {
          moved += rate[i] * rate[i];
          room += stretch[i] * stretch[i];
        }
        moved = std::sqrt(moved) * dt;
        room = std::sqrt(room);
        if (room > 0.0 && moved > room) {
          for (std::size_t i = from; i < from + 3; ++i) {
            rate[i] *= room / moved;
          }
        }
      }
    }
  } else {
    // Give the drift back, slowly (2 cm/s, 0.2 rad/s), within the budget: it costs energy.
    double cost = 0.0;
    for (std::size_t from = 0; from < 6; from += 3) {
      const double speed = from == 0 ? 0.02 : 0.2;
      double norm = 0.0;
      for (std::size_t i = from; i < from + 3; ++i) {
        norm += drift_[i] * drift_[i];
      }
      norm = std::sqrt(norm);
      const double step = norm > 0.0 ? std::min(norm / dt, speed) / norm : 0.0;
      for (std::size_t i = from; i < from + 3; ++i) {
        rate[i] = -drift_[i] * step;
        cost -= force[i] * rate[i] * dt;
      }
    }
    if (cost > -excess && cost > 0.0) {
      for (double& r : rate) {
        r *= -excess / cost;
      }
    }
  }
  double dissipated = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    dissipated += force[i] * rate[i] * dt;
    drift_[i] += rate[i] * dt;
  }
  drift_rate_ = rate;
  energy_out_ -= dissipated;
  return std::max(0.0, excess - std::max(0.0, dissipated));
}

void ChannelPassivity::on_cut(double joules) noexcept {
  if (std::isfinite(joules) && joules > 0.0) {
    energy_out_ -= joules;
  }
}

Vector6 ChannelPassivity::render(const Vector6& wrench) noexcept {
  raw_ = wrench;
  Vector6 out = wrench;
  // The damper removes at most the share of the wrench that does work on the object's motion:
  // it stops the channel's output without ever pushing against the motion itself. A full damper
  // held over the application's catch-up steps (the demo integrates several cycles with one
  // wrench after a lost answer) drove the weighted sphere to 77 m/s at 20 ms with 10 % loss.
  const auto limited = [&](std::size_t from, double alpha) {
    double along = 0.0;
    double v_sq = 0.0;
    for (std::size_t i = from; i < from + 3; ++i) {
      along += wrench[i] * twist_[i];
      v_sq += twist_[i] * twist_[i];
    }
    const double working = v_sq > 1e-15 ? std::max(0.0, along / v_sq) : 0.0;
    const double a = std::min(alpha, working);
    for (std::size_t i = from; i < from + 3; ++i) {
      out[i] -= a * twist_[i];
    }
  };
  limited(0, alpha_linear_);
  limited(3, alpha_angular_);
  rendered_ = out;
  return out;
}

void ChannelPassivity::on_step(const Vector6& twist, double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  // The channel's power into the object, with the controller's wrench (Ryu's observer); the
  // PC's damper is booked apart: what it took leaves the output account.
  double power = 0.0;
  double damped = 0.0;
  double v_sq = 0.0;
  double w_sq = 0.0;
  for (std::size_t i = 0; i < 6; ++i) {
    power += raw_[i] * twist[i];
    damped += (raw_[i] - rendered_[i]) * twist[i];
    (i < 3 ? v_sq : w_sq) += twist[i] * twist[i];
  }
  if (!std::isfinite(power) || !std::isfinite(damped)) {
    return;
  }
  (power >= 0.0 ? energy_out_ : energy_in_) += std::abs(power) * dt;
  energy_out_ -= damped * dt;
  twist_ = twist;
  alpha_linear_ = 0.0;
  alpha_angular_ = 0.0;
  // The damper for the next step: enough to dissipate the excess at this motion, within the
  // bounds the object's integration bears.
  const double excess = energy_out_ - controller_in_;
  const double motion = (v_sq + w_sq) * dt;
  if (excess > 0.0 && motion > 1e-15) {
    const double alpha = excess / motion;
    alpha_linear_ = bounded(alpha, kDamperShare * mass_ / dt,
                            coupling_linear_ / (force_factor_ * speed_factor_));
    alpha_angular_ =
        bounded(alpha, kDamperShare * inertia_ / dt, coupling_angular_ / force_factor_);
    ++active_steps_;
  }
}

std::uint32_t ChannelPassivity::energy_in_uj() const noexcept {
  const double uj = std::fmod(std::floor(energy_in_ * 1e6), 4294967296.0);
  return static_cast<std::uint32_t>(uj);
}

}  // namespace hapticctrl::client
