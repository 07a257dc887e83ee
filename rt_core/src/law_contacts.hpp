#pragma once
// What the servo law's contact parts share (servo_law_contact.cpp, servo_law_surface.cpp): when
// a contact counts as touching and how its weight fades when it stops coming. Internal.
#include <algorithm>

#include "hapticctrl/base/realtime.hpp"
#include "hapticctrl/rt_core/servo_law.hpp"

namespace hapticctrl::rt_core::law_contacts {

/// A contact counts as touching from this gap down (its stiffening comes in over it): the
/// object image arrives at the surface at the speed of the hand, and a stiffening switched on in
/// one cycle would step the force by k x its first penetration.
inline constexpr double kTouchBand = 1e-3;  // m

/// Share of the contact a slot still has after `silence` without a refresh: 1 while fresh,
/// falling linearly to 0 over the fade (a contact that stops coming fades as the link does).
HAPTICCTRL_RT inline double contact_weight(Duration silence, const LawConfig& config) noexcept {
  if (silence <= config.contact_fresh) {
    return 1.0;
  }
  const std::chrono::duration<double> left = config.contact_fresh + config.contact_fade - silence;
  return std::clamp(left / config.contact_fade, 0.0, 1.0);
}

}  // namespace hapticctrl::rt_core::law_contacts
