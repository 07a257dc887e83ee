// Tests of servo_law_contact.cpp: the coupling stiffened along a contact the client reports, the
// spring re-anchored after a full disengagement, and the contact held through a blackout (J1).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "hapticctrl/rt_core/servo_law.hpp"
#include "support/law_inputs.hpp"
#include "support/law_runs.hpp"

using namespace std::chrono_literals;

namespace hapticctrl::rt_core {
namespace {

using test::chain_at;
using test::coupled_to_object_ahead;
using test::default_dynamics;
using test::ForceTrace;
using test::impedance_on_surface;
using test::kReady;
using test::press_along_x;
using test::run;
using test::run_on_contacts;
using test::wall_at;

/// Coupled to an object `dx` ahead of the handle along x, with the loop of a 20 ms link (the
/// derived stiffness is then about 70 N/m), a fresh sample every cycle.
ServoInputs slow_link_coupling(double dx) {
  ServoInputs in = coupled_to_object_ahead(dx);
  in.client.local_coupling = true;
  in.client.energy_in = 1e3;  // the two-port has budget: this test is about the stiffness
  in.loop_delay = 40ms;
  in.new_sample = true;
  return in;
}

TEST(ServoLawContact, TheHandFeelsTheContactAtItsStiffnessAndTheObjectAStifferCoupling) {
  // J2: behind a 20 ms link the coupling is soft (about 70 N/m); pressed 1 cm into a 1600 N/m
  // wall the object touches, the hand feels the wall itself, rendered here (16 N: through the
  // coupling stiffened to half the wall's stiffness it felt 8 N), and the object gets the
  // coupling stiffened along the contact to the wall's 1600 N/m, which its client closes
  // itself: it is pressed into its wall with the 16 N the hand feels.
  ServoLaw law(default_dynamics());
  ServoInputs in = slow_link_coupling(0.0);
  in.client.contact_count = 1;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, in.now);
  ServoOutputs out = run_on_contacts(law, in, 300);
  const double k_free = out.gains.k_linear;
  ASSERT_LT(k_free, 200.0) << "a 40 ms loop derives a soft spring";
  const double depth = press_along_x(law, in, 0.01);
  out = run_on_contacts(law, in, 300);
  EXPECT_EQ(out.contacts, 1U);
  EXPECT_NEAR(out.contact_normal.x(), -1.0, 1e-9);
  EXPECT_NEAR(out.normal_stiffness, 1600.0 - k_free, 1e-6) << "1600 N/m in all";
  EXPECT_NEAR(out.rendered_wrench(0), -1600.0 * depth, 0.02 * 16.0)
      << "the handle pressing 1 cm into the wall is pushed out with the wall's 1600 N/m";
  EXPECT_NEAR(out.object_wrench(0), 1600.0 * depth, 0.02 * 16.0)
      << "the object is pressed into its wall with what the hand feels";
  EXPECT_NEAR(out.surface_normal.x(), -1.0, 1e-9) << "telemetry: the surface rendered";
  EXPECT_NEAR(out.surface_depth, depth, 1e-9);
  EXPECT_NEAR(out.surface_force, 1600.0 * depth, 1e-6);
  EXPECT_EQ(out.surface_hidden, 0.0);
  ASSERT_TRUE(out.contact_age.has_value());
  EXPECT_GE(*out.contact_age, 0ns);
  EXPECT_LE(*out.contact_age, 1ms);
}

TEST(ServoLawContact, AContactOlderThanItsObjectsStateCountsTheObjectsTravelOntoTheSurface) {
  // The client reported its object 3 mm short of a wall (beyond the 1 mm touch band); its next
  // state carries the object 3 mm on, onto the wall, before its next contact frame: the gap is
  // the reported 3 mm less that travel, and the coupling is stiffened along the wall. (Until
  // 2026-12-07 the travel was added: the gap read 6 mm and the coupling stayed soft.)
  ServoLaw law(default_dynamics());
  ServoInputs in = slow_link_coupling(0.0);
  in.client.contact_count = 1;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, in.now);
  in.client.contacts[0].distance = 0.003;
  ServoOutputs out = run(law, in, 2);
  EXPECT_EQ(out.normal_stiffness, 0.0) << "3 mm short of the wall: no contact in force";
  in.client.object_pose[0] += 0.003;  // along +x, against the wall's normal: onto it
  out = run(law, in, 10);             // within the contact's 30 ms of freshness
  EXPECT_GT(out.normal_stiffness, 0.0) << "on the wall: the coupling stiffened along it";
  EXPECT_NEAR(out.contact_normal.x(), -1.0, 1e-9);
  in.client.object_pose[0] -= 0.006;  // 3 mm back from where it was reported: 6 mm short
  out = run(law, in, 2);
  EXPECT_EQ(out.normal_stiffness, 0.0) << "moving away from the wall is no contact";
}

TEST(ServoLawContact, TheWallsStiffnessIsFeltWhateverTheLoopAndBoundedByTheDevice) {
  // A 5000 N/m wall is rendered at the device's 2000 N/m, at any loop delay.
  for (const Duration loop : {Duration{2ms}, Duration{200ms}}) {
    ServoLaw law(default_dynamics());
    ServoInputs in = slow_link_coupling(0.0);
    in.loop_delay = loop;
    in.client.contact_count = 1;
    in.client.contacts[0] = wall_at(in.client.object_pose, 5000.0, in.now);
    run_on_contacts(law, in, 300);
    const double first = press_along_x(law, in, 0.0025);
    const double f5 = run_on_contacts(law, in, 300).rendered_wrench(0);
    const double second = press_along_x(law, in, 0.0025);
    const double f10 = run_on_contacts(law, in, 300).rendered_wrench(0);
    EXPECT_NEAR(-f5 / first, 2000.0, 20.0) << "loop " << to_ns(loop) << " ns";
    EXPECT_NEAR(-(f10 - f5) / second, 2000.0, 20.0) << "loop " << to_ns(loop) << " ns";
  }
}

TEST(ServoLawContact, TheStiffeningIsUnilateralAndAbsentBeforeTouching) {
  ServoLaw law(default_dynamics());
  ServoInputs in = slow_link_coupling(0.01);  // the handle pulls the object off the wall
  in.client.contact_count = 1;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, TimePoint{});
  ServoOutputs out;
  for (int k = 0; k < 300; ++k) {
    in.client.contacts[0].received = in.now;
    out = run(law, in, 1);
  }
  EXPECT_NEAR(out.rendered_wrench(0), out.gains.k_linear * 0.01, 0.02 * out.gains.k_linear * 0.01)
      << "pulling away: the free spring alone";

  ServoLaw near_law(default_dynamics());
  ServoInputs near = slow_link_coupling(-0.01);
  near.client.contact_count = 1;
  near.client.contacts[0] = wall_at(near.client.object_pose, 1600.0, TimePoint{});
  near.client.contacts[0].distance = 0.003;  // 3 mm short of the wall
  for (int k = 0; k < 300; ++k) {
    near.client.contacts[0].received = near.now;
    out = run(near_law, near, 1);
  }
  EXPECT_EQ(out.normal_stiffness, 0.0) << "not touching yet";
}

TEST(ServoLawContact, AContactThatStopsComingFadesOutWithinFortyFiveMs) {
  ServoLaw law(default_dynamics());
  ServoInputs in = slow_link_coupling(-0.01);
  in.client.contact_count = 1;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, TimePoint{});
  ServoOutputs out;
  for (int k = 0; k < 300; ++k) {
    in.client.contacts[0].received = in.now;
    out = run(law, in, 1);
  }
  ASSERT_GT(out.normal_stiffness, 0.0);
  out = run(law, in, 35);
  EXPECT_GT(out.normal_stiffness, 0.0) << "fresh for 30 ms, then fading";
  EXPECT_LT(out.normal_stiffness, 0.9 * (1600.0 - out.gains.k_linear));
  out = run(law, in, 11);
  EXPECT_EQ(out.normal_stiffness, 0.0);
  EXPECT_EQ(out.contacts, 0U);
}

TEST(ServoLawContact, AfterAFullDisengagementTheSpringRestartsWhereTheHandleIs) {
  // The object 30 cm away (a hand that went through a faded wall during a blackout): the
  // coupling comes back without a snap at either end, and regains the stretch at 8 cm/s at most.
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.3);
  in.new_sample = true;
  ServoOutputs out = run(law, in, 1);
  EXPECT_NEAR(out.rendered_wrench.head<3>().norm(), 0.0, 1e-9) << "relaxed at the handle";
  double last = 0.0;
  double largest_step = 0.0;
  for (int k = 0; k < 200; ++k) {
    out = run(law, in, 1);
    largest_step = std::max(largest_step, std::abs(out.rendered_wrench(0) - last));
    last = out.rendered_wrench(0);
  }
  EXPECT_LE(largest_step, 1.0) << "N per 1 ms cycle";
  const double k = out.gains.k_linear;
  EXPECT_NEAR(out.rendered_wrench(0), std::min(35.0, k * 0.08 * 0.2), 0.05 * 35.0)
      << "0.2 s at 8 cm/s: 1.6 cm of the stretch back";
  EXPECT_NEAR(out.object_wrench(0), -out.rendered_wrench(0), 0.05 * out.rendered_wrench(0))
      << "the object feels the same re-anchored spring (the whole stretch would be 35 N at once, "
         "energy the channel made)";
}

TEST(ServoLawContact, TheHiddenStretchShrinksWithTheTrueOneAndNeverPullsBack) {
  ServoLaw law(default_dynamics());
  ServoInputs in = coupled_to_object_ahead(0.1);
  run(law, in, 100);  // engaged; 10 cm hidden, 5 mm of it back
  // The object arrives at the handle (a free object its own spring pulled along).
  const ChainState s = chain_at(kReady);
  in.client.object_pose[0] = s.handle_position.x() + 0.001;
  const ServoOutputs out = run(law, in, 40);  // re-engaging, the force falls at 1 N per ms
  EXPECT_GE(out.rendered_wrench(0), 0.0) << "never pulls the handle away from the object";
  EXPECT_LE(out.rendered_wrench(0), out.gains.k_linear * 0.001 + 1e-9);
}

TEST(ServoLawContact, WhileTheStretchReturnsTheHandlesMotionAlongItIsDampedAndFreeAcrossIt) {
  // A handle that plunged through a faded wall meets the returning stretch moving: its motion
  // along the stretch is damped with the device's stable damping (it bounced off at 0.13-0.16
  // m/s, J1 2026-12-03), its motion across it is not. Compared with the same law, the same
  // motion and no hidden stretch (the object where the coupling holds it).
  const ChainState s = chain_at(kReady);
  const Matrix6d jacobian = default_dynamics().jacobian(s);
  const double max_damping = default_dynamics().model().limits.max_damping_linear;
  ASSERT_GT(max_damping, 0.0);
  const auto wrench_moving = [&](double object_dx, const Vector3d& velocity) -> Vector6d {
    ServoLaw law(default_dynamics());
    ServoInputs in = coupled_to_object_ahead(object_dx);
    in.new_sample = true;
    run(law, in, 100);  // engaged; the hold let go; with 10 cm hidden, 8 mm of it back
    Vector6d twist = Vector6d::Zero();
    twist.head<3>() = velocity;
    in.measures.velocity = jacobian.colPivHouseholderQr().solve(twist);
    // 10 cycles at the new velocity: the rate limit (1 N/ms while the stretch returns) settles.
    return run(law, in, 10).rendered_wrench;
  };
  // What moving adds to the force, with the hidden stretch (the object 10 cm ahead, +x) and
  // without it (the object at the handle): the coupling's own damper is the same in both.
  const double v = 0.01;
  const auto damping_added = [&](const Vector3d& velocity) -> Vector6d {
    return (wrench_moving(0.1, velocity) - wrench_moving(0.1, Vector3d::Zero())) -
           (wrench_moving(0.0, velocity) - wrench_moving(0.0, Vector3d::Zero()));
  };
  const Vector6d into = damping_added(Vector3d(-v, 0.0, 0.0));  // into the returning stretch
  EXPECT_NEAR(into.x(), max_damping * v, 0.05 * max_damping * v)
      << "the device's stable damping along the returning stretch";
  EXPECT_NEAR(into.tail<5>().norm(), 0.0, 0.05 * max_damping * v);
  const Vector6d sliding = damping_added(Vector3d(0.0, v, 0.0));  // along the wall
  EXPECT_NEAR(sliding.norm(), 0.0, 0.05 * max_damping * v)
      << "across the stretch nothing is added: the hand slides freely";
}

/// Runs `cycles` cycles of 1 ms with the link silent (no new sample: its silence and the last
/// sample's age grow) or, `fresh`, with a sample and its contacts refreshed every cycle.
ForceTrace run_link(ServoLaw& law, ServoInputs& in, int cycles, bool fresh) {
  ForceTrace trace;
  ServoOutputs out;
  for (int k = 0; k < cycles; ++k) {
    in.now += in.dt;
    in.new_sample = fresh;
    in.client_silence = fresh ? 0ns : in.client_silence + in.dt;
    in.client_age = fresh ? 0ns : in.client_age + in.dt;
    if (fresh) {
      in.client.contacts[0].received = in.now;
    }
    law.compute(in, false, out);
    trace.add(out.rendered_wrench.x(), k == 0);
  }
  return trace;
}

/// Coupled behind a 20 ms link to an object on a 1600 N/m wall (normal -x), the handle pressed
/// into it by about 1 cm; returns the force the wall renders then.
double pressed_on_wall(ServoLaw& law, ServoInputs& in) {
  in = slow_link_coupling(0.0);
  in.client.contact_count = 1;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, in.now);
  run_on_contacts(law, in, 300);
  return -1600.0 * press_along_x(law, in, 0.01);
}

TEST(ServoLawHeldContact, ThroughABlackoutTheHandPressesOnTheContactItFeltAndNothingSteps) {
  // The handle presses 1 cm into a 1600 N/m contact (16 N); the link falls silent for 2 s and
  // comes back. The coupling fades and re-anchors as before, and the contact as the hand felt
  // it takes over what fades: the hand meets the same wall all along (without it, it went 30 cm
  // through the faded wall in 2 s, J1).
  ServoLaw law(default_dynamics());
  ServoInputs in;
  const double felt = pressed_on_wall(law, in);
  ForceTrace trace = run_link(law, in, 300, true);
  ASSERT_NEAR(trace.last, felt, 0.2);
  trace = run_link(law, in, 2000, false);
  EXPECT_NEAR(trace.least, felt, 0.2) << "the push the hand felt, through the blackout";
  EXPECT_NEAR(trace.most, felt, 0.2);
  EXPECT_LE(trace.largest_step, 1.0 + 1e-9) << "N per 1 ms cycle";
  EXPECT_EQ(law.memory().engage, 0.0) << "the link's coupling is wholly faded";
  trace = run_link(law, in, 300, true);
  EXPECT_GT(-trace.most, -0.9 * felt) << "no dip as the coupling re-engages";
  EXPECT_LT(-trace.least, -1.05 * felt) << "no overshoot";
  EXPECT_LE(trace.largest_step, 1.0 + 1e-9);
  EXPECT_NEAR(trace.last, felt, 0.2);
  EXPECT_EQ(law.memory().engage, 1.0);
}

TEST(ServoLawHeldContact, AnObjectDeeperInItsSurfaceThanTheHandleDoesNotPullTheHandIn) {
  // While the surface pushes, the handle meets the surface alone along its normal: an object
  // that comes back to its wall deeper than the handle and still moving into it (kicked off
  // during a blackout, it returned at speed) does not drag the hand in through the coupling
  // (kept, it turned a felt 5 N into 2 N, then 7.4 N in steps of 1.3 N, 2026-12-05).
  ServoLaw law(default_dynamics());
  ServoInputs in;
  const double felt = pressed_on_wall(law, in);
  in.loop_delay = 4ms;  // a stiff coupling: what it would pull shows
  ForceTrace trace = run_link(law, in, 300, true);
  ASSERT_NEAR(trace.last, felt, 0.2);
  in.client.object_pose[0] += 0.02;  // 2 cm deeper than the handle, going in at 0.3 m/s
  in.client.object_twist[0] = 0.3;
  in.client.contacts[0] = wall_at(in.client.object_pose, 1600.0, in.now);
  in.client.contacts[0].distance = -0.02 - 0.01;  // the same plane, the object 3 cm in it
  trace = run_link(law, in, 100, true);
  EXPECT_NEAR(trace.least, felt, 0.2) << "the wall alone along its normal";
  EXPECT_NEAR(trace.most, felt, 0.2);
}

TEST(ServoLawHeldContact, IsUnilateralAndForgottenWhenTheClientWithdrawsItOnALiveLink) {
  ServoLaw law(default_dynamics());
  ServoInputs in;
  const double felt = pressed_on_wall(law, in);
  run_link(law, in, 300, true);
  // Silent, the hand pulls the handle 2 cm back out of the wall (-x), then pushes it back in.
  const Vector6d pressing = in.measures.position;
  const Matrix6d jacobian = default_dynamics().jacobian(chain_at(pressing));
  Vector6d back = Vector6d::Zero();
  back.x() = -0.02;
  in.measures.position += jacobian.colPivHouseholderQr().solve(back);
  run_link(law, in, 100, false);
  EXPECT_EQ(run_link(law, in, 1, false).last, 0.0) << "a held contact never pulls";
  in.measures.position = pressing;
  EXPECT_NEAR(run_link(law, in, 20, false).last, felt, 0.3) << "pushed back in: it is there";

  ServoLaw live(default_dynamics());
  ServoInputs withdrawn;
  pressed_on_wall(live, withdrawn);
  run_link(live, withdrawn, 300, true);
  withdrawn.client.contact_count = 0;  // the object left the wall in the client's world
  run_link(live, withdrawn, 100, true);
  const double stretch =
      chain_at(withdrawn.measures.position).handle_position.x() - withdrawn.client.object_pose[0];
  const double k_free = -run_link(live, withdrawn, 1, true).last / stretch;
  EXPECT_NEAR(k_free, live.memory().gains.k_linear, 1.0) << "the free coupling alone";
  EXPECT_NEAR(run_link(live, withdrawn, 100, false).last, 0.0, 1e-9)
      << "and nothing held when the link then falls silent";
}

TEST(ServoLawHeldContact, AnImpedanceSurfaceIsHeldThroughABlackout) {
  ServoLaw law(default_dynamics());
  ServoInputs in = impedance_on_surface(0.0, 0.0);
  run_on_contacts(law, in, 100);
  const double felt = -2000.0 * press_along_x(law, in, 0.005);
  ForceTrace trace = run_link(law, in, 200, true);
  ASSERT_NEAR(trace.last, felt, 0.05);
  trace = run_link(law, in, 2000, false);
  EXPECT_NEAR(trace.least, felt, 0.05) << "2000 N/m x 5 mm, through the blackout";
  EXPECT_NEAR(trace.most, felt, 0.05);
  trace = run_link(law, in, 300, true);
  EXPECT_NEAR(trace.least, felt, 0.05) << "and when the link returns";
  EXPECT_NEAR(trace.most, felt, 0.05);
}

}  // namespace
}  // namespace hapticctrl::rt_core
