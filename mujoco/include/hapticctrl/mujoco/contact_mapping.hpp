#pragma once
/// @file contact_mapping.hpp
/// MuJoCo's soft contacts as the controller's local contact model (protocol 1.3, J2): the spring
/// and the damper a hand feels when it pushes the coupled body into a surface.
///
/// MuJoCo gives each contact constraint rows (one, or 2 (condim - 1) pyramid edges) with a
/// reference acceleration aref = -b v - k d r and a regulariser R = (1 - d) / d * A, A the
/// row's approximate inverse inertia (MuJoCo's diagApprox: the two bodies' translational
/// inverse weights, times 1 + mu^2 on a pyramid edge); the row's force at rest is aref / R.
/// So a push F held by the surface at depth r gives, summed over the rows of the contacts the
/// surface holds the body with,
///   K = sum rows  d^2 / (1 - d) * k / A,   B = sum rows  d / (1 - d) * b / A,
/// with, from solref (timeconst, dampratio) > 0: k = 1 / (dmax^2 timeconst^2 dampratio^2),
/// b = 2 / (dmax timeconst), the time constant at least two steps (MuJoCo's refsafe); from
/// solref < 0 (-stiffness, -damping): k = stiffness / dmax^2, b = damping / dmax; d is solimp's
/// dmin, the impedance where the hand meets the surface (it grows to dmax over solimp's width).
/// Checked against the engine: a box settling on a table sinks m g / K (tests/mujoco). A box
/// on four corners is four times as stiff as on one: MuJoCo's contacts are, and so is its
/// report. The controller clamps K to what the arm renders.
///
/// Nothing here reads a clock or allocates: pure functions, safe anywhere.
#include <array>
#include <cstddef>
#include <span>

#include "hapticctrl/client/types.hpp"

namespace hapticctrl::mujoco {

/// A surface's or a contact's spring and damper along its normal.
struct SurfaceGains {
  double stiffness = 0.0;  ///< N/m
  double damping = 0.0;    ///< N.s/m
};

/// One MuJoCo contact of the coupled body, copied out of mjContact and the model so that the
/// mapping is tested without them.
struct EngineContact {
  double distance = 0.0;             ///< mjContact.dist: < 0 penetrating [m]
  std::array<double, 3> midpoint{};  ///< mjContact.pos: between the two surfaces [m]
  std::array<double, 3> normal{};    ///< mjContact.frame[0..2]: from geom1 toward geom2
  bool body_is_geom2 = true;         ///< which side the coupled body is on
  int condim = 3;                    ///< mjContact.dim
  bool pyramidal = true;             ///< the model's friction cone (opt.cone)
  std::array<double, 5> friction{};  ///< mjContact.friction: 2 sliding, spin, 2 rolling
  /// The two bodies' translational inverse weights summed (model body_invweight0) [1/kg].
  double inverse_weight = 0.0;
  std::array<double, 2> solref{};  ///< mjContact.solref
  std::array<double, 5> solimp{};  ///< mjContact.solimp
};

/// K and B of one contact (all its rows) at the model's `timestep` (s). Invalid or degenerate
/// parameters (dmin outside (0, 1), a zero time constant or weight) give zero gains.
[[nodiscard]] SurfaceGains contact_gains(const EngineContact& c, double timestep) noexcept;

/// The contacts in the client's terms, in their order (at most out.size()): the point on the
/// coupled body, the normal along which the surface pushes the body, the gap; each with the
/// stiffness and damping of its whole surface (the contacts whose normals are within 10 degrees
/// of its own), stiffness clamped to `max_stiffness` (> 0: the controller's limit,
/// LinkStatistics::max_contact_stiffness), friction the sliding coefficient within the
/// protocol's 0..10. Contacts with zero gains are left out. Returns the count written.
std::size_t to_client_contacts(std::span<const EngineContact> in, double timestep,
                               double max_stiffness, std::span<client::Contact> out) noexcept;

}  // namespace hapticctrl::mujoco
