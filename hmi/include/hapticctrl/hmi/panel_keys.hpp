#pragma once
/// @file panel_keys.hpp
/// The operator panel's keyboard, apart from the screen so that it is unit-tested: a key and
/// the panel's force state give an action and the new force state.
///
/// Keys: p power on, o power off, space or e emergency stop, r reset the emergency stop,
/// 1-6 choose the axis (fx fy fz tx ty tz), + and - push along / against it by the step,
/// [ and ] halve / double the step, 0 release the handle (zero wrench), S stop the controller
/// (asks y to confirm), q quit.
#include <cstddef>
#include <cstdint>

#include "hapticctrl/shm/ctrl.hpp"
#include "hapticctrl/shm/payloads.hpp"

namespace hapticctrl::hmi {

enum class PanelAction {
  kNone,
  kCommand,  ///< send `command`
  kForce,    ///< request the (changed) `wrench`
  kAskStop,  ///< ask to confirm the controller stop
  kQuit,
};

/// The panel's force state: the wrench requested and how the keys change it.
struct PanelForce {
  shm::Vector6 wrench{};
  std::size_t axis = 0;      ///< 0..5: fx fy fz tx ty tz
  double force_step = 2.0;   ///< N per key press
  double torque_step = 0.1;  ///< N.m per key press

  [[nodiscard]] double step() const noexcept { return axis < 3 ? force_step : torque_step; }
};

struct KeyResult {
  PanelAction action = PanelAction::kNone;
  shm::CtrlCode command = shm::CtrlCode::kNone;
};

/// What the panel tells the operator when a command key is pressed, given the controller's
/// state word (shm::state_bits) at that moment: what was asked, or why it cannot take effect
/// (it only said "sent" when power-on met a latched emergency stop, 2026-12-02).
[[nodiscard]] const char* command_feedback(shm::CtrlCode code, std::uint32_t state_word) noexcept;

/// Applies one key (an ncurses/ASCII code) to `force` and says what the panel must do.
/// Steps stay within [0.125, 32] N and [0.00625, 1.6] N.m; the wrench within `max_force` /
/// `max_torque` per axis. Allocation-free.
KeyResult apply_key(int key, PanelForce& force, double max_force, double max_torque) noexcept;

}  // namespace hapticctrl::hmi
