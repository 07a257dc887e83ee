// Tests of channel_passivity.hpp: the client library's end of the two-port time-domain passivity of
// the coupling channel (docs/control.md; Ryu, Artigas, Preusche).
#include "channel_passivity.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace hapticctrl::client {
namespace {

constexpr double kDt = 1e-3;

/// Step times, 1 ms apart (the PC compares outputs by time).
TimePoint next_ms() {
  static TimePoint now{};
  return now += std::chrono::milliseconds(1);
}

TEST(ChannelPassivity, ForwardsTheWrenchWhileTheControllersEnergyCoversTheOutput) {
  ChannelPassivity pc;
  pc.set_object(0.5, 1e-4);
  pc.on_controller_energy(1.0);
  for (int k = 0; k < 100; ++k) {
    const Vector6 w = pc.render({1.0, 0, 0, 0, 0, 0});
    EXPECT_EQ(w[0], 1.0);
    pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt,
               next_ms());  // 0.1 W out of the channel into the object
  }
  EXPECT_NEAR(pc.energy_out(), 0.01, 1e-12);
  EXPECT_EQ(pc.active_steps(), 0U);
}

TEST(ChannelPassivity, DampsTheObjectWhenTheChannelWouldGiveMoreThanItGot) {
  ChannelPassivity pc;
  pc.set_object(0.5, 1e-4);
  (void)pc.render({1.0, 0, 0, 0, 0, 0});
  pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());  // 1e-4 J out, nothing reported in
  const Vector6 damped = pc.render({1.0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(damped[0], 0.0, 1e-9) << "a damper of 10 N.s/m at 0.1 m/s: the excess, no more";
  pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  EXPECT_NEAR(pc.energy_out(), 1e-4, 1e-12) << "no further energy given";
  EXPECT_GT(pc.active_steps(), 0U);
  pc.on_controller_energy(1e-3);  // the controller's report catches up
  pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  EXPECT_EQ(pc.render({1.0, 0, 0, 0, 0, 0})[0], 1.0) << "transparent again";
}

TEST(ChannelPassivity, TheDamperNeverPushesAgainstTheMotionItself) {
  ChannelPassivity pc;
  pc.set_object(0.5, 1e-4);
  (void)pc.render({1.0, 0, 0, 0, 0, 0});
  pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());  // 1 mJ out, nothing reported in
  const Vector6 w = pc.render({1.0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(w[0], 0.0, 1e-12) << "only the working share (1 N along the motion) is removed";
  const Vector6 against = pc.render({-1.0, 0, 0, 0, 0, 0});
  EXPECT_EQ(against[0], -1.0) << "a wrench that takes energy from the object is left alone";
}

TEST(ChannelPassivity, TheDamperStaysWithinWhatTheObjectsIntegrationBears) {
  ChannelPassivity pc;
  pc.set_object(0.2, 1e-5);
  (void)pc.render({500.0, 0, 0, 0, 0, 0});
  pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, 2 * kDt, next_ms());  // 0.5 J out, alpha 500 wanted
  const Vector6 damped = pc.render({500.0, 0, 0, 0, 0, 0});
  EXPECT_NEAR(damped[0], 500.0 - 0.5 * 0.2 / (2 * kDt) * 1.0, 1e-9)
      << "alpha <= m / (2 x the time the wrench is held)";
}

TEST(ChannelPassivity, HeldByAContactTheDamperIsWholeWithinTheIntegrationAndTheRestIsOwed) {
  // In contact (protocol 1.3) the damper may push against the motion and stop the object's step
  // outright (alpha <= m / dt), no more; nothing beyond it is cut (a cut turned the object's
  // next step and dithered it against the wall), and what it could not take stays owed.
  ChannelPassivity pc;
  pc.set_object(0.2, 1e-5);
  pc.set_contact_share(1.0);
  (void)pc.render({500.0, 0, 0, 0, 0, 0});
  pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());  // 0.5 J out: alpha 500 wanted
  EXPECT_NEAR(pc.render({500.0, 0, 0, 0, 0, 0})[0], 300.0, 1e-9)
      << "alpha <= m / dt = 200 N.s/m, and nothing more";
  EXPECT_NEAR(pc.render({-500.0, 0, 0, 0, 0, 0})[0], -500.0 - 200.0, 1e-9)
      << "against the motion: the same damper";
  pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());  // the damper took 0.2 J of 0.5
  EXPECT_NEAR(pc.render({500.0, 0, 0, 0, 0, 0})[0], 300.0, 1e-9)
      << "0.3 J still owed: the damper stays on the next step";
}

TEST(ChannelPassivity, HeldByAContactTheRotationsDamperStaysAtHalfTheIntegrationsBound) {
  // The application's own contact terms turn the object unseen (friction at the contact point,
  // a rolling patch): on the rotation the damper keeps the free bound, I / (2 dt).
  ChannelPassivity pc;
  pc.set_object(0.2, 1e-5);
  pc.set_contact_share(1.0);
  (void)pc.render({5000.0, 0, 0, 0, 0, 0.5});
  pc.on_step({1.0, 0, 0, 0, 0, 1.0}, kDt, kDt, next_ms());  // 5 J out: alpha 2500 wanted
  const Vector6 w = pc.render({5000.0, 0, 0, 0, 0, 0.5});
  EXPECT_NEAR(w[0], 5000.0 - 0.2 / kDt * 1.0, 1e-9) << "along the motion: m / dt";
  EXPECT_NEAR(w[5], 0.5 - 0.5 * 1e-5 / kDt * 1.0, 1e-9) << "on the rotation: I / (2 dt)";
}

TEST(ChannelPassivity, TheObjectsOutputIsComparedALoopLate) {
  // The controller's report covers the object's motion up to a loop ago: with a 5 ms loop, the
  // output of the last 5 ms is not yet excess.
  ChannelPassivity pc;
  pc.set_object(0.5, 1e-4);
  pc.set_loop(5e-3);
  for (int k = 0; k < 4; ++k) {
    (void)pc.render({1.0, 0, 0, 0, 0, 0});
    pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  }
  EXPECT_EQ(pc.active_steps(), 0U) << "4 ms of output: within the loop";
  for (int k = 0; k < 4; ++k) {
    (void)pc.render({1.0, 0, 0, 0, 0, 0});
    pc.on_step({0.1, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  }
  EXPECT_GT(pc.active_steps(), 0U) << "the output of a loop ago was never paid";
}

TEST(ChannelPassivity, TheHandleImageGivesWayAlongTheApplicationsWrench) {
  // IMPEDANCE: a wall in the application pushes back (-x) while the image moves into it (+x)
  // and the controller reports nothing in: the image drifts along the wall's push (-x) at the
  // rate that dissipates the excess, and comes back within the budget later.
  ChannelPassivity pc;
  const Vector6 wall{-10.0, 0, 0, 0, 0, 0};
  pc.on_image_step(wall, {0.1, 0, 0, 0, 0, 0}, kDt);  // 1 mJ out of the channel
  EXPECT_NEAR(pc.drift_rate()[0], -0.1, 1e-9) << "1 mJ / (10 N x 1 ms)";
  EXPECT_NEAR(pc.drift()[0], -1e-4, 1e-12);
  EXPECT_NEAR(pc.energy_out(), 0.0, 1e-12) << "the drift dissipated it";
  pc.on_controller_energy(1.0);  // budget: the drift is given back at 2 cm/s
  pc.on_image_step(wall, {0, 0, 0, 0, 0, 0}, kDt);
  EXPECT_GT(pc.drift_rate()[0], 0.0);
  for (int k = 0; k < 20; ++k) {
    pc.on_image_step(wall, {0, 0, 0, 0, 0, 0}, kDt);
  }
  EXPECT_NEAR(pc.drift()[0], 0.0, 1e-12);
}

TEST(ChannelPassivity, AnImpedanceWrenchThatDoesWorkIsTheClientsEnergyIn) {
  ChannelPassivity pc;
  pc.on_image_step({2.0, 0, 0, 0, 0, 0}, {0.5, 0, 0, 0, 0, 0}, kDt);
  EXPECT_NEAR(pc.energy_in(), 1e-3, 1e-15);
  EXPECT_EQ(pc.active_steps(), 0U);
}

TEST(ChannelPassivity, EnergyInGoesOnTheWireInMicrojoulesModulo2To32) {
  ChannelPassivity pc;
  (void)pc.render({-2.0, 0, 0, 0, 0, 0});
  pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());  // the object pushes the channel: 2 mJ in
  EXPECT_NEAR(pc.energy_in(), 2e-3, 1e-15);
  EXPECT_EQ(pc.energy_in_uj(), 2000U);
  for (int k = 0; k < 2500; ++k) {  // 5000 J: past 2^32 uJ = 4295 J
    (void)pc.render({-2000.0, 0, 0, 0, 0, 0});
    pc.on_step({1.0, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  }
  const double uj = std::fmod(std::floor(pc.energy_in() * 1e6), 4294967296.0);
  EXPECT_EQ(pc.energy_in_uj(), static_cast<std::uint32_t>(uj));
}

TEST(ChannelPassivity, IgnoresNonFiniteSteps) {
  ChannelPassivity pc;
  (void)pc.render({1.0, 0, 0, 0, 0, 0});
  pc.on_step({NAN, 0, 0, 0, 0, 0}, kDt, kDt, next_ms());
  pc.on_step({0.1, 0, 0, 0, 0, 0}, -1.0, -1.0, next_ms());
  EXPECT_EQ(pc.energy_out(), 0.0);
  EXPECT_EQ(pc.energy_in(), 0.0);
}

}  // namespace
}  // namespace hapticctrl::client
