#pragma once
/// @file panel.hpp
/// The full-screen operator panel (ncurses). It reads the regions at 10 Hz for display and
/// ramps the operator force at up to 500 Hz; it never waits on the controller, so it cannot
/// disturb the cycle. Keys: see panel_keys.hpp.
#include "hapticctrl/hmi/operator.hpp"

namespace hapticctrl::hmi {

/// How a panel session ended.
enum class PanelEnd {
  kQuit,                ///< the operator quit
  kControllerReplaced,  ///< the controller ended and a new one of the instance runs: re-attach
  kRestartRequested,    ///< the controller ended and the operator asked for a new one (R)
};

/// Runs the panel until the operator quits; releases the handle (ramps the force to zero)
/// before quitting. When the controller ends, the panel says why and when in reverse video
/// ("controller failed safe: <reason> at <time>") and waits: for a new controller of the
/// instance, for the operator's quit, or (offer_restart, when whoever started the panel can start
/// a core) for R. Needs a terminal (throws HmiError otherwise). Not real-time: a UI loop.
PanelEnd run_panel(Operator& op, bool offer_restart);

}  // namespace hapticctrl::hmi
