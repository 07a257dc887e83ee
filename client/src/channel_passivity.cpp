#include "channel_passivity.hpp"

#include <algorithm>
#include <cmath>

namespace hapticctrl::client {
namespace {

/// A damper alpha on a mass m integrated at dt is stable for alpha dt / m < 1 (explicit); the PC
/// stays at half of that.
constexpr double kDamperShare = 0.5;

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

Vector6 ChannelPassivity::render(const Vector6& wrench) noexcept {
  Vector6 out = wrench;
  for (std::size_t i = 0; i < 3; ++i) {
    out[i] -= alpha_linear_ * twist_[i];
    out[i + 3] -= alpha_angular_ * twist_[i + 3];
  }
  rendered_ = out;
  return out;
}

void ChannelPassivity::on_step(const Vector6& twist, double dt) noexcept {
  if (!(dt > 0.0) || !std::isfinite(dt)) {
    return;
  }
  double power = 0.0;  // from the channel into the object
  double v_sq = 0.0;
  double w_sq = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    power += rendered_[i] * twist[i] + rendered_[i + 3] * twist[i + 3];
    v_sq += twist[i] * twist[i];
    w_sq += twist[i + 3] * twist[i + 3];
  }
  if (!std::isfinite(power)) {
    return;
  }
  (power >= 0.0 ? energy_out_ : energy_in_) += std::abs(power) * dt;
  twist_ = twist;
  alpha_linear_ = 0.0;
  alpha_angular_ = 0.0;
  // The damper the next step adds would dissipate (alpha_l v^2 + alpha_a w^2) dt at this
  // motion: enough for the excess, within the stable bounds. Its real effect is counted by the
  // next step's power, which includes it (rendered_).
  const double excess = energy_out_ - controller_in_;
  const double motion = (v_sq + w_sq) * dt;
  if (excess > 0.0 && motion > 1e-15) {
    const double alpha = excess / motion;
    alpha_linear_ = std::min(alpha, kDamperShare * mass_ / dt);
    alpha_angular_ = std::min(alpha, kDamperShare * inertia_ / dt);
    ++active_steps_;
  }
}

std::uint32_t ChannelPassivity::energy_in_uj() const noexcept {
  const double uj = std::fmod(std::floor(energy_in_ * 1e6), 4294967296.0);
  return static_cast<std::uint32_t>(uj);
}

void ChannelPassivity::reset() noexcept {
  const double mass = mass_;
  const double inertia = inertia_;
  *this = ChannelPassivity{};
  mass_ = mass;
  inertia_ = inertia;
}

}  // namespace hapticctrl::client
