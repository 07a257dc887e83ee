#pragma once
/// @file panel.hpp
/// The full-screen operator panel (ncurses). It reads the regions at 10 Hz for display and
/// ramps the operator force at up to 500 Hz; it never waits on the controller, so it cannot
/// disturb the cycle. Keys: see panel_keys.hpp.
#include "hapticctrl/hmi/operator.hpp"

namespace hapticctrl::hmi {

/// Runs the panel until the operator quits or the controller goes away; releases the handle
/// (ramps the force to zero) before returning. Returns the process exit status. Needs a
/// terminal (throws HmiError otherwise).
int run_panel(Operator& op);

}  // namespace hapticctrl::hmi
