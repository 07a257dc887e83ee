// Tests of servo_law_surface.cpp: the surfaces rendered on the handle (J2): an IMPEDANCE
// client's surface in place of its push out of it, a surface found with the handle inside, a
// plane that jumps, friction, and several surfaces at once.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "support/law_inputs.hpp"
#include "support/law_runs.hpp"

namespace hapticctrl::rt_core {
namespace {

using test::chain_at;
using test::default_dynamics;
using test::ForceTrace;
using test::impedance_on_surface;
using test::kReady;
using test::press_along_x;
using test::run_on_contacts;

/// Adds to `in` a frictionless 2000 N/m surface of the same client whose normal is `normal`,
/// with the handle's point `depth` (m) inside it (< 0: outside).
void add_plane(ServoInputs& in, const Vector3d& normal, double depth) {
  const Vector3d handle = chain_at(in.measures.position).handle_position;
  const Vector3d point = handle + depth * normal.normalized();
  ClientContact& c = in.client.contacts[in.client.contact_count++];
  c.point = {point.x(), point.y(), point.z()};
  const Vector3d n = normal.normalized();
  c.normal = {n.x(), n.y(), n.z()};
  c.stiffness = 2000.0;
  c.friction = {0.0, 0.0};
}

/// The force along x over `cycles` cycles of a hand held still that felt `felt` before them.
ForceTrace held_still(ServoLaw& law, ServoInputs& in, double felt, int cycles) {
  ForceTrace trace;
  trace.add(felt, true);
  for (int k = 0; k < cycles; ++k) {
    trace.add(run_on_contacts(law, in, 1).rendered_wrench.x(), false);
  }
  return trace;
}

/// An IMPEDANCE client that reports no surface yet and pushes nothing.
ServoInputs impedance_client() {
  ServoInputs in = impedance_on_surface(0.0, 0.0);
  in.client.contact_count = 0;
  return in;
}

/// A surface whose normal is 30 degrees off -x, toward -z: a hand pressed d along x is d cos 30
/// deep in it, and it pushes back along its normal.
const Vector3d kSlanted(-std::cos(0.5236), 0.0, -std::sin(0.5236));

TEST(ServoLawSurface, AnImpedanceSurfaceIsRenderedHereInPlaceOfTheClientsPushOutOfIt) {
  // The client's own push out of the surface (-7 N, a loop late) gives way to the surface
  // rendered at the servo rate: 2000 N/m x 5 mm.
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_on_surface(0.0, -7.0);
  run_on_contacts(law, in, 100);
  const double depth = press_along_x(law, in, 0.005);
  ServoOutputs out = run_on_contacts(law, in, 200);
  EXPECT_NEAR(out.rendered_wrench.x(), -2000.0 * depth, 0.05)
      << "the surface, not the client's too";
  EXPECT_EQ(out.contacts, 1U);
  EXPECT_NEAR(out.normal_stiffness, 2000.0, 1e-9);

  ServoLaw pressing_law(default_dynamics());
  ServoInputs pressing = impedance_on_surface(0.0, 3.0);  // the client pushes into it
  run_on_contacts(pressing_law, pressing, 100);
  const double pressed = press_along_x(pressing_law, pressing, 0.005);
  out = run_on_contacts(pressing_law, pressing, 200);
  EXPECT_NEAR(out.rendered_wrench.x(), -2000.0 * pressed + 3.0, 0.05)
      << "a push into the surface stays";
}

TEST(ServoLawSurface, ASurfaceFoundWithTheHandleInsideIsRenderedFromWhereTheHandleIs) {
  // Reported a loop late (or moved onto the handle), a surface found with the handle 5 mm inside
  // is no step and puts no energy out: a 2000 N/m wall whose first report found the handle 7 cm
  // deep kicked it out at 35 N (100 ms one way, 2026-12-03); given back on time alone, the
  // hidden 5 mm would have pushed a still hand out with 25 mJ it never put in (J2).
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_on_surface(0.005, -7.0);
  ForceTrace trace;
  for (int k = 0; k < 300; ++k) {
    trace.add(run_on_contacts(law, in, 1).rendered_wrench.x(), k == 0);
  }
  EXPECT_LT(std::abs(trace.least), 0.05) << "held still, nothing comes back";
  EXPECT_LT(std::abs(trace.most), 0.05);
  EXPECT_GE(law.counters().surface_updates_held, 1U);
  const double depth = press_along_x(law, in, 0.002);
  EXPECT_NEAR(run_on_contacts(law, in, 100).rendered_wrench.x(), -2000.0 * depth, 0.05)
      << "pressed 2 mm further, the surface from where the handle met it";
}

TEST(ServoLawSurface, APlaneThatJumpsIntoTheHandleStepsNothingAndOneThatLeavesLetsGo) {
  // J2's model update: the client's surface comes 5 mm toward the handle pressing 10 N on it.
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_on_surface(0.0, 0.0);
  run_on_contacts(law, in, 100);
  const double depth = press_along_x(law, in, 0.005);
  ASSERT_NEAR(run_on_contacts(law, in, 200).rendered_wrench.x(), -2000.0 * depth, 0.05);
  in.client.contacts[0].point[0] -= 0.005;  // 5 mm into the handle
  const ForceTrace trace = held_still(law, in, -2000.0 * depth, 300);
  EXPECT_LT(trace.largest_step, 1.0) << "N per 1 ms cycle";
  EXPECT_NEAR(trace.least, -2000.0 * depth, 0.05) << "the still hand feels what it felt";
  EXPECT_NEAR(trace.most, -2000.0 * depth, 0.05);
  ServoOutputs out = run_on_contacts(law, in, 1);
  EXPECT_NEAR(out.surface_hidden, 0.005, 1e-6) << "telemetry: the jump held back";
  EXPECT_NEAR(out.surface_withheld, 2000.0 * 0.005 * (depth + 0.0025), 1e-4)
      << "J: what the jump would have stored in the spring at once";
  in.client.contacts[0].point[0] += 0.008;  // then 8 mm away: 2 mm of the 5 are left
  EXPECT_NEAR(run_on_contacts(law, in, 50).rendered_wrench.x(), -2000.0 * (depth - 0.003), 0.05);
}

TEST(ServoLawSurface, FrictionHoldsTheHandleWithinTheConeAndSlidesBeyondIt) {
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_on_surface(0.0, 0.0);
  run_on_contacts(law, in, 100);
  const double depth = press_along_x(law, in, 0.005);
  run_on_contacts(law, in, 200);  // 10 N into the surface
  // Turning the first joint moves the handle's point along y, on the surface.
  const double reach = chain_at(kReady).handle_position.head<2>().norm();
  in.measures.position[0] += 0.0005 / reach;  // 0.5 mm
  ServoOutputs out = run_on_contacts(law, in, 20);
  EXPECT_NEAR(out.rendered_wrench.y(), -2000.0 * 0.0005, 0.1) << "sticking: 1 N back";
  in.measures.position[0] += 0.01 / reach;  // 1 cm more: past mu_s x 10 N = 5 N
  out = run_on_contacts(law, in, 20);
  EXPECT_NEAR(out.rendered_wrench.y(), -0.4 * 2000.0 * depth, 0.2)
      << "sliding: mu_d x the normal force";
  EXPECT_NEAR(out.rendered_wrench.x(), -2000.0 * depth, 0.2);
}

TEST(ServoLawSurface, EverySurfaceInForceIsRenderedAtOnce) {
  // A peg on the floor of its hole and against its wall: each pushes (J3: the deepest alone
  // dropped the floor when the wall became the deeper, and the handle fell 3.5 mm, 2026-12-07).
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_client();
  add_plane(in, Vector3d(-1.0, 0.0, 0.0), 0.0);
  add_plane(in, kSlanted, 0.0);
  run_on_contacts(law, in, 100);
  const double d = press_along_x(law, in, 0.004);
  const ServoOutputs out = run_on_contacts(law, in, 200);
  const double slanted = 2000.0 * d * std::cos(0.5236);
  EXPECT_NEAR(out.rendered_wrench.x(), -2000.0 * d + slanted * kSlanted.x(), 0.05);
  EXPECT_NEAR(out.rendered_wrench.z(), slanted * kSlanted.z(), 0.05);
  EXPECT_EQ(out.contacts, 2U);
}

TEST(ServoLawSurface, ASurfaceThatBecomesTheDeepestLeavesTheOneInForceRendered) {
  // The handle presses 10 N on a surface; a second appears with the handle deeper in it (found
  // inside: rendered from where the handle is). The first keeps pushing, with no step.
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_client();
  add_plane(in, Vector3d(-1.0, 0.0, 0.0), 0.0);
  run_on_contacts(law, in, 100);
  const double d = press_along_x(law, in, 0.005);
  ASSERT_NEAR(run_on_contacts(law, in, 200).rendered_wrench.x(), -2000.0 * d, 0.05);
  add_plane(in, kSlanted, 0.008);  // 8 mm deep: deeper than the first
  const ForceTrace trace = held_still(law, in, -2000.0 * d, 300);
  EXPECT_LT(trace.largest_step, 1.0) << "N per 1 ms cycle";
  EXPECT_NEAR(trace.least, -2000.0 * d, 0.05) << "the first surface still pushes";
  EXPECT_NEAR(trace.most, -2000.0 * d, 0.05);
}

TEST(ServoLawSurface, ContactsAlongOneNormalAreOnePlaneTheDeepest) {
  // A box on a table: four contacts, one plane; summed, the table would be four times as stiff.
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_client();
  add_plane(in, Vector3d(-1.0, 0.0, 0.0), 0.0);
  add_plane(in, Vector3d(-1.0, 0.0, 0.0), -0.001);  // 1 mm further on
  add_plane(in, Vector3d(-1.0, 0.001, 0.0), 0.0);   // its normal 0.06 degrees off
  run_on_contacts(law, in, 100);
  const double d = press_along_x(law, in, 0.005);
  EXPECT_NEAR(run_on_contacts(law, in, 200).rendered_wrench.x(), -2000.0 * d, 0.05);
}

TEST(ServoLawSurface, SurfacesTogetherAreNoStifferThanTheSampledDataBound) {
  // At a 10 ms period 2 B / T is 4000 N/m: each surface may have 2000 N/m, three pressed at
  // once share the 4000 (each rendered at two thirds).
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_client();
  in.dt = std::chrono::milliseconds(10);
  add_plane(in, Vector3d(-1.0, 0.0, 0.0), 0.0);
  add_plane(in, kSlanted, 0.0);
  const Vector3d other(-std::cos(0.5236), 0.0, std::sin(0.5236));
  add_plane(in, other, 0.0);
  run_on_contacts(law, in, 20);
  const double d = press_along_x(law, in, 0.003);
  const ServoOutputs out = run_on_contacts(law, in, 50);
  const double each = 2000.0 * 2.0 / 3.0;
  const double cos2 = std::cos(0.5236) * std::cos(0.5236);
  EXPECT_NEAR(out.rendered_wrench.x(), -each * d * (1.0 + 2.0 * cos2), 0.05);
}

}  // namespace
}  // namespace hapticctrl::rt_core
