#pragma once
/// The object's side of the coupling, closed by the client library on the application's own
/// object state (protocol 1.3, HCP_FEATURE_LOCAL_COUPLING; docs/control.md). The controller
/// renders the handle's side of the spring-damper on its view of the object (which a link delay
/// late); here the object gets the other side on its current state and the handle as the newest
/// answer gives it, with the gains, contact stiffening and limits that answer reports. So the
/// object's own motion never comes back to it through the network: an object that rests on a
/// stiff surface in the application's physics is no longer driven by a damper that acts a loop
/// delay late (J1: a 5000 N/m wall with little damping chattered at 43 mm/s at 5 ms one way and
/// 167 mm/s at 10 ms; 0.2 and 0.4 mm/s with the object's side closed here, 2026-12-03).
///
/// Internal to the client library. Real-time contract: noexcept, no allocation; not
/// thread-safe (the connection serialises it).
#include "hapticctrl/client/types.hpp"
#include "hapticctrl_protocol.h"

namespace hapticctrl::client {

/// What an ANSWER_COUPLED says about the coupling, in the application's frame and units.
struct CouplingTerms {
  std::array<double, 4> gains{};           ///< k_lin, b_lin, k_ang, b_ang (controller units)
  std::array<double, 3> contact_normal{};  ///< client frame; zero: no contact stiffening
  std::array<double, 2> normal_gains{};    ///< stiffness, damping added along it
  std::array<double, 2> limits{};          ///< force, torque limits (controller units)
};

/// The terms of an ANSWER_COUPLED.
[[nodiscard]] CouplingTerms terms_of(const hcp_coupling_report& report,
                                     const hcp_local_coupling& local) noexcept;

/// The wrench on the object (client frame, the application's units): the coupling's spring and
/// damper between the object (`object_pose`, `object_twist`) and the handle image
/// (`handle_pose`, `handle_twist`), with the contact stiffening while the spring pushes the
/// object into the contact (on the handle's depth in the surface: the stretch plus the object's
/// own `penetration` into it, client metres), clamped to the limits. `speed_factor` and
/// `force_factor` turn the controller's units into the application's. Safe in a loop: no
/// allocation.
[[nodiscard]] Vector6 object_wrench(const CouplingTerms& terms, const Pose7& handle_pose,
                                    const Vector6& handle_twist, const Pose7& object_pose,
                                    const Vector6& object_twist, double penetration,
                                    double speed_factor, double force_factor) noexcept;

/// The object's wrench to apply: the controller's (`controller`, computed on its view of the
/// object a loop late), but while a contact is in force the library's own (`local`, on the
/// object's current state), in the share the answer gives (the contact normal's length). Held
/// by a surface (along its normal, and across it by static friction), an object whose own
/// motion comes back to it a loop late through the controller's damper chatters on it (a
/// 5000 N/m wall with little damping: 43 mm/s at 5 ms one way, 167 mm/s at 10 ms; 0.2 and 0.4
/// mm/s closed locally; closed locally along the normal only, friction held it across and it
/// still shook at 2 mm/s at 20 ms). Free, the object keeps the controller's wrench: closed
/// locally in every direction, the handle's own resonance (a 2 kg handle on a 2000 N/m spring,
/// 20 N.s/m) came back through the object and the demo's sphere pushed on the fixed one at a
/// 4 ms cycle shook at 0.35 m/s (2026-12-03). Without a contact, `controller` unchanged.
[[nodiscard]] Vector6 along_contact(const CouplingTerms& terms, const Vector6& controller,
                                    const Vector6& local) noexcept;

}  // namespace hapticctrl::client
